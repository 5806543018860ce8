#include <zraka/app/program_options.hpp>

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

using namespace zraka;

namespace {
// Parses a command line; returns the exit code or -1 when the program should go on.
int run(program_options& o, std::vector<std::string> args) {
  args.insert(args.begin(), "prog");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  const auto done = o.parse(int(argv.size()), argv.data());
  return done ? *done : -1;
}
}  // namespace

TEST_CASE("program_options: defaults, and given values override them") {
  program_options o{"t", take::image | take::depth};
  o.width = 40, o.height = 30, o.out = "x.png";
  std::filesystem::create_directories("sub");  // an output's folder must exist (checked at parse)
  CHECK(run(o, {"--spp", "8", "--out", "sub/y.ppm"}) == -1);
  CHECK(o.width == 40);
  CHECK(o.spp == 8);
  CHECK(o.out == "sub/y.ppm");  // a name with a folder is taken as given
  CHECK(o.given("--spp"));
  CHECK_FALSE(o.given("--width"));
  CHECK(o.threads >= 1);  // 0 became the number of cores
  CHECK(o.sibling("-reference") == "sub/y-reference.ppm");
  CHECK(o.sibling("-naive", ".csv") == "sub/y-naive.csv");
}

TEST_CASE("program_options: bad values are exit code 1, before any work") {
  {
    program_options o{"t", take::image};
    o.out = "x.png";
    CHECK(run(o, {"--out", "x.jpg"}) == 1);
  }
  {
    program_options o{"t", take::image};
    o.out = "x.png";
    CHECK(run(o, {"--spp", "0"}) == 1);
  }
  {
    program_options o{"t", take::image};
    o.out = "x.png";
    CHECK(run(o, {"--width", "0"}) == 1);
  }
  {
    program_options o{"t", take::image | take::depth};
    o.out = "x.png", o.min_depth = 0, o.max_depth = 5;
    CHECK(run(o, {"--depth", "6"}) == 1);
    program_options p{"t", take::image | take::depth};
    p.out = "x.png", p.min_depth = 0, p.max_depth = 5;
    CHECK(run(p, {"--depth", "0"}) == -1);
  }
  {
    program_options o{"t", take::image};
    o.out = "x.png";
    CHECK(run(o, {"--no-such"}) == 1);
  }
}

TEST_CASE("program_options: --sampler only where taken, its name checked before any work") {
  {
    program_options o{"t", take::image | take::sampler};
    o.out = "x.png", o.sampler = "stratified";
    CHECK(run(o, {}) == -1);
    CHECK(o.sampler_choice() == sampler_kind::stratified);  // the program's default
  }
  {
    program_options o{"t", take::image | take::sampler};
    o.out = "x.png";
    CHECK(run(o, {"--sampler", "sobol"}) == -1);
    CHECK(o.sampler_choice() == sampler_kind::sobol);
  }
  {
    program_options o{"t", take::image | take::sampler};
    o.out = "x.png";
    CHECK(run(o, {"--sampler", "Sobol"}) == 1);  // names are exact
  }
  {
    program_options o{"t", take::image};  // a program that does not take it refuses it
    o.out = "x.png";
    CHECK(run(o, {"--sampler", "sobol"}) == 1);
  }
}

TEST_CASE("program_options: scene settings are the defaults unless the command line gives one") {
  struct settings_like { int width = 200, height = 100, spp = 64, max_depth = 8; std::uint64_t seed = 5; };
  program_options o{"t", take::image | take::depth | take::scene};
  o.out = "x.png", o.scene_settings = true;
  CHECK(run(o, {"--height", "50"}) == -1);
  settings_like s;
  o.apply_to(s);
  CHECK(s.width == 200);
  CHECK(s.height == 50);
  CHECK(o.width == 200);
  CHECK(o.height == 50);
  CHECK(o.seed == 5);
  settings_like bad;
  bad.spp = 0;  // a scene's own value is checked as well
  CHECK_THROWS_AS(o.apply_to(bad), error);
}

TEST_CASE("program_options: output_file keeps a name with a folder, input_file finds what it wrote") {
  std::filesystem::create_directories("a");
  CHECK(output_file("a/b.png") == std::filesystem::path("a/b.png"));
  CHECK(output_file("/tmp/b.png") == std::filesystem::path("/tmp/b.png"));
  CHECK(input_file("no-such-file.pfm") == std::filesystem::path("no-such-file.pfm"));  // reported as given
}

TEST_CASE("program_options: every output name is checked before any work, and an error names its option") {
  // A folder that does not exist: refused at parse (--out) or by output_file (a program's other
  // outputs, e.g. --pfm), before a render could write anything else.
  std::filesystem::remove_all("no-such-folder");
  {
    program_options o{"t", take::image};
    o.out = "x.png";
    CHECK(run(o, {"--out", "no-such-folder/x.png"}) == 1);
  }
  CHECK_THROWS_WITH_AS(output_file("no-such-folder/x.pfm"),
                       "cannot write 'no-such-folder/x.pfm': the folder 'no-such-folder' does not exist", error);
  // An empty --out: the error says which option was empty.
  program_options o{"t", take::image};
  o.out = "x.png";
  CHECK(run(o, {"--out", ""}) == 1);
}
