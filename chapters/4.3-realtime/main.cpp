// Chapter 4.3 — the real-time path tracer. The thesis's third program: path tracing in OpenCL,
// shown by OpenGL. The scene is packed into flat arrays (gpu_scene.hpp), the kernel
// (kernels/pathtrace.cl) is compiled for the features the scene uses, and every frame adds
// samples to a per-pixel sum on the device (progressive accumulation). The running mean comes
// back to the host and goes into a texture drawn over the whole window (PoCL, the CPU OpenCL
// this course runs on, cannot share buffers with OpenGL). Moving the camera starts the sum again.
//
// --headless renders with the same kernel and writes --out, without a window. A scene file's
// settings (width, height, spp, max_depth, seed) are used unless given on the command line.
// --integrator naive|nee|mis picks path.hpp's method, compiled into the kernel. What the kernel
// cannot render (a user shape, a custom BSDF, participating media) is an error before the
// first frame.
// The program prints the device, the kernel options, size, spp, depth and time together
// (errata C12), and in window mode the viewer's frame rate next to the kernel's alone.
//
// The program is one function of the library, zraka::realtime_main (app/realtime_main.hpp: read
// it there, top to bottom: the orbit camera, the setup, the headless loop, the viewer), so that a
// course's own program can offer it with its own shapes and materials in the scene files, which
// it then refuses by name (book 2.3, "Extending zraka"). Here without them: the built-in kinds.
#include <zraka/app/realtime_main.hpp>

int main(int argc, char** argv) { return zraka::realtime_main(argc, argv); }
