# Precompiled headers (issue 12, "the student's loop"): two precompiled headers, each compiled
# once and reused by every target of its kind (target_precompile_headers REUSE_FROM):
#   zraka_pch_programs  cmake/pch/programs.hpp  chapters, benchmarks, assignments' render programs
#   zraka_pch_tests     cmake/pch/tests.hpp     unit tests, assignments' tests
# CLI11 is in neither: it is compiled once into zraka::compiled (include/zraka/cli.hpp), and the
# programs' PCH is made with that library's -DZRAKA_COMPILED, like its users.
#
# What is in them: standard, GLM, yaml-cpp, tinyobjloader and doctest headers; no zraka
# header. Measured, and decided against zraka's: with the zraka headers of 2.2-whitted added to
# the PCH, its front end (-fsyntax-only) went from 3.2 to 1.7 CPU-s, out of ~20 CPU-s for the
# whole compile, which is code generation at -O3 that no PCH saves; the PCH grew from 150 to
# 210 MB, which every unit loads. In exchange every chapter and test would depend on every
# header: editing any header, the most common edit after main.cpp, would rebuild the PCH (~7 s,
# before anything else can start) and then every target, instead of only those that include
# that header. And the PCH would hide a missing #include in a chapter or test.
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
  foreach(kind IN ITEMS programs tests)
    set(host_src ${CMAKE_BINARY_DIR}/pch/zraka_pch_${kind}.cpp)
    file(CONFIGURE OUTPUT ${host_src} CONTENT "// Hosts the precompiled header cmake/pch/${kind}.hpp.\n")
    add_library(zraka_pch_${kind} OBJECT ${host_src})
    # The same usage requirements as its users, so that the flags match.
    target_link_libraries(zraka_pch_${kind} PRIVATE zraka::zraka zraka_warnings)
    target_link_libraries(zraka_pch_${kind} PRIVATE zraka::compiled)  # its -DZRAKA_COMPILED
    target_precompile_headers(zraka_pch_${kind} PRIVATE ${CMAKE_CURRENT_LIST_DIR}/pch/${kind}.hpp)
  endforeach()
endif()

# zraka_use_pch(<programs|tests> <target>...)
function(zraka_use_pch kind)
  if(NOT ZRAKA_PCH)
    return()
  endif()
  foreach(target IN LISTS ARGN)
    target_precompile_headers(${target} REUSE_FROM zraka_pch_${kind})
  endforeach()
endfunction()

# zraka_use_pch_in_directory(<dir>): every executable defined in <dir> gets a PCH by what it
# links: zraka_test_main (zraka::test_main) -> tests, otherwise programs. For folders whose CMakeLists.txt only
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
      zraka_use_pch(programs ${target})
    endif()
  endforeach()
endfunction()
