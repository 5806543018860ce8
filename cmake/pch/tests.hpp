// The precompiled header of the unit tests and the assignments' tests (cmake/ZrakaPch.cmake).
// doctest's main() is not built with it: doctest_main.cpp defines
// DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN before its include, which a precompiled doctest would ignore.
#pragma once
#include "common.hpp"

#include <doctest/doctest.h>
