# Precompiled headers (issue 12, "the student's loop"): four precompiled headers, each compiled
# once and reused by every target of its kind (target_precompile_headers REUSE_FROM):
#   zraka_pch_programs  cmake/pch/programs.hpp  chapters, benchmarks, assignments' render programs
#   zraka_pch_scene     cmake/pch/scene.hpp     the same, for those that render scenes
#                                               (zraka_pch_kind below picks it from the sources)
#   zraka_pch_gpu       cmake/pch/gpu.hpp       the same, for those that drive OpenCL or OpenGL
#   zraka_pch_tests     cmake/pch/tests.hpp     unit tests, assignments' tests
# CLI11 is in neither: it is compiled once into zraka::compiled (include/zraka/app/cli.hpp), and the
# programs' PCH is made with that library's -DZRAKA_COMPILED, like its users.
#
# What is in them: standard, GLM, yaml-cpp, tinyobjloader and doctest headers in all; zraka's
# scene-level headers in scene.hpp and gpu.hpp, and OpenCL's, libepoxy's and GLFW's in gpu.hpp.
# Decided against at first, when a chapter's unit was ~20 CPU-s of -O3 code generation that no
# PCH saves; since the heavy non-template parts are compiled once (zraka::compiled), a scene
# chapter's unit is ~2.4 s, about half of it parsing zraka's headers, so now they are in:
# 2.3-pathtrace 2.39 -> 1.72 s, 6.4-metropolis 2.76 -> 2.08 s, 4.3-realtime (gpu.hpp) 3.43 -> 2.15 s
# (tools/build_times.sh). The price: editing one of those headers rebuilds the PCH (~10 s) and
# then every target that uses it; that edit already rebuilt zraka::compiled's units (20-47 s,
# measured touching path.hpp, sphere.hpp, program_options.hpp), which the PCH builds beside.
# The early chapters keep programs.hpp (a larger PCH costs them more to load than it saves),
# and a PCH still hides a missing #include in a chapter or test (not in a header: the
# headers.self_contained test compiles each one alone).
#
# GCC uses a PCH only when the flags that define macros (-D, -O, -pthread, -fsanitize, ...) are
# the same as when it was made; otherwise it silently parses the headers again. CMake passes
# -Winvalid-pch, and with ZRAKA_WERROR a rejected PCH fails the build, so CI checks that every
# user really gets it. A target with its own flags (a sanitizer build of a few targets, the
# fuzzers) must not be given these PCHs; a project-wide flag is fine (the hosts get it too).
#
# Not given a PCH, on purpose: the per-header self-containedness check (tests/CMakeLists.txt,
# headers.self_contained: a PCH would hide a missing #include) and doctest's main (zraka_test_main:
# it defines DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN before including doctest).
#
# ccache: works with these PCHs given CCACHE_SLOPPINESS=pch_defines,time_macros (BRIEF.md's
# setting adds include_file_mtime,include_file_ctime, which a freshly built PCH needs); without
# that sloppiness ccache just does not cache the units that use a PCH. CI has no ccache.
option(ZRAKA_PCH "Use precompiled headers for the chapters, tests and benchmarks" ON)

if(ZRAKA_PCH)
  foreach(kind IN ITEMS programs scene gpu tests)
    set(host_src ${CMAKE_BINARY_DIR}/pch/zraka_pch_${kind}.cpp)
    file(CONFIGURE OUTPUT ${host_src} CONTENT "// Hosts the precompiled header cmake/pch/${kind}.hpp.\n")
    add_library(zraka_pch_${kind} OBJECT ${host_src})
    # The same usage requirements as its users, so that the flags match.
    target_link_libraries(zraka_pch_${kind} PRIVATE zraka::zraka zraka_warnings)
    target_link_libraries(zraka_pch_${kind} PRIVATE zraka::compiled)  # its -DZRAKA_COMPILED
    target_precompile_headers(zraka_pch_${kind} PRIVATE ${CMAKE_CURRENT_LIST_DIR}/pch/${kind}.hpp)
  endforeach()
  # The C APIs' include folders and definitions, as their users get them.
  foreach(lib IN ITEMS OpenCL::OpenCL glfw PkgConfig::EPOXY)
    if(TARGET ${lib})
      target_link_libraries(zraka_pch_gpu PRIVATE ${lib})
    endif()
  endforeach()
endif()

# zraka_use_pch(<programs|scene|gpu|tests> <target>...)
function(zraka_use_pch kind)
  if(NOT ZRAKA_PCH)
    return()
  endif()
  foreach(target IN LISTS ARGN)
    target_precompile_headers(${target} REUSE_FROM zraka_pch_${kind})
  endforeach()
endfunction()

# zraka_use_pch_in_directory(<dir>): every executable defined in <dir> gets a PCH by what it
# links: zraka_test_main (zraka::test_main) -> tests, otherwise programs or scene (zraka_pch_kind). For folders whose CMakeLists.txt only
# lists programs and tests (book/assignments/), so that it needs no PCH lines of its own.
function(zraka_use_pch_in_directory dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(NOT type STREQUAL "EXECUTABLE")
      continue()
    endif()
    get_target_property(libs ${target} LINK_LIBRARIES)
    if("zraka_test_main" IN_LIST libs OR "zraka::test_main" IN_LIST libs)
      zraka_use_pch(tests ${target})
    else()
      zraka_use_program_pch(${target})
    endif()
  endforeach()
endfunction()

# zraka_pch_kind(<out_var> <source>...): "scene" when a source includes a header that brings in
# the scene and most of cmake/pch/scene.hpp with it, else "programs" (a unit that includes only,
# say, error.hpp would load the larger PCH for nothing).
function(zraka_pch_kind out_var)
  set(kind programs)
  foreach(src IN LISTS ARGN)
    file(STRINGS ${src} lines REGEX "^#include <zraka/[a-z]+/(path|render|scene|scene_argument|scene_query|lights|progressive)\\.hpp>")
    if(lines)
      set(kind scene)
    endif()
  endforeach()
  set(${out_var} ${kind} PARENT_SCOPE)
endfunction()

# zraka_use_program_pch(<target>...): each program target gets the PCH zraka_pch_kind picks from
# its own sources.
function(zraka_use_program_pch)
  foreach(target IN LISTS ARGN)
    get_target_property(srcs ${target} SOURCES)
    get_target_property(sdir ${target} SOURCE_DIR)
    list(TRANSFORM srcs PREPEND ${sdir}/ REGEX "^[^/]")
    zraka_pch_kind(kind ${srcs})
    zraka_use_pch(${kind} ${target})
  endforeach()
endfunction()
