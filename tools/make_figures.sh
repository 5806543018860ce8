#!/usr/bin/env bash
# Regenerates every figure of the book from the chapter programs (build first: bash tools/build.sh).
# Each figure's caption in the book repeats the command that made it.
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(pwd)/build/bin"
fig="$(pwd)/book/figures"
mkdir -p "$fig"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# --- 1.0-1.2
# --- 1.3-1.4
# --- 1.5
# --- 1.6
# --- 1.7-1.9
# --- 5.1, 5.3
