# How the library is installed and packaged (docs/design.md → "Packaging"):
#   - a CMake package: find_package(fcl_superellipsoid) → fcl_superellipsoid::fcl_superellipsoid
#     and the opt-in fcl_superellipsoid::interpose
#   - a pkg-config file: pkg-config --cflags --libs fcl_superellipsoid
#   - Debian packages of them and of the Python module: cmake/debian_package.cmake
# Everything here is the install component "dev"; the Python module's files are "python"
# (python/CMakeLists.txt).
include(CMakePackageConfigHelpers)
set(CMAKE_INSTALL_DEFAULT_COMPONENT_NAME dev)

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
