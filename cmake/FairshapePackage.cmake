# `cmake --install`: the CLI, every library with its headers under include/fairshape/, and a
# CMake package (fairshapeConfig.cmake, its version file, the exported targets) so another
# project can find_package(fairshape) — tested by tests/cli/package_consumer.sh.
include(CMakePackageConfigHelpers)
if(TARGET fairshape)  # the command line (a full build: VTK, CGAL, Ceres and TBB)
  install(TARGETS fairshape RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(FAIRSHAPE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/fairshape)
install(EXPORT fairshapeTargets NAMESPACE fairshape:: DESTINATION ${FAIRSHAPE_CMAKE_DIR})
get_property(FAIRSHAPE_LIBRARIES GLOBAL PROPERTY FAIRSHAPE_LIBRARIES)
list(JOIN FAIRSHAPE_VTK_COMPONENTS " " FAIRSHAPE_VTK_COMPONENTS)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/fairshapeConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/fairshapeConfig.cmake INSTALL_DESTINATION ${FAIRSHAPE_CMAKE_DIR})
# 0.x: a minor version may change the interface, so a request for 0.1 takes 0.1.* only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/fairshapeConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/fairshapeConfig.cmake ${PROJECT_BINARY_DIR}/fairshapeConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FairshapeImportedTargets.cmake
        DESTINATION ${FAIRSHAPE_CMAKE_DIR})
