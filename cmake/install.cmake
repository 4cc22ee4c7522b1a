# make install: library, headers, CMake package config and pkg-config file under the prefix.
include(CMakePackageConfigHelpers)
install(TARGETS geomint geomint_static EXPORT geomintTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS geomint_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/geomint DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT geomintTargets NAMESPACE geomint:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geomint)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/geomintConfig.cmake.in
  ${PROJECT_BINARY_DIR}/geomintConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geomint)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/geomintConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/geomintConfig.cmake ${PROJECT_BINARY_DIR}/geomintConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geomint)
configure_file(${PROJECT_SOURCE_DIR}/cmake/geomint.pc.in ${PROJECT_BINARY_DIR}/geomint.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/geomint.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
