# Imported targets for the two dependencies whose Debian packages have no usable CMake
# package: SuiteSparse (SuiteSparse::<PART>_fs) and OpenSubdiv (OpenSubdiv::cpu). Included by
# the build (FairshapeDependencies.cmake) and installed beside fairshapeConfig.cmake, whose
# exported targets name them.
if(TARGET OpenSubdiv::cpu)
  return()  # defined already (a project that includes fairshape twice)
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
