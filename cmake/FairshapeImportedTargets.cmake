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

# PETSc (the `petsc_*` solvers): Debian's petsc-dev has a pkg-config file but no CMake
# package, and its headers include mpi.h without adding OpenMPI's include path.
if(FAIRSHAPE_WITH_PETSC OR fairshape_WITH_PETSC)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(PETSC QUIET IMPORTED_TARGET PETSc)
  endif()
  set(MPI_CXX_SKIP_MPICXX TRUE)  # the C API only (the C++ bindings are deprecated)
  find_package(MPI QUIET COMPONENTS CXX)
  if(NOT PETSC_FOUND OR NOT MPI_CXX_FOUND)
    message(FATAL_ERROR "fairshape: PETSc (pkg-config PETSc) with MPI not found: install the Debian packages "
                        "'petsc-dev libhypre-dev openmpi-bin' (or run scripts/install-deps.sh), or configure with "
                        "-DFAIRSHAPE_WITH_PETSC=OFF")
  endif()
  add_library(PETSc::petsc_fs INTERFACE IMPORTED)
  target_link_libraries(PETSc::petsc_fs INTERFACE PkgConfig::PETSC MPI::MPI_CXX)
endif()
