# Every dependency comes from a Debian package; a missing one stops configuration with one
# line naming that package (scripts/install-deps.sh installs them all).
macro(fairshape_require package debian_package)
  find_package(${package} ${ARGN} QUIET)
  if(NOT ${package}_FOUND)
    message(FATAL_ERROR "fairshape: ${package} not found: install the Debian package "
                        "'${debian_package}' (or run scripts/install-deps.sh)")
  endif()
endmacro()

fairshape_require(Eigen3 libeigen3-dev 3.4 NO_MODULE)
fairshape_require(yaml-cpp libyaml-cpp-dev CONFIG)
fairshape_require(nlohmann_json nlohmann-json3-dev CONFIG)
fairshape_require(CLI11 libcli11-dev CONFIG)
fairshape_require(Ceres libceres-dev 2.1 CONFIG)
fairshape_require(VTK libvtk9-dev 9.1 COMPONENTS CommonCore CommonDataModel IOXML IOImage
                  RenderingCore RenderingOpenGL2 RenderingAnnotation RenderingFreeType FiltersCore
                  FiltersGeometry FiltersSources)
fairshape_require(TBB libtbb-dev CONFIG)
fairshape_require(OpenSSL libssl-dev)  # SHA-256 of input files and configs (provenance)
if(FAIRSHAPE_BUILD_TESTS)
  fairshape_require(Catch2 catch2 2 CONFIG)
endif()
if(FAIRSHAPE_BUILD_BENCHMARKS)
  fairshape_require(benchmark libbenchmark-dev CONFIG)
endif()
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
fairshape_require(CGAL libcgal-dev CONFIG)
find_package(X11 QUIET)
if(NOT X11_FOUND)
  message(FATAL_ERROR "fairshape: X11 not found: install the Debian package 'libx11-dev'")
endif()

# SuiteSparse 5 ships no CMake package: imported targets from its headers and libraries.
find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
if(NOT SUITESPARSE_INCLUDE_DIR)
  message(FATAL_ERROR "fairshape: SuiteSparse (cholmod.h) not found: install the Debian package "
                      "'libsuitesparse-dev' (or run scripts/install-deps.sh)")
endif()
foreach(part cholmod spqr umfpack)
  string(TOUPPER ${part} PART)
  find_library(SUITESPARSE_${PART}_LIBRARY ${part})
  if(NOT SUITESPARSE_${PART}_LIBRARY)
    message(FATAL_ERROR "fairshape: SuiteSparse library '${part}' not found: install the Debian "
                        "package 'libsuitesparse-dev'")
  endif()
  add_library(SuiteSparse::${PART}_fs INTERFACE IMPORTED)
  target_include_directories(SuiteSparse::${PART}_fs SYSTEM INTERFACE ${SUITESPARSE_INCLUDE_DIR})
  target_link_libraries(SuiteSparse::${PART}_fs INTERFACE ${SUITESPARSE_${PART}_LIBRARY})
endforeach()

# OpenSubdiv's Debian CMake config is broken (it names static libraries that are not shipped):
# an imported target from its headers and the shared libosdCPU. subdivision uses it for exact
# limit evaluation at surface points (Bfr); the conformance tests use it as an oracle.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h)
find_library(OPENSUBDIV_CPU_LIBRARY osdCPU)
if(NOT OPENSUBDIV_INCLUDE_DIR OR NOT OPENSUBDIV_CPU_LIBRARY)
  message(FATAL_ERROR "fairshape: OpenSubdiv (opensubdiv/far/topologyRefiner.h, libosdCPU) not found: "
                      "install the Debian package 'libosd-dev' (or run scripts/install-deps.sh)")
endif()
add_library(OpenSubdiv::cpu INTERFACE IMPORTED)
target_include_directories(OpenSubdiv::cpu SYSTEM INTERFACE ${OPENSUBDIV_INCLUDE_DIR})
target_link_libraries(OpenSubdiv::cpu INTERFACE ${OPENSUBDIV_CPU_LIBRARY})
