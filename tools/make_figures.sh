#!/usr/bin/env bash
# Regenerates every figure of the book from the chapter programs (build first: bash tools/build.sh).
# Each figure's caption in the book repeats the command that made it.
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(pwd)/build/bin"
fig="$(pwd)/book/figures"
mkdir -p "$fig"
# One command draws any error-against-time CSV (convergence.hpp's csv) to PNG.
plot() { python3 "${bin%/build/bin}/tools/plot_convergence.py" "$@"; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# --- 1.0-1.2
"$bin/sphere" --width 320 --height 240 --out sphere.png >/dev/null && cp sphere.png "$fig/1.2-sphere.png"
# --- 1.3-1.4
"$bin/bezier" --samples 200000 --out 1.3-bezier.png --obj patch.obj >/dev/null && cp 1.3-bezier.png "$fig/"
"$bin/normals" --out 1.4-normals.png >/dev/null && cp 1.4-normals.png "$fig/"
# --- 1.5
"$bin/intersections" --width 400 --height 300 --rays 20000 --out 1.5-intersections.png && cp 1.5-intersections.png "$fig/"
"$bin/intersections" --mask --width 400 --height 300 --rays 20000 --out 1.5-mask.png && cp 1.5-mask.png "$fig/"
# --- 1.6
# Convergence plots: the chapter writes CSVs, tools/plot_convergence.py draws them (Debian's
# python3-matplotlib, which tools/setup.sh installs).
"$bin/monte-carlo" --max-log2n 22 --csv-dir . > /dev/null
plot 1.6-pi.csv -o "$fig/1.6-pi.png" --labels "dart throwing" \
  --title 'Estimating $\pi$ by dart throwing'
plot 1.6-x2-uniform.csv 1.6-x2-linear.csv -o "$fig/1.6-x2.png" \
  --labels 'uniform,$p(x)=x/2$' --title '$\int_0^2 x^2\,dx$: uniform and importance sampling'
plot 1.6-sinx2-uniform.csv 1.6-sinx2-importance.csv -o "$fig/1.6-sinx2.png" \
  --labels 'uniform,$p(x)=3x^2$' --title '$\int_0^1 \sin(x^2)\,dx$: uniform and importance sampling'
# --- 3.1-3.3
"$bin/rasterization" --width 320 --height 240 --out 3.1.png >/dev/null && cp 3.1-raster.png "$fig/"
"$bin/rasterization" --width 64 --height 48 --triangles 0 --out 3.1-square.png >/dev/null && cp 3.1-square-diff.png "$fig/"
xvfb=(xvfb-run -a -s "-screen 0 1280x720x24 -noreset")
"${xvfb[@]}" "$bin/opengl" --frames 3 --screenshot 3.2-triangle.png >/dev/null && cp 3.2-triangle.png "$fig/"
"${xvfb[@]}" "$bin/opengl" --frames 3 --thesis-stride --screenshot 3.2-thesis-stride.png >/dev/null && cp 3.2-thesis-stride.png "$fig/"
"${xvfb[@]}" "$bin/tessellation" --frames 3 --level 8 --screenshot 3.2-teapot.png >/dev/null && cp 3.2-teapot.png "$fig/"
"${xvfb[@]}" "$bin/tessellation" --frames 3 --level 4 --wireframe --screenshot 3.2-teapot-wire.png >/dev/null && cp 3.2-teapot-wire.png "$fig/"
# --- 1.7-1.9
"$bin/reflection" --width 320 --height 160 --spp 128 --out 1.7-reflection.png >/dev/null && cp 1.7-reflection.png "$fig/"
"$bin/refraction" --width 320 --height 200 --spp 128 --out 1.8-refraction.png >/dev/null && cp 1.8-refraction.png "$fig/"
"$bin/bxdf" --out 1.9-bxdf.png >/dev/null && cp 1.9-bxdf.png "$fig/"
# --- 5.1, 5.3
"$bin/antialiasing" --out 5.1-antialiasing.png >/dev/null && cp 5.1-antialiasing.png "$fig/"
"$bin/importance" --out 5.3-importance.png >/dev/null && cp 5.3-importance.png "$fig/"
"$bin/pathtrace" --scene "$fig/../../scenes/sky.yaml" --spp 256 --out 5.3-sky.png >/dev/null && cp 5.3-sky.png "$fig/"
"$bin/pathtrace" --scene "$fig/../../scenes/textures.yaml" --spp 256 --out 2.2-textures.png >/dev/null && cp 2.2-textures.png "$fig/"
"$bin/pathtrace" --scene "$fig/../../scenes/gltf-model.yaml" --out 4.1-gltf.png >/dev/null && cp 4.1-gltf.png "$fig/"
"$bin/pathtrace" --scene "$fig/../../scenes/teapot-sky.yaml" --spp 256 --out 5.4-teapot-sky.png >/dev/null && cp 5.4-teapot-sky.png "$fig/"
plot 5.1-antialiasing-{regular,uniform,stratified,sampler-sobol}.csv -o "$fig/5.1-rmse.png" \
  --labels "regular,uniform,stratified,sobol" --title "Anti-aliasing: RMSE of the pixel integral"
# 5.1's samplers on the Cornell box: a long sobol reference (a seed of its own), then each
# sampler to 1024 spp, the error after every doubling; stratified is only stratified when all
# its samples are in, so it gets a render of its own per spp (about 10 minutes on two cores).
"$bin/pathtrace" --scene cornell --width 64 --height 64 --spp 16384 --sampler sobol --seed 1001 \
  --pfm 5.1-ref.pfm --out 5.1-ref.png >/dev/null
for s in independent halton sobol; do
  "$bin/pathtrace" --scene cornell --width 64 --height 64 --spp 1024 --sampler $s --reference 5.1-ref.pfm \
    --report 5.1-$s.csv --out 5.1-$s.png >/dev/null
done
echo "spp,seconds,rmse,relmse" > 5.1-stratified-each.csv
for n in 1 2 4 8 16 32 64 128 256 512 1024; do
  "$bin/pathtrace" --scene cornell --width 64 --height 64 --spp $n --sampler stratified --reference 5.1-ref.pfm \
    --report 5.1-s.csv --out 5.1-s.png >/dev/null && tail -n 1 5.1-s.csv >> 5.1-stratified-each.csv
done
plot 5.1-independent.csv 5.1-stratified-each.csv 5.1-halton.csv 5.1-sobol.csv -o "$fig/5.1-samplers.png" \
  --labels "independent,stratified (a render per spp),halton,sobol" \
  --title "Cornell box, 64x64, mis: RMSE by sampler" --width 640
plot 5.3-importance-{uniform,cosine,light,mixture}.csv -o "$fig/5.3-error.png" \
  --labels "uniform,cosine,light,mixture" --title "Direct light: RMSE by sampling strategy"
# --- 6.2 (about 10 minutes on two cores: three 2048-spp mis references)
for s in caustic-box tiny-light; do
  "$bin/bdpt" --scene $s --width 64 --height 64 --spp 32 --ref-spp 2048 --threads 2 --strategies 4 --out 6.2-$s.png >/dev/null
done
"$bin/bdpt" --scene ajar-door --width 64 --height 48 --spp 32 --ref-spp 2048 --threads 2 --strategies 4 --out 6.2-ajar-door.png >/dev/null
cp 6.2-caustic-box.png 6.2-caustic-box-strategies.png 6.2-ajar-door.png 6.2-ajar-door-strategies.png 6.2-tiny-light.png "$fig/"
# --- 5.4
"$bin/microfacets" --width 480 --height 154 --spp 32 --ref-spp 64 --albedo-samples 0 --out 5.4-balls.png >/dev/null \
  && cp 5.4-balls-reference.png "$fig/5.4-material-balls.png"
# --- 6.3
"$bin/photons" --width 96 --height 96 --spp 64 --photons 10000 --ref-spp 64 --caustic-ref-spp 512 \
  --out 6.3-photons.png >/dev/null && cp 6.3-photons.png "$fig/"
# --- 6.4
"$bin/metropolis" --width 160 --height 120 --spp 64 --ref-spp 1024 --out 6.4-metropolis.png >/dev/null \
  && cp 6.4-metropolis.png "$fig/"
# --- 6.1 (the long delta-tracking references are the figures)
"$bin/media" --width 128 --height 128 --spp 1 --ref-spp 384 --steps 0.5 --out 6.1-fog.png >/dev/null && cp 6.1-fog-reference.png "$fig/6.1-fog.png"
"$bin/media" --scene milk-glass --width 128 --height 128 --spp 1 --ref-spp 192 --steps 0.5 --out 6.1-milk.png >/dev/null && cp 6.1-milk-reference.png "$fig/6.1-milk.png"
# --- 5.2
"$bin/bvh" --divs 32 --out 5.2-bvh-heat.png >/dev/null && cp 5.2-bvh-heat.png "$fig/"
# --- assignments (book/assignments): the target images, made by the reference solutions
"$bin/assignment-01-cylinder-render" --out "${bin%/build/bin}/book/assignments/01-cylinder/target.png" >/dev/null
"$bin/assignment-02-ggx-render" --out "${bin%/build/bin}/book/assignments/02-ggx/target.png" >/dev/null
"$bin/assignment-03-material-render" --out "${bin%/build/bin}/book/assignments/03-material/target.png" >/dev/null
"$bin/assignment-04-shape-render" --out "${bin%/build/bin}/book/assignments/04-shape/target.png" >/dev/null
# --- 2.1, 2.2, 4.1
"$bin/shaders" --out 2.1-shaders.png >/dev/null && cp 2.1-shaders.png "$fig/"
"$bin/shaders" --shader normal --out 2.1-normal.png >/dev/null && cp 2.1-normal.png "$fig/"
"$bin/whitted" --out 2.2-default.png >/dev/null && cp 2.2-default.png "$fig/"
"$bin/whitted" --scene box --spp 16 --out 2.2-box.png >/dev/null && cp 2.2-box.png "$fig/"
for g in reflect both refract; do
  "$bin/whitted" --scene glass-$g --width 240 --height 180 --spp 16 --out 2.2-glass-$g.png >/dev/null
  cp 2.2-glass-$g.png "$fig/"
done
"$bin/whitted" --scene teapot --spp 16 --out 2.2-teapot.png >/dev/null && cp 2.2-teapot.png "$fig/"
"$bin/whitted" --scene box --spp 16 --depth 1 --out 2.2-box-depth1.png >/dev/null && cp 2.2-box-depth1.png "$fig/"
# --- realtime (4.3)
"$bin/realtime" --headless --width 320 --height 240 --frames 64 --out 4.3-spheres.png >/dev/null && cp 4.3-spheres.png "$fig/"
"$bin/realtime" --headless --scene cornell-glass --width 240 --height 240 --frames 64 --out 4.3-cornell.png >/dev/null && cp 4.3-cornell.png "$fig/"
"$bin/realtime" --headless --width 200 --height 200 --frames 1 --weak-seed --out 4.3-weak-seed.png >/dev/null && cp 4.3-weak-seed.png "$fig/"
"$bin/realtime" --headless --width 200 --height 200 --frames 1 --out 4.3-hashed-seed.png >/dev/null && cp 4.3-hashed-seed.png "$fig/"
"$bin/realtime" --headless --scene "$fig/../../scenes/triangle-light.yaml" --out 4.3-triangle-light.png >/dev/null && cp 4.3-triangle-light.png "$fig/"
"$bin/pathtrace" --scene "$fig/../../scenes/triangle-light.yaml" --integrator mis --out 4.3-triangle-light-cpu >/dev/null && cp 4.3-triangle-light-cpu.png "$fig/"
"$bin/realtime" --headless --scene "$fig/../../scenes/textures.yaml" --out 4.3-textures.png >/dev/null && cp 4.3-textures.png "$fig/"
"$bin/realtime" --headless --scene "$fig/../../scenes/sky.yaml" --out 4.3-sky.png >/dev/null && cp 4.3-sky.png "$fig/"
xvfb=(xvfb-run -a -s "-screen 0 1280x720x24 -noreset")
"${xvfb[@]}" "$bin/realtime" --frames 16 --width 320 --height 240 --scene cornell-spheres --screenshot 4.3-viewer.png >/dev/null && cp 4.3-viewer.png "$fig/"
# --- 2.3, 4.2 (path tracing; several minutes on two cores)
"$bin/pathtrace" --scene cornell-glass --width 160 --height 160 --spp 256 --out 2.3-pathtrace.png >/dev/null && cp 2.3-pathtrace.png "$fig/"
"$bin/pathtrace" --scene cornell-glass --width 64 --height 64 --centre --spp 2048 --seed 1001 --pfm ref.pfm --out ref.png >/dev/null
for m in naive nee mis; do
  "$bin/pathtrace" --scene cornell-glass --width 64 --height 64 --centre --spp 1024 --integrator $m \
    --reference ref.pfm --report 2.3-$m.csv --out 2.3-$m.png >/dev/null
done
# The live preview (--window) under a virtual display: the window after the last pass.
"${xvfb[@]}" "$bin/pathtrace" --scene cornell-glass --width 64 --height 64 --centre --spp 256 --reference ref.pfm \
  --window --window-screenshot 2.3-window.png --out 2.3-window-image.png >/dev/null && cp 2.3-window.png "$fig/"
"$bin/results" --tile 80 --spp-sweep 1,8,64,512 --depth-spp 256 --conv-spp 512 --ref-spp 2048 >/dev/null
cp 4.2-samples.png 4.2-depth.png "$fig/"
plot 2.3-{naive,nee,mis}.csv -o "$fig/2.3-error.png" --labels "naive,nee,mis" \
  --title "Cornell box with a glass ball: RMSE against a 2048-spp reference"
plot 4.2-{naive,nee,mis}.csv -o "$fig/4.2-error.png" --labels "naive,nee,mis" \
  --title "Figure 4.3's scene: RMSE against spp and seconds"
