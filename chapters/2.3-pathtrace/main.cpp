// Chapter 2.3 — path tracing. Renders a scene physically with one of three integrators of the
// rendering equation (path.hpp): `naive` (the thesis's algorithm: bounce until a light is
// hit by chance), `nee` (next-event estimation: ask a light at every diffuse hit) and `mis`
// (light and BSDF sampling combined by multiple importance sampling). The image is refined in
// passes that double the samples per pixel; with --reference it prints, after every pass, the
// error against that image and the time so far (error against run time), and --report writes the
// same table as CSV for tools/plot_convergence.py. --time-budget stops the doubling early.
// --window shows the image as the passes finish (preview_window.hpp). --sampler picks where each
// sample's numbers come from (samplers.hpp, book 5.1): independent (the default), stratified,
// halton or sobol.
//
// Scenes (--scene): a name from named_scenes.hpp, among them the Cornell boxes (cornell,
// cornell-glass, cornell-spheres; scenes/cornell*.yaml hold the same) and `furnace`, a camera
// inside a glowing Lambertian sphere whose radiance has a closed form, checked here; or a
// scene file (scenes/README.md).
//
// The program is one function of the library, zraka::pathtrace_main (app/pathtrace_main.hpp:
// read it there, top to bottom), so that a course's own program gets this whole command line
// by calling it with the registry of its own shapes and materials (book 2.3, "Extending zraka").
// Here without one: the built-in kinds only.
#include <zraka/app/pathtrace_main.hpp>

int main(int argc, char** argv) { return zraka::pathtrace_main(argc, argv); }
