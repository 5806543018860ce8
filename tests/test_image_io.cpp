// Tests for image_io.hpp: PNG/PPM as sRGB bytes, PFM as exact floats, NaN handling, atomic
// writes and clear errors. PNGs are decoded again with stb_image to check what was written.
#include <zraka/image/image_io.hpp>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <unistd.h>

using namespace zraka;
namespace fs = std::filesystem;

namespace {
struct temp_dir {
  fs::path path = fs::temp_directory_path() / ("zraka-test-io-" + std::to_string(::getpid()));
  temp_dir() { fs::create_directories(path); }
  ~temp_dir() { fs::remove_all(path); }
  std::size_t entries() const {
    return std::size_t(std::distance(fs::directory_iterator(path), fs::directory_iterator()));
  }
};
struct capture_cerr {
  std::ostringstream text;
  std::streambuf* old = std::cerr.rdbuf(text.rdbuf());
  ~capture_cerr() { std::cerr.rdbuf(old); }
};
std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
const float nan_f = std::numeric_limits<float>::quiet_NaN();
}  // namespace

TEST_CASE("image_io: the sRGB transfer function at known points") {
  CHECK(to_byte(0.0f) == 0);
  CHECK(to_byte(1.0f) == 255);
  CHECK(to_byte(7.5f) == 255);   // clamped
  CHECK(to_byte(-1.0f) == 0);    // clamped
  CHECK(to_byte(std::numeric_limits<float>::quiet_NaN()) == 0);  // never undefined behaviour
  CHECK(to_byte(0.5f) == 188);   // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
  CHECK(to_byte(0.0031308f) == 10);  // the linear segment's end: 12.92 * 0.0031308 = 0.04045
  CHECK(to_byte(0.2159f) == 128);    // mid grey in sRGB is only 21.6 % linear light
  // Round trip through 8 bits: every byte decodes and re-encodes to itself.
  for (int b = 0; b < 256; ++b) CHECK(to_byte(srgb_to_linear(b / 255.0f)) == b);
}

TEST_CASE("image_io: to_byte is the count of srgb_byte_steps at or below a value (the kernel's display)") {
  const std::array<float, 256> steps = srgb_byte_steps();
  auto steps_at_or_below = [&](float x) {  // NaN compares false: 0 steps, like to_byte(NaN)
    return int(std::count_if(steps.begin() + 1, steps.end(), [&](float s) { return x >= s; }));
  };
  for (int b = 1; b < 256; ++b) {  // each step is where to_byte moves from b - 1 to b
    CAPTURE(b);
    CHECK(to_byte(steps[std::size_t(b)]) == b);
    CHECK(to_byte(std::nextafter(steps[std::size_t(b)], 0.0f)) == b - 1);
    if (b > 1) CHECK(steps[std::size_t(b)] > steps[std::size_t(b) - 1]);
    // Around every step, float by float.
    float x = steps[std::size_t(b)];
    for (int k = 0; k < 64; ++k) x = std::nextafter(x, 0.0f);
    for (int k = 0; k < 128; ++k, x = std::nextafter(x, 2.0f)) REQUIRE(steps_at_or_below(x) == int(to_byte(x)));
  }
  // One float in 4096 of [0, 1], and the extremes.
  for (std::uint32_t bits = 0; bits <= std::bit_cast<std::uint32_t>(1.0f); bits += 4096) {
    const float x = std::bit_cast<float>(bits);
    REQUIRE(steps_at_or_below(x) == int(to_byte(x)));
  }
  const float inf = std::numeric_limits<float>::infinity();
  for (const float x : {nan_f, -nan_f, -inf, -1.0f, -0.0f, 0.0f, 0x1p-149f, std::numeric_limits<float>::min(), 1.0f,
                        std::nextafter(1.0f, 2.0f), 7.5f, std::numeric_limits<float>::max(), inf}) {
    CAPTURE(x);
    CHECK(steps_at_or_below(x) == int(to_byte(x)));
  }
}

TEST_CASE("image_io: PPM P3 text is exact for a tiny image") {
  temp_dir dir;
  image img(2, 2);
  img.at(0, 0) = rgb(1, 0, 0);
  img.at(1, 0) = rgb(0, 1, 0.5f);
  img.at(0, 1) = rgb(0, 0, 1);
  img.at(1, 1) = rgb(0.2159f);
  CHECK(write_ppm(img, dir.path / "t.ppm") == 0);
  CHECK(read(dir.path / "t.ppm") == "P3\n2 2\n255\n255 0 0\n0 255 188\n0 0 255\n128 128 128\n");
}

TEST_CASE("image_io: PNG is a valid PNG holding the sRGB-encoded pixels") {
  temp_dir dir;
  image img(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) img.at(x, y) = rgb(x / 4.0f, y / 2.0f, 0.5f);
  CHECK(write_png(img, dir.path / "t.png") == 0);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data(
      stbi_load((dir.path / "t.png").c_str(), &w, &h, &channels, 3), stbi_image_free);
  REQUIRE(data != nullptr);
  CHECK(w == 5);
  CHECK(h == 3);
  CHECK(channels == 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c)
        CHECK(int(data.get()[3 * (y * 5 + x) + c]) == int(to_byte(img.at(x, y)[c])));
  CHECK(int(data.get()[2]) == 188);  // linear 0.5 is written as sRGB 188, not 128
}

TEST_CASE("image_io: NaN pixels are counted, written magenta and reported") {
  temp_dir dir;
  image img(3, 1, rgb(0.5f));
  img.at(1, 0) = rgb(0, nan_f, 0);
  capture_cerr cap;
  CHECK(write_png(img, dir.path / "n.png") == 1);
  CHECK(write_ppm(img, dir.path / "n.ppm") == 1);
  CHECK(cap.text.str().find("warning: 1 NaN/inf pixel(s) written as magenta") != std::string::npos);
  CHECK(read(dir.path / "n.ppm") == "P3\n3 1\n255\n188 188 188\n255 0 255\n188 188 188\n");
  int w = 0, h = 0, n = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data(
      stbi_load((dir.path / "n.png").c_str(), &w, &h, &n, 3), stbi_image_free);
  REQUIRE(data != nullptr);
  CHECK(int(data.get()[3]) == 255);
  CHECK(int(data.get()[4]) == 0);
  CHECK(int(data.get()[5]) == 255);
}

TEST_CASE("image_io: PFM round trip is bit-exact; PFM refuses NaN") {
  temp_dir dir;
  image img(3, 2);
  const float specials[] = {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(), 1e-30f, 0.1f, 12345.678f,
                            -2.5f, std::nextafter(1.0f, 2.0f)};
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) img.pixels[i][c] = specials[(3 * i + c) % 9] * (c == 2 ? -1 : 1);
  write_pfm(img, dir.path / "t.pfm");
  const image back = read_pfm(dir.path / "t.pfm");
  REQUIRE(back.width == 3);
  REQUIRE(back.height == 2);
  CHECK(std::memcmp(back.pixels.data(), img.pixels.data(), img.pixels.size() * sizeof(rgb)) == 0);
  // Rows bottom to top in the file: the last row of floats is the image's top row.
  const std::string bytes = read(dir.path / "t.pfm");
  CHECK(bytes.rfind("PF\n3 2\n-1.0\n", 0) == 0);
  CHECK(std::memcmp(bytes.data() + bytes.size() - 3 * sizeof(rgb), &img.at(0, 0), 3 * sizeof(rgb)) == 0);

  img.at(2, 1).r = nan_f;
  CHECK_THROWS_WITH_AS(write_pfm(img, dir.path / "nan.pfm"), doctest::Contains("1 NaN/inf pixel(s)"),
                       error);
  CHECK_FALSE(fs::exists(dir.path / "nan.pfm"));
}

TEST_CASE("image_io: EXR round trip is bit-exact in float; EXR refuses NaN; write_image takes .exr") {
  temp_dir dir;
  image img(5, 3);
  const float specials[] = {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(), 1e-30f, 0.1f, 12345.678f,
                            -2.5f, std::nextafter(1.0f, 2.0f)};
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) img.pixels[i][c] = specials[(3 * i + c) % 9] * (c == 2 ? -1 : 1) + float(i) * (c == 1);
  write_image(img, dir.path / "t.exr");
  const image back = read_exr(dir.path / "t.exr");
  REQUIRE(back.width == 5);
  REQUIRE(back.height == 3);
  CHECK(std::memcmp(back.pixels.data(), img.pixels.data(), img.pixels.size() * sizeof(rgb)) == 0);
  CHECK(read(dir.path / "t.exr").rfind("\x76\x2f\x31\x01", 0) == 0);  // the EXR magic number
  const image also = read_float_image(dir.path / "t.exr");
  CHECK(std::memcmp(also.pixels.data(), img.pixels.data(), img.pixels.size() * sizeof(rgb)) == 0);

  img.at(4, 2).g = nan_f;
  CHECK_THROWS_WITH_AS(write_exr(img, dir.path / "nan.exr"), doctest::Contains("1 NaN/inf pixel(s)"), error);
  CHECK_FALSE(fs::exists(dir.path / "nan.exr"));
}

TEST_CASE("image_io: truncated, corrupted or foreign EXR files give a clear error, never a crash") {
  temp_dir dir;
  image img(16, 8);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = rgb(float(i), 0.5f, 1e3f / float(i + 1));
  write_exr(img, dir.path / "t.exr");
  const std::string bytes = read(dir.path / "t.exr");
  CHECK_THROWS_WITH_AS(parse_exr("PF\n1 1\n-1.0\n", "p.exr"), doctest::Contains("p.exr: not an OpenEXR file"), error);
  CHECK_THROWS_WITH_AS(read_exr(dir.path / "none.exr"), doctest::Contains("cannot open"), error);
  int refused = 0, read_ok = 0;
  for (std::size_t n = 0; n < bytes.size(); n += 3) {  // every truncation
    try {
      (void)parse_exr(std::string_view(bytes).substr(0, n), "cut.exr");
      ++read_ok;
    } catch (const error& e) {
      CHECK(std::string(e.what()).rfind("cut.exr: ", 0) == 0);
      ++refused;
    }
  }
  for (std::size_t k = 0; k < bytes.size(); k += 5) {  // a byte changed anywhere
    std::string bad = bytes;
    bad[k] = char(bad[k] ^ 0x5a);
    try {
      const image b = parse_exr(bad, "flip.exr");
      CHECK(b.count_nonfinite() == 0);
      ++read_ok;
    } catch (const error& e) {
      CHECK(std::string(e.what()).rfind("flip.exr: ", 0) == 0);
      ++refused;
    }
  }
  MESSAGE("malformed EXR: " << refused << " refused, " << read_ok << " read (a flip inside the pixels)");
  CHECK(refused > 0);
  std::ofstream(dir.path / "t.png") << "not a float image";
  CHECK_THROWS_WITH_AS(read_float_image(dir.path / "t.png"), doctest::Contains("not a little-endian colour PFM"), error);
}

TEST_CASE("image_io: truncated or foreign PFM files give a clear error") {
  temp_dir dir;
  image img(4, 4, rgb(0.25f));
  write_pfm(img, dir.path / "t.pfm");
  std::string bytes = read(dir.path / "t.pfm");
  bytes.resize(bytes.size() - 5);
  std::ofstream(dir.path / "cut.pfm", std::ios::binary) << bytes;
  CHECK_THROWS_WITH_AS(read_pfm(dir.path / "cut.pfm"), doctest::Contains("file ends early (truncated PFM)"),
                       error);
  std::ofstream(dir.path / "p6.pfm", std::ios::binary) << "P6\n1 1\n255\nabc";
  CHECK_THROWS_WITH_AS(read_pfm(dir.path / "p6.pfm"), doctest::Contains("not a little-endian colour PFM"),
                       error);
  std::ofstream(dir.path / "big.pfm", std::ios::binary) << "PF\n100000 100000\n-1.0\n";
  CHECK_THROWS_WITH_AS(read_pfm(dir.path / "big.pfm"), doctest::Contains("out of range"), error);
  CHECK_THROWS_WITH_AS(read_pfm(dir.path / "none.pfm"), doctest::Contains("cannot open"), error);
}

TEST_CASE("image_io: a write into a missing folder throws and leaves nothing; no temporaries") {
  temp_dir dir;
  image img(2, 2);
  for (const char* name : {"a.png", "a.ppm", "a.pfm"}) {
    CHECK_THROWS_WITH_AS(write_image(img, dir.path / "missing" / name), doctest::Contains("does not exist"),
                         error);
    write_image(img, dir.path / name);
  }
  CHECK(dir.entries() == 3);  // a.png a.ppm a.pfm and nothing else
  CHECK_THROWS_WITH_AS(write_image(img, dir.path / "a.jpg"), doctest::Contains("unknown image type '.jpg'"),
                       error);
  CHECK(dir.entries() == 3);
}

TEST_CASE("image_io: every malformed PFM is refused with its own message") {
  temp_dir dir;
  const std::string px(12, '\0');                                  // one black pixel
  std::string nan_px = px;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::memcpy(nan_px.data() + 4, &nan, 4);
  std::string inf_px = px;
  std::memcpy(inf_px.data(), &inf, 4);
  struct bad {
    const char* name;
    std::string bytes;
    const char* expected;  // after "PATH: "
  };
  const bad cases[] = {
      {"empty", "", "not a PFM file (the header ends before the magic)"},
      {"grey", "Pf\n1 1\n-1.0\n" + std::string(4, '\0'), "not a little-endian colour PFM file (it does not start with PF)"},
      {"no-height", "PF\n1", "not a PFM file (the header ends before the height)"},
      {"word-width", "PF\none 1\n-1.0\n" + px, "the width 'one' is not an integer"},
      {"width-overflow", "PF\n99999999999999999999 1\n-1.0\n" + px, "the width '99999999999999999999' is not an integer"},
      {"zero-width", "PF\n0 1\n-1.0\n", "image size 0x1 is out of range (each side 1..16384)"},
      {"too-many-pixels", "PF\n8192 8192\n-1.0\n",
       "the image size 8192x8192 in pixels is 67108864, more than the limit of 16777216 (raise with --limit pixels=N)"},
      {"nan-scale", "PF\n1 1\nnan\n" + px, "the scale 'nan' is not a finite non-zero number"},
      {"zero-scale", "PF\n1 1\n0\n" + px, "the scale '0' is not a finite non-zero number"},
      {"big-endian", "PF\n1 1\n1.0\n" + px, "a big-endian PFM (positive scale); only little-endian is read"},
      {"truncated", "PF\n2 1\n-1.0\n" + px, "file ends early (truncated PFM)"},
      {"trailing", "PF\n1 1\n-1.0\n" + px + "xyz", "3 bytes after the last pixel"},
      {"nan-pixel", "PF\n2 1\n-1.0\n" + px + nan_px, "pixel (1, 0) is NaN or infinite"},
      {"inf-pixel", "PF\n1 2\n-1.0\n" + inf_px + px, "pixel (0, 1) is NaN or infinite"},  // bottom row first
  };
  for (const bad& b : cases) {
    INFO(b.name);
    const fs::path p = dir.path / (std::string(b.name) + ".pfm");
    std::ofstream(p, std::ios::binary) << b.bytes;
    CHECK_THROWS_WITH_AS(read_pfm(p), (p.string() + ": " + b.expected).c_str(), error);
  }
  CHECK_THROWS_WITH_AS(read_pfm(dir.path), (dir.path.string() + ": is a directory; only regular files are read").c_str(),
                       error);
  CHECK_THROWS_WITH_AS(read_pfm("/dev/zero"), "/dev/zero: is a character device; only regular files are read", error);
}

TEST_CASE("image_io: an empty or folder-only output name is refused by name, and nothing is written") {
  temp_dir dir;
  image img(2, 2);
  CHECK_THROWS_WITH_AS(write_image(img, ""), "the output file name is empty", error);
  CHECK_THROWS_WITH_AS(write_image(img, dir.path.string() + "/"),
                       ("cannot write '" + dir.path.string() + "/': it names a folder, not a file").c_str(), error);
  CHECK_THROWS_WITH_AS(write_png(img, dir.path / ".png"), doctest::Contains("(an empty --out?)"), error);
  CHECK(dir.entries() == 0);
}
