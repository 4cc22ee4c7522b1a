# make install: library, headers, CMake package config and pkg-config file under the prefix.
include(CMakePackageConfigHelpers)
# Installed binaries find the installed library without LD_LIBRARY_PATH, wherever the prefix is
# (relative RPATH, so a moved prefix keeps working).
set_target_properties(geomint PROPERTIES INSTALL_RPATH "$ORIGIN")
set_target_properties(geomint_cli PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
# The static library's users link SuiteSparse themselves: with SuiteSparse found by pkg-config the
# build links it as a build-only target, so name its libraries for the installed package.
if(SUITESPARSE_FOUND)
  foreach(lib ${SUITESPARSE_LINK_LIBRARIES})
    target_link_libraries(geomint_static PUBLIC $<INSTALL_INTERFACE:${lib}>)
  endforeach()
endif()
install(TARGETS geomint geomint_static EXPORT geomintTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS geomint_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/geomint DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT geomintTargets NAMESPACE geomint:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geomint)
set(GM_CONFIG_OPENMP ${OpenMP_C_FOUND})
if(NOT GM_CONFIG_OPENMP)
  set(GM_CONFIG_OPENMP FALSE)
endif()
set(GM_CONFIG_MPI ${GM_MPI})
if(NOT GM_CONFIG_MPI)
  set(GM_CONFIG_MPI FALSE)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/geomintConfig.cmake.in
  ${PROJECT_BINARY_DIR}/geomintConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geomint)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/geomintConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/geomintConfig.cmake ${PROJECT_BINARY_DIR}/geomintConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geomint)
# pkg-config: what a static link needs beyond lapacke (SuiteSparse, OpenMP's runtime, libm), the
# prefix relative to the .pc file, and an rpath to libdir outside /usr.
file(RELATIVE_PATH GM_PC_PREFIX_FROM_PCDIR "${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig"
     "${CMAKE_INSTALL_PREFIX}")
string(REGEX REPLACE "/$" "" GM_PC_PREFIX_FROM_PCDIR "${GM_PC_PREFIX_FROM_PCDIR}")
set(GM_PC_REQUIRES_PRIVATE " harminv")
string(APPEND GM_PC_REQUIRES_PRIVATE " fftw3 libcjson")
if(GM_MPI)
  string(APPEND GM_PC_REQUIRES_PRIVATE " mpi-c")
endif()
set(GM_PC_LIBS_PRIVATE "")
if(SUITESPARSE_FOUND)
  string(APPEND GM_PC_REQUIRES_PRIVATE " cholmod umfpack")
else()
  set(GM_PC_LIBS_PRIVATE "-lumfpack -lcholmod -lsuitesparseconfig")
endif()
if(OpenMP_C_FOUND)
  foreach(lib ${OpenMP_C_LIB_NAMES})
    string(APPEND GM_PC_LIBS_PRIVATE " -l${lib}")
  endforeach()
endif()
string(APPEND GM_PC_LIBS_PRIVATE " -lm")
foreach(lib ${CMAKE_DL_LIBS})
  string(APPEND GM_PC_LIBS_PRIVATE " -l${lib}")
endforeach()
string(STRIP "${GM_PC_LIBS_PRIVATE}" GM_PC_LIBS_PRIVATE)
set(GM_PC_RPATH "")
if(NOT CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  set(GM_PC_RPATH " -Wl,-rpath,\${libdir}")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/geomint.pc.in ${PROJECT_BINARY_DIR}/geomint.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/geomint.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
