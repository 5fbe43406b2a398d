# The build tree as an installation: share/fastron beside the built programs, so that they find
# the data at run time as installed ones do (fastron/core/install_location.h), then the install
# rules and the CMake package (find_package(fastron CONFIG)).
include(CMakePackageConfigHelpers)

set(FASTRON_SHARE_SUBDIR ${CMAKE_INSTALL_DATADIR}/fastron)
set(build_share ${PROJECT_BINARY_DIR}/${FASTRON_SHARE_SUBDIR})
file(MAKE_DIRECTORY ${build_share})
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/data/robots ${build_share}/robots SYMBOLIC)
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/data/scenes ${build_share}/scenes SYMBOLIC)
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/scripts ${build_share}/scripts SYMBOLIC)

install(DIRECTORY include/fastron DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS fastron_build_options ${FASTRON_INSTALLED_LAYERS}
  EXPORT fastronTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS fastron RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY data/robots data/scenes DESTINATION ${FASTRON_SHARE_SUBDIR})
install(FILES scripts/plot_along_path.py scripts/plot_demo.py scripts/plot_experiments.py
  DESTINATION ${FASTRON_SHARE_SUBDIR}/scripts)

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/fastron)
install(EXPORT fastronTargets NAMESPACE fastron:: DESTINATION ${config_dir})
configure_package_config_file(cmake/fastronConfig.cmake.in
  ${PROJECT_BINARY_DIR}/fastronConfig.cmake INSTALL_DESTINATION ${config_dir})
# The ABI changes with every minor version until 1.0.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/fastronConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/fastronConfig.cmake
  ${PROJECT_BINARY_DIR}/fastronConfigVersion.cmake DESTINATION ${config_dir})
