// The compiled part from an installed zraka (zraka::compiled): the options struct and image
// writing come from the library, the resource root from this program (the install prefix).
#include <zraka/app/program_options.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/image/image_io.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  zraka::program_options opt{"consumer of zraka::compiled", zraka::take::size | zraka::take::out};
  opt.width = 4, opt.height = 3, opt.out = "consumer.png";
  if (const auto done = opt.parse(argc, argv)) return *done;
  zraka::write_image(zraka::image(opt.width, opt.height, zraka::rgb(0.5f)), opt.out);
  std::printf("wrote %s; resource root %s\n", opt.out.c_str(), zraka::resource_root().string().c_str());
  return 0;
}
