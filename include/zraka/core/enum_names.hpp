#pragma once
// Names for an enum's values, written once per enum as a table that the command line, the
// scene files and the messages all read. An enum takes part by declaring, next to itself, its
// table and a function enum_names that returns it (found by argument-dependent lookup, so a
// chapter's own enum takes part the same way):
//
//   enum class integrator { naive, nee, mis };
//   inline constexpr enum_name<integrator> integrator_names[] = {
//       {integrator::naive, "naive"}, {integrator::nee, "nee"}, {integrator::mis, "mis"}};
//   constexpr std::span<const enum_name<integrator>> enum_names(integrator) { return integrator_names; }
//
// Then name(e) is the value's name, parse_enum<E>(text, what) the value of a name, and a name
// that is not in the table is refused with the valid ones listed:
//   what a noun ("integrator"):  unknown integrator 'x' (naive, nee, mis)
//   what an option ("--lights"): --lights must be power or uniform, got 'x'
#include <zraka/core/error.hpp>

#include <concepts>
#include <span>
#include <string>
#include <string_view>

namespace zraka {

template <class E> struct enum_name {
  E value;
  const char* name;
};

template <class E>
concept named_enum = requires(E e) {
  { enum_names(e) } -> std::convertible_to<std::span<const enum_name<E>>>;
};

// The name of e ("?" for a value the table lacks).
template <named_enum E> constexpr const char* name(E e) {
  for (const enum_name<E>& n : enum_names(E{}))
    if (n.value == e) return n.name;
  return "?";
}

// The names in table order: "naive, nee, mis", or with last = " or ": "power or uniform".
template <named_enum E> std::string enum_name_list(std::string_view last = ", ") {
  const std::span<const enum_name<E>> names = enum_names(E{});
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += std::string(i == 0 ? "" : i + 1 == names.size() ? last : ", ") + names[i].name;
  return out;
}

template <named_enum E> E parse_enum(std::string_view text, std::string_view what) {
  for (const enum_name<E>& n : enum_names(E{}))
    if (text == n.name) return n.value;
  if (what.starts_with("--"))
    throw error(std::string(what) + " must be " + enum_name_list<E>(" or ") + ", got '" + std::string(text) + "'");
  throw error("unknown " + std::string(what) + " '" + std::string(text) + "' (" + enum_name_list<E>() + ")");
}

}  // namespace zraka
