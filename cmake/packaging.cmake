# How the library is installed and packaged (docs/design.md → "Packaging"):
#   - a CMake package: find_package(fcl_superellipsoid) → fcl_superellipsoid::fcl_superellipsoid
#     and the opt-in fcl_superellipsoid::interpose
#   - a pkg-config file: pkg-config --cflags --libs fcl_superellipsoid
#   - a Debian package of both: cpack -G DEB in the build tree (configure with
#     -DCMAKE_INSTALL_PREFIX=/usr for Debian's multiarch library folder)
include(CMakePackageConfigHelpers)

install(TARGETS fcl_superellipsoid fcl_superellipsoid_interpose EXPORT fcl_superellipsoidTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/fcl_superellipsoid
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_BINARY_DIR}/include/fcl_superellipsoid/export.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fcl_superellipsoid)

# CMake package.
set(FSE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/fcl_superellipsoid)
install(EXPORT fcl_superellipsoidTargets NAMESPACE fcl_superellipsoid::
  DESTINATION ${FSE_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/fcl_superellipsoidConfig.cmake.in
  ${PROJECT_BINARY_DIR}/fcl_superellipsoidConfig.cmake
  INSTALL_DESTINATION ${FSE_CMAKE_DIR})
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/fcl_superellipsoidConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/fcl_superellipsoidConfig.cmake
  ${PROJECT_BINARY_DIR}/fcl_superellipsoidConfigVersion.cmake
  DESTINATION ${FSE_CMAKE_DIR})

# pkg-config. The prefix is found from the .pc file's own place (${pcfiledir}), so the file is
# right wherever the tree is installed: --prefix at install time, a Debian package, a copy.
file(RELATIVE_PATH FSE_PC_TO_PREFIX "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
if(BUILD_SHARED_LIBS)
  set(FSE_PC_PRIVATE_LIBS "")
else()
  set(FSE_PC_PRIVATE_LIBS "-ltbb -lhwy")  # a static library's private links
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/fcl_superellipsoid.pc.in
  ${PROJECT_BINARY_DIR}/fcl_superellipsoid.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/fcl_superellipsoid.pc
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# Debian package (cpack -G DEB): the library, headers, CMake and pkg-config files, in one
# development package. Its dependencies are Debian's development packages of what the headers
# and the CMake package need; the shared library's own run-time dependencies are computed by
# dpkg-shlibdeps.
set(CPACK_PACKAGE_NAME "libfcl-superellipsoid-dev")
set(CPACK_PACKAGE_VENDOR "fcl-superellipsoid")
set(CPACK_PACKAGE_CONTACT "fcl-superellipsoid developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libfcl-dev (>= 0.7), libeigen3-dev (>= 3.3), libtbb-dev, libhwy-dev (>= 1.0)")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
  "A superellipsoid collision geometry for FCL (the Flexible Collision Library):\n a Superellipsoid shape for FCL's collision objects and broadphase managers,\n exact point-distance solvers, FCL function-table entries, a drop-in front end\n and batched SIMD queries. C++17 headers, library, CMake and pkg-config files.")
include(CPack)
