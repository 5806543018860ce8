# zraka_add_chapters(DIR): every folder DIR/<N.M>-<slug>/ holding a main.cpp becomes the
# executable <slug> (e.g. chapters/1.5-intersections -> bin/intersections). Nothing is listed
# by hand, so a new chapter folder is built, and smoke-tested, as soon as it exists.
#
# Optional files in a chapter folder:
#   link.txt   one CMake target per line that the chapter links besides zraka (e.g. zraka::compiled)
#   needs.txt  one package per line (OpenCL, glfw, epoxy, yaml-cpp, tinyobjloader, fmt) to find first;
#              if one is missing the chapter is skipped with a message
#   smoke.txt  the smoke test: see tools/smoke.py
function(zraka_add_chapters dir)
  file(GLOB children RELATIVE ${dir} CONFIGURE_DEPENDS ${dir}/*)
  list(SORT children COMPARE NATURAL)
  foreach(child IN LISTS children)
    if(NOT IS_DIRECTORY ${dir}/${child} OR NOT EXISTS ${dir}/${child}/main.cpp)
      continue()
    endif()
    if(NOT child MATCHES "^([0-9]+(\\.[0-9]+)?)-([a-z0-9-]+)$")
      message(FATAL_ERROR "chapter folder '${child}' is not named <N.M>-<slug>")
    endif()
    set(name ${CMAKE_MATCH_3})
    if(ZRAKA_SANITIZE AND NOT child IN_LIST ZRAKA_SANITIZE_CHAPTERS)
      continue()  # see ZRAKA_SANITIZE_CHAPTERS in CMakeLists.txt
    endif()
    set(extra_libs "")
    set(ok TRUE)
    zraka_pch_kind(pch ${dir}/${child}/main.cpp)
    if(EXISTS ${dir}/${child}/needs.txt)
      file(STRINGS ${dir}/${child}/needs.txt needs)
      foreach(need IN LISTS needs)
        zraka_find_dependency(${need} found lib)
        if(NOT found)
          message(STATUS "zraka: skipping chapter ${child}: ${need} not found")
          set(ok FALSE)
        else()
          list(APPEND extra_libs ${lib})
          if(pch STREQUAL "scene" AND (need STREQUAL "OpenCL" OR need STREQUAL "glfw"))
            set(pch gpu)  # cmake/pch/gpu.hpp: the C APIs' headers precompiled too
          endif()
        endif()
      endforeach()
    endif()
    if(NOT ok)
      continue()
    endif()
    file(GLOB sources CONFIGURE_DEPENDS ${dir}/${child}/*.cpp)
    add_executable(${name} ${sources})
    target_link_libraries(${name} PRIVATE zraka::zraka zraka_warnings zraka::compiled ${extra_libs})
    zraka_use_pch(${pch} ${name})
    set_property(GLOBAL APPEND PROPERTY ZRAKA_CHAPTERS ${name})
    if(EXISTS ${dir}/${child}/smoke.txt AND ZRAKA_BUILD_TESTS)
      set(work ${CMAKE_BINARY_DIR}/smoke/${child})
      file(MAKE_DIRECTORY ${work})
      add_test(NAME chapter.${child}
               COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/smoke.py
                       $<TARGET_FILE:${name}> ${dir}/${child}/smoke.txt
               WORKING_DIRECTORY ${work})
      set_tests_properties(chapter.${child} PROPERTIES LABELS chapter TIMEOUT 300)
    endif()
  endforeach()
endfunction()

# The optional dependencies by the short names used in needs.txt and "// links:" lines:
# short name | find_package arguments | imported target. epoxy has no CMake package (pkg-config).
set(ZRAKA_DEPENDENCIES
  "OpenCL|OpenCL|OpenCL::OpenCL"
  "glfw|glfw3|glfw"
  "yaml-cpp|yaml-cpp|yaml-cpp"
  "assimp|assimp|assimp::assimp"
  "pugixml|pugixml|pugixml::pugixml"
  "tinyobjloader|tinyobjloader|tinyobjloader::tinyobjloader"
  "fmt|fmt|fmt::fmt"
  "threads|Threads|Threads::Threads"
  "embree|embree 3|embree")

# Finds one optional dependency by its short name; sets <found_var> and <lib_var>.
function(zraka_find_dependency need found_var lib_var)
  if(need STREQUAL "epoxy")
    pkg_check_modules(EPOXY QUIET IMPORTED_TARGET GLOBAL epoxy)
    set(${found_var} ${EPOXY_FOUND} PARENT_SCOPE)
    set(${lib_var} PkgConfig::EPOXY PARENT_SCOPE)
    return()
  endif()
  foreach(row IN LISTS ZRAKA_DEPENDENCIES)
    string(REPLACE "|" ";" fields "${row}")
    list(GET fields 0 short)
    if(short STREQUAL need)
      list(GET fields 1 package)
      list(GET fields 2 target)
      separate_arguments(package)  # "embree 3": the name and the version
      find_package(${package} QUIET)
      list(GET package 0 name)
      set(${found_var} ${${name}_FOUND} PARENT_SCOPE)
      set(${lib_var} ${target} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "zraka: unknown dependency '${need}' in needs.txt")
endfunction()
