// enum_names.hpp: one table per enum gives name(e), parse_enum and the error that lists the
// valid names; the library's enums and a program's own enum take part the same way.
#include <zraka/core/enum_names.hpp>
#include <zraka/geometry/triangle.hpp>
#include <zraka/integrators/bdpt.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/media/medium.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/sampling/samplers.hpp>
#include <zraka/scene/cornell.hpp>
#include <zraka/scene/lights.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace zraka;

namespace course {  // an enum of a program's own, outside namespace zraka
enum class fruit { apple, pear };
constexpr enum_name<fruit> fruit_names[] = {{fruit::apple, "apple"}, {fruit::pear, "pear"}};
constexpr std::span<const enum_name<fruit>> enum_names(fruit) { return fruit_names; }
}  // namespace course

namespace {
// Every value of the table round-trips, and the names are distinct.
template <class E> void round_trip(std::string_view what) {
  const auto table = enum_names(E{});
  REQUIRE(!table.empty());
  for (const auto& n : table) {
    CHECK(std::string(name(n.value)) == n.name);
    CHECK(parse_enum<E>(n.name, what) == n.value);
  }
}
}  // namespace

TEST_CASE("enum_names: every library table round-trips") {
  round_trip<integrator>("integrator");
  round_trip<sampler_kind>("sampler");
  round_trip<pixel_pattern>("pixel pattern");
  round_trip<media_estimator>("media estimator");
  round_trip<cornell_variant>("Cornell box variant");
  round_trip<light_selection>("--lights");
  round_trip<mis_heuristic>("--heuristic");
  round_trip<triangle_method>("--method");
  round_trip<course::fruit>("fruit");
}

TEST_CASE("enum_names: the names a table gives, and the errors that list them") {
  CHECK(std::string(name(integrator::nee)) == "nee");
  CHECK(std::string(name(triangle_method::moller_trumbore)) == "mt");
  CHECK(std::string(name(course::fruit::pear)) == "pear");
  CHECK(enum_name_list<integrator>() == "naive, nee, mis");
  CHECK(enum_name_list<light_selection>(" or ") == "power or uniform");
  CHECK(sampler_names == "independent, stratified, halton, sobol");
  // a noun: "unknown <what> '<text>' (<names>)"; an option: "<option> must be <a or b>, got '<text>'"
  CHECK_THROWS_WITH_AS(parse_enum<integrator>("bidirectional", "integrator"),
                       "unknown integrator 'bidirectional' (naive, nee, mis)", error);
  CHECK_THROWS_WITH_AS(parse_integrator("bidirectional"), "unknown integrator 'bidirectional' (naive, nee, mis)", error);
  CHECK_THROWS_WITH_AS(parse_enum<mis_heuristic>("max", "--heuristic"), "--heuristic must be power or balance, got 'max'",
                       error);
  CHECK_THROWS_WITH_AS(parse_enum<triangle_method>("fast", "--method"),
                       "--method must be edge, mt or watertight, got 'fast'", error);
  CHECK_THROWS_WITH_AS(parse_enum<course::fruit>("Apple", "fruit"), "unknown fruit 'Apple' (apple, pear)", error);
  CHECK_THROWS_WITH_AS(parse_media_estimator(""), "unknown media estimator '' (delta, march)", error);
}
