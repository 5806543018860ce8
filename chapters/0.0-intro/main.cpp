// Chapter 0.0 — the introduction. Prints what the course is about (the ladder of algorithms and
// the two back ends) and then the course itself: every chapter folder, the program it builds,
// whether that program is built yet, and its book page. Nothing is listed by hand: the chapter
// folders are read from the resource root (ZRAKA_ROOT, or the source tree compiled in) or, when
// that has none, from the folder this file was compiled from.
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/stopwatch.hpp>

#include <zraka/app/cli.hpp>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <system_error>
#include <tuple>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct chapter {
  int major = 0, minor = 0;  // N.M, compared as numbers: 1.10 comes after 1.9
  std::string folder, slug;
};

// [listing folders]
// "<N>.<M>-<slug>" with a slug of lowercase letters, digits and dashes: the chapter it names.
std::optional<chapter> parse_folder(const std::string& folder) {
  chapter c{0, 0, folder, ""};
  const char *p = folder.data(), *end = p + folder.size();
  auto number = [&](int& v) {
    const auto r = std::from_chars(p, end, v);
    const bool ok = r.ec == std::errc() && r.ptr != p && *p != '-' && *p != '+';
    p = r.ptr;
    return ok;
  };
  if (!number(c.major) || p == end || *p++ != '.' || !number(c.minor) || p == end || *p++ != '-' || p == end)
    return std::nullopt;
  c.slug.assign(p, end);
  for (char ch : c.slug)
    if (!((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '-')) return std::nullopt;
  return c;
}

// Every folder <N.M>-<slug>/ holding a main.cpp, in course order (numbers compared as numbers).
std::vector<chapter> find_chapters(const fs::path& dir) {
  std::vector<chapter> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const auto c = parse_folder(entry.path().filename().string());
    if (c && entry.is_directory() && fs::exists(entry.path() / "main.cpp")) found.push_back(*c);
  }
  std::sort(found.begin(), found.end(), [](const chapter& a, const chapter& b) {
    return std::tie(a.major, a.minor, a.slug) < std::tie(b.major, b.minor, b.slug);
  });
  return found;
}
// [end]

// The page's title (its first "# " line), or "" when the page does not exist.
std::string page_title(const fs::path& page) {
  std::ifstream in(page);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("# ", 0) == 0) return line.substr(2);
  return "";
}

// The book page of a chapter: book/<folder>.md, else the page that names chapters/<folder>/
// (two programs may share a page, as 3.2-opengl and 3.2-tessellation do), else "".
std::string find_page(const fs::path& book, const chapter& c) {
  if (fs::exists(book / (c.folder + ".md"))) return c.folder + ".md";
  if (c.folder == "0.0-intro" && fs::exists(book / "intro.md")) return "intro.md";
  if (!fs::is_directory(book)) return "";
  std::string first;  // of the pages that name the folder, the first by name (not by listing order)
  for (const auto& entry : fs::directory_iterator(book)) {
    const std::string p = entry.path().filename().string();
    if (entry.path().extension() != ".md" || (!first.empty() && p > first)) continue;
    std::ifstream in(entry.path());
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    if (text.find("chapters/" + c.folder + "/") != std::string::npos) first = p;
  }
  return first;
}

}  // namespace

int main(int argc, char** argv) {
  std::string root;
  zraka::cli_app app{"Chapter 0.0: the course at a glance, and every chapter with its program and page"};
  app.add_option("--root", root,
                 "folder holding chapters/ and book/ (default: ZRAKA_ROOT or the source tree)");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;

  return zraka::guarded([&] {
    const zraka::stopwatch clock;
    // Where the chapter folders are: --root, else the resource root, else this file's folder.
    fs::path base;
    if (!root.empty()) {
      base = root;
      if (!fs::is_directory(base / "chapters"))
        throw zraka::error("--root " + root + " has no chapters/ folder");
    } else if (fs::is_directory(zraka::resource_root() / "chapters")) {
      base = zraka::resource_root();
    } else if (const fs::path here = fs::path(__FILE__).parent_path().parent_path().parent_path();
               fs::is_directory(here / "chapters")) {
      base = here;
    } else {
      throw zraka::error("no chapters/ folder found: set ZRAKA_ROOT or pass --root");
    }

    // [listing ladder]
    std::printf(
        "zraka: a course in ray tracing and path tracing, one program per section of the thesis\n"
        "\n"
        "The ladder (each rung keeps what the one below it does):\n"
        "  1. ray casting       one ray per pixel, stops at the first hit      1.2, 1.5, 2.1, 3.1\n"
        "  2. Whitted tracing   + mirror and glass rays, light from the lamps  2.2, 4.1\n"
        "  3. path tracing      + random bounces until a light is reached     2.3, 4.2, 4.3\n"
        "\n"
        "Two back ends:\n"
        "  CPU  plain C++, writes image files (PPM, PNG, PFM): every chapter but the GPU ones below\n"
        "  GPU  OpenGL draws in a live window (3.2), OpenCL computes on the device (3.3), and\n"
        "       4.3 joins them: OpenCL path-traces each frame, OpenGL shows it\n"
        "\n");
    // [end]

    std::error_code ec;
    fs::path bin = fs::read_symlink("/proc/self/exe", ec).parent_path();
    if (ec) bin = fs::absolute(argv[0]).parent_path();

    const auto chapters = find_chapters(base / "chapters");
    std::printf("Chapters (from %s):\n", (base / "chapters").string().c_str());
    std::printf("  %-5s %-27s %-6s %-29s %s\n", "", "program", "built", "book page", "title");
    int pages = 0, built = 0;
    for (const auto& c : chapters) {
      const std::string page = find_page(base / "book", c);
      const bool is_built = fs::exists(bin / c.slug);
      pages += !page.empty();
      built += is_built;
      const std::string title = page.empty() ? "" : page_title(base / "book" / page);
      std::printf("  %-5s %-27s %-6s %-29s %s\n", c.folder.substr(0, c.folder.find('-')).c_str(),
                  ("build/bin/" + c.slug).c_str(), is_built ? "yes" : "no",
                  page.empty() ? "(not written yet)" : ("book/" + page).c_str(), title.c_str());
    }
    std::printf("\nStart with book/intro.md; build everything with `bash tools/build.sh`;\n"
                "every program takes --help.\n");
    std::printf("summary: %zu chapters, %d with a book page, %d built, listed in %.3f s\n",
                chapters.size(), pages, built, clock.seconds());
    return 0;
  });
}
