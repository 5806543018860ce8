#pragma once
// The integrators by name (book 2.3, "A program of one's own"): the built-ins naive, nee and mis
// are registered with scene_registry::add_integrator, one line each below, as a course registers
// its own (an ambient-occlusion integrator: tests/course/ao.hpp); `--integrator NAME` is looked up
// among both.
//
// A built-in's factory returns the path tracer itself (path_tracer_t, whose call is a radiance
// function's), so the program can find it again (radiance_fn::target) and call it directly, as
// before the door: only a course's integrator is called through std::function.
#include <zraka/core/error.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <string>

namespace zraka {

// The factory of the path tracer with `method` (path.hpp).
inline scene_registry::integrator_factory path_integrator(integrator method) {
  return [method](const scene& sc, const path_options& o) {
    path_options p = o;
    p.method = method;
    return scene_registry::radiance_fn(path_tracer(sc, p));
  };
}

// [listing builtin-integrators]
inline const scene_registry& builtin_integrators() {
  static const scene_registry reg = [] {
    scene_registry r;
    r.add_integrator(name(integrator::naive), path_integrator(integrator::naive));
    r.add_integrator(name(integrator::nee), path_integrator(integrator::nee));
    r.add_integrator(name(integrator::mis), path_integrator(integrator::mis));
    return r;
  }();
  return reg;
}
// [end]

// "ao, fog" (or ""): the names of a course's integrators, for the lists below.
inline std::string registered_integrators(const scene_registry& course) {
  std::string s;
  for (const auto& kv : course.integrators()) s += (s.empty() ? "" : ", ") + kv.first;
  return s;
}

// "naive, nee or mis; registered: ao": what --integrator takes with this course's registry.
inline std::string integrator_choices(const scene_registry& course) {
  const std::string own = registered_integrators(course);
  return enum_name_list<integrator>(" or ") + (own.empty() ? "" : "; registered: " + own);
}

// The factory of the integrator called `name`, built in or the course's. A course's integrator
// may not take a built-in's name; an unknown name is refused with the valid ones, as
// parse_integrator refuses it ("unknown integrator 'x' (naive, nee, mis; registered: ao)").
inline const scene_registry::integrator_factory& find_integrator(const std::string& name, const scene_registry& course) {
  for (const auto& kv : course.integrators())
    if (builtin_integrators().integrator_type(kv.first))
      throw error("scene registry: integrator '" + kv.first + "' is built in; a registered integrator must have a new name");
  if (const auto* f = builtin_integrators().integrator_type(name)) return *f;
  if (const auto* f = course.integrator_type(name)) return *f;
  const std::string own = registered_integrators(course);
  throw error("unknown integrator '" + name + "' (" + enum_name_list<integrator>() +
              (own.empty() ? "" : "; registered: " + own) + ")");
}

// The integrator a program renders with: --integrator when it was given (`option`), else the
// scene file's settings.integrator, else the option's default. A name the scene file gives is
// checked here, where the course's names are known, and refused with the file and the field.
inline std::string chosen_integrator(const std::string& option, bool given, const scene& sc,
                                     const std::string& scene_name, const scene_registry& course) {
  if (given || sc.settings.integrator.empty()) return option;
  try {
    (void)find_integrator(sc.settings.integrator, course);
  } catch (const error& e) {
    throw error(scene_name + ": settings.integrator: " + e.what());
  }
  return sc.settings.integrator;
}

// A renderer that runs the built-ins only (realtime's kernel) refuses a course's integrator by
// name and says which program can: "realtime: integrator 'ao' is a course's integrator, which the
// OpenCL kernel cannot run; render it with your course's program built on zraka::pathtrace_main".
inline void refuse_course_integrator(const std::string& name, const scene_registry& course, const char* program,
                                     const char* renderer) {
  if (!builtin_integrators().integrator_type(name) && course.integrator_type(name))
    throw error(std::string(program) + ": integrator '" + name + "' is a course's integrator, which " + renderer +
                " cannot run; render it with your course's program built on zraka::pathtrace_main");
}

}  // namespace zraka
