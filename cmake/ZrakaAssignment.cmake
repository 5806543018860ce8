# zraka_add_assignment(<dir> [NAME <name>] [LIBS <target>...] [TIMEOUT <seconds>])
# zraka_add_assignments(<parent dir> [LIBS <target>...])   every NN-name/ folder under it
#
# An assignment folder (book/assignments/README.md) holds student/ (the stub), solution/ (not in
# a handed-out copy) and test_*.cpp, and optionally render.cpp. Installed with zraka, so an
# instructor's own repository uses the same pairing: find_package(zraka COMPONENTS testing).
# The tests are built once per variant:
#   assignment-<name>-solution  against solution/  -> ctest assignment.<name>.solution (must pass)
#   assignment-<name>-student   against student/   -> ctest assignment.<name>.stub     (must fail)
# The stub must compile and fail through assertions: its test passes only when doctest reports
# "Status: FAILURE!" (failed checks or a "not implemented" exception), and fails on a crash or a
# timeout. Without solution/ only the student's build is made, and assignment.<name> must pass
# (the student's progress). A render.cpp becomes assignment-<name>-render (against solution/) and
# assignment-<name>-render-student. The variant's folder comes first on the include path (the
# tests include the student's file by its bare name); ASSIGNMENT_DIR is the folder.
# LIBS: more targets for every program (zraka's own build adds its warning flags).
function(zraka_add_assignment dir)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "NAME;TIMEOUT" "LIBS")
  get_filename_component(dir "${dir}" ABSOLUTE)
  if(NOT arg_NAME)
    get_filename_component(arg_NAME "${dir}" NAME)
  endif()
  if(NOT arg_TIMEOUT)
    set(arg_TIMEOUT 120)
  endif()
  set(name ${arg_NAME})
  file(GLOB tests CONFIGURE_DEPENDS ${dir}/test_*.cpp)
  set(variants "")
  foreach(variant IN ITEMS solution student)
    if(IS_DIRECTORY ${dir}/${variant})
      list(APPEND variants ${variant})
    endif()
  endforeach()
  if(NOT "student" IN_LIST variants OR NOT tests)
    message(STATUS "zraka: assignment ${name} has no student/ and test_*.cpp yet: not built")
    return()
  endif()
  foreach(variant IN LISTS variants)
    set(target assignment-${name}-${variant})
    add_executable(${target} ${tests})
    target_include_directories(${target} PRIVATE ${dir}/${variant} ${dir})
    target_compile_definitions(${target} PRIVATE ASSIGNMENT_DIR="${dir}")
    target_link_libraries(${target} PRIVATE zraka::test_main ${arg_LIBS})
    set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/assignments)
  endforeach()
  if(NOT "solution" IN_LIST variants)
    add_test(NAME assignment.${name} COMMAND assignment-${name}-student)
    set_tests_properties(assignment.${name} PROPERTIES LABELS assignment TIMEOUT ${arg_TIMEOUT})
  else()
    add_test(NAME assignment.${name}.solution COMMAND assignment-${name}-solution)
    add_test(NAME assignment.${name}.stub COMMAND assignment-${name}-student)
    set_tests_properties(assignment.${name}.solution assignment.${name}.stub PROPERTIES
                         LABELS assignment TIMEOUT ${arg_TIMEOUT})
    set_tests_properties(assignment.${name}.stub PROPERTIES
                         PASS_REGULAR_EXPRESSION "Status: FAILURE!"
                         FAIL_REGULAR_EXPRESSION "CRASHED|SIGSEGV|SIGABRT")
  endif()
  if(EXISTS ${dir}/render.cpp)
    foreach(variant IN LISTS variants)
      set(target assignment-${name}-render)
      if(variant STREQUAL "student")
        set(target assignment-${name}-render-student)
      endif()
      add_executable(${target} ${dir}/render.cpp)
      target_include_directories(${target} PRIVATE ${dir}/${variant} ${dir})
      target_link_libraries(${target} PRIVATE zraka::zraka zraka::compiled ${arg_LIBS})
    endforeach()
  endif()
endfunction()

function(zraka_add_assignments parent)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "LIBS")
  get_filename_component(parent "${parent}" ABSOLUTE)
  file(GLOB children RELATIVE ${parent} CONFIGURE_DEPENDS ${parent}/*)
  list(SORT children COMPARE NATURAL)
  foreach(name IN LISTS children)
    if(IS_DIRECTORY ${parent}/${name} AND name MATCHES "^[0-9][0-9]-[a-z0-9-]+$")
      zraka_add_assignment(${parent}/${name} LIBS ${arg_LIBS})
    endif()
  endforeach()
endfunction()
