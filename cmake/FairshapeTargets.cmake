# Helpers that give every fairshape target the same language level and warnings.

function(fairshape_set_flags target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(FAIRSHAPE_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(FAIRSHAPE_NATIVE_ARCH)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()

# fairshape_add_library(name SOURCES ... DEPS ...): static library fairshape_<name>,
# alias fairshape::<name>, headers included as "<module>/<file>.h" from src/.
function(fairshape_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(fairshape_${name} STATIC ${ARG_SOURCES})
  add_library(fairshape::${name} ALIAS fairshape_${name})
  target_include_directories(fairshape_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src
                                                      ${PROJECT_SOURCE_DIR})
  target_link_libraries(fairshape_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  fairshape_set_flags(fairshape_${name})
endfunction()

# fairshape_add_test(name SOURCES ... LABELS ...): one Catch2 executable, each TEST_CASE a ctest.
function(fairshape_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LABELS;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE Catch2::Catch2WithMain ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE
      FAIRSHAPE_SOURCE_DIR="${PROJECT_SOURCE_DIR}" FAIRSHAPE_BINARY_DIR="${PROJECT_BINARY_DIR}")
  fairshape_set_flags(${name})
  # --warn NoTests: a test whose name ctest cannot pass back to Catch (a ';' splits it) would
  # otherwise match nothing and pass without running.
  catch_discover_tests(${name} PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${FAIRSHAPE_TEST_TIMEOUT}
                       EXTRA_ARGS --warn NoTests
                       WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()
