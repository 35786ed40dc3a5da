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
if(FAIRSHAPE_FULL)
  fairshape_require(CLI11 libcli11-dev CONFIG)
endif()
if(FAIRSHAPE_WITH_CERES)
  fairshape_require(Ceres libceres-dev 2.1 CONFIG)
endif()
set(FAIRSHAPE_VTK_COMPONENTS CommonCore CommonDataModel IOXML IOImage RenderingCore RenderingOpenGL2
    RenderingAnnotation RenderingFreeType FiltersCore FiltersGeometry FiltersSources)
if(FAIRSHAPE_WITH_VTK)
  fairshape_require(VTK libvtk9-dev 9.1 COMPONENTS ${FAIRSHAPE_VTK_COMPONENTS})
endif()
fairshape_require(TBB libtbb-dev CONFIG)
if(FAIRSHAPE_FULL)
  fairshape_require(OpenSSL libssl-dev)  # SHA-256 of input files and configs (provenance)
endif()
if(FAIRSHAPE_BUILD_TESTS)
  fairshape_require(Catch2 catch2 2 CONFIG)
endif()
if(FAIRSHAPE_BUILD_BENCHMARKS)
  fairshape_require(benchmark libbenchmark-dev CONFIG)
endif()
if(FAIRSHAPE_WITH_CGAL)
  set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
  fairshape_require(CGAL libcgal-dev CONFIG)
endif()
if(FAIRSHAPE_WITH_VTK)  # Debian's VTK renders through X11
  find_package(X11 QUIET)
  if(NOT X11_FOUND)
    message(FATAL_ERROR "fairshape: X11 not found: install the Debian package 'libx11-dev'")
  endif()
endif()

# SuiteSparse and OpenSubdiv as imported targets (also what an installed fairshape's
# fairshapeConfig.cmake defines for its users).
include(FairshapeImportedTargets)
