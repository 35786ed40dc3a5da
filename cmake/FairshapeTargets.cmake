# Helpers that give every fairshape target the same language level and warnings.

# FAIRSHAPE_TBB: TBB::tbb in a build with TBB (FAIRSHAPE_WITH_TBB), else nothing; a module's
# optimized back end (its *_tbb.cpp) is compiled only with it.
if(FAIRSHAPE_WITH_TBB)
  set(FAIRSHAPE_TBB TBB::tbb)
else()
  set(FAIRSHAPE_TBB "")
endif()

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

# The include root of the build tree: fairshape/<module> -> src/<module> (and reference/), the
# layout `cmake --install` gives <prefix>/include/fairshape/. Every include of fairshape's own
# headers is "fairshape/<module>/<file>.h", in the build as in a project that installed it, so
# no bare "core/..." or "io/..." name can collide with another project's.
set(FAIRSHAPE_INCLUDE_ROOT ${PROJECT_BINARY_DIR}/include)
file(MAKE_DIRECTORY ${FAIRSHAPE_INCLUDE_ROOT}/fairshape)
file(GLOB fairshape_module_dirs LIST_DIRECTORIES true ${PROJECT_SOURCE_DIR}/src/*)
foreach(dir ${fairshape_module_dirs} ${PROJECT_SOURCE_DIR}/reference)
  if(IS_DIRECTORY ${dir})
    get_filename_component(module ${dir} NAME)
    file(CREATE_LINK ${dir} ${FAIRSHAPE_INCLUDE_ROOT}/fairshape/${module} SYMBOLIC)
  endif()
endforeach()

# fairshape_add_library(name SOURCES ... DEPS ... [PRIVATE_DEPS ...] [HEADERS_FROM dir]): static
# library fairshape_<name>, alias fairshape::<name> (the exported name too), headers included as
# "fairshape/<module>/<file>.h"; installed with its module's headers (HEADERS_FROM: the module's
# folder relative to the project, default src/<name>).
function(fairshape_add_library name)
  cmake_parse_arguments(ARG "" "HEADERS_FROM" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(fairshape_${name} STATIC ${ARG_SOURCES})
  add_library(fairshape::${name} ALIAS fairshape_${name})
  set_target_properties(fairshape_${name} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(fairshape_${name} PUBLIC $<BUILD_INTERFACE:${FAIRSHAPE_INCLUDE_ROOT}>
                                                      $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(fairshape_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  fairshape_set_flags(fairshape_${name})
  install(TARGETS fairshape_${name} EXPORT fairshapeTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  if(NOT ARG_HEADERS_FROM)
    file(RELATIVE_PATH ARG_HEADERS_FROM ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  endif()
  get_property(installed GLOBAL PROPERTY FAIRSHAPE_INSTALLED_HEADER_DIRS)
  if(NOT ARG_HEADERS_FROM IN_LIST installed)  # two libraries of one folder install it once
    set_property(GLOBAL APPEND PROPERTY FAIRSHAPE_INSTALLED_HEADER_DIRS ${ARG_HEADERS_FROM})
    get_filename_component(module ${ARG_HEADERS_FROM} NAME)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${ARG_HEADERS_FROM}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fairshape/${module}
            FILES_MATCHING PATTERN "*.h")
  endif()
  set_property(GLOBAL APPEND PROPERTY FAIRSHAPE_LIBRARIES ${name})
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
                       TEST_SPEC ${FAIRSHAPE_CATCH_TEST_SPEC} EXTRA_ARGS --warn NoTests
                       WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()
