// Tests for image.hpp: sizes, pixel layout, non-finite pixel count.
#include <zraka/image/image.hpp>

#include <doctest/doctest.h>

#include <limits>

using namespace zraka;

TEST_CASE("image: absurd sizes are rejected with a clear message") {
  CHECK_THROWS_WITH_AS(image(0, 10), "image size 0x10 is out of range (each side 1..16384)", error);
  CHECK_THROWS_WITH_AS(image(10, -3), doctest::Contains("10x-3 is out of range"), error);
  CHECK_THROWS_WITH_AS(image(16385, 1), doctest::Contains("16385x1"), error);
  // Each side allowed, but 16384 x 16384 = 268 M pixels is more than max_pixels (134 M).
  CHECK_THROWS_AS(image::check_size(16384, 16384), error);
  CHECK_THROWS_AS(image::check_size(1LL << 40, 1LL << 40), error);  // no overflow
  CHECK_NOTHROW(image(1, 1));
  // Within the hard maximum, the raisable limit (limits.hpp: 4096 x 4096 by default) decides.
  CHECK_NOTHROW(image::check_size(4096, 4096));
  CHECK_THROWS_WITH_AS(image::check_size(4097, 4096),
                       "the image size 4097x4096 in pixels is 16781312, more than the limit of 16777216 "
                       "(raise with --limit pixels=N)", error);
  const input_limits saved = limits();
  set_limit(limits(), "pixels=134217728");
  CHECK_NOTHROW(image::check_size(16384, 8192));
  limits() = saved;
}

TEST_CASE("image: (0,0) is the top-left pixel, rows are stored top to bottom") {
  image img(3, 2, rgb(0.25f));
  CHECK(img.pixels.size() == 6);
  CHECK(img.at(2, 1) == rgb(0.25f));
  img.at(1, 0) = rgb(1, 0, 0);
  img.at(0, 1) = rgb(0, 1, 0);
  CHECK(img.pixels[1] == rgb(1, 0, 0));
  CHECK(img.pixels[3] == rgb(0, 1, 0));
}

TEST_CASE("image: NaN and inf pixels are counted") {
  image img(4, 4);
  CHECK(img.count_nonfinite() == 0);
  img.at(0, 0).g = std::numeric_limits<float>::quiet_NaN();
  img.at(3, 3).b = -std::numeric_limits<float>::infinity();
  img.at(2, 1) = rgb(std::numeric_limits<float>::max());  // huge but finite
  CHECK(img.count_nonfinite() == 2);
}
