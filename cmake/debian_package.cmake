# Debian packages (cpack -G DEB in the build tree; configure with -DCMAKE_INSTALL_PREFIX=/usr for
# Debian's multiarch library folder), one per install component:
#   libfcl-superellipsoid-dev     the library, headers, CMake and pkg-config files (component
#                                 "dev"). Its dependencies are Debian's development packages of
#                                 what the headers and the CMake package need; the shared
#                                 library's own run-time dependencies are computed by
#                                 dpkg-shlibdeps.
#   python3-fcl-superellipsoid    the Python module in /usr/lib/python3/dist-packages (component
#                                 "python-deb"), when it is built. It needs the library's package
#                                 of the same version, numpy, and the Python version it was built
#                                 for.
set(CPACK_PACKAGE_VENDOR "fcl-superellipsoid")
set(CPACK_PACKAGE_CONTACT "fcl-superellipsoid developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_COMPONENTS_ALL dev)

set(CPACK_DEBIAN_DEV_PACKAGE_NAME "libfcl-superellipsoid-dev")
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
  "libfcl-dev (>= 0.7), libeigen3-dev (>= 3.3), libtbb-dev, libhwy-dev (>= 1.0)")
set(CPACK_DEBIAN_DEV_PACKAGE_SHLIBDEPS ON)
set(CPACK_COMPONENT_DEV_DESCRIPTION
  "A superellipsoid collision geometry for FCL (the Flexible Collision Library):\na Superellipsoid shape for FCL's collision objects and broadphase managers,\nexact point-distance solvers, FCL function-table entries, a drop-in front end\nand batched SIMD queries. C++17 headers, library, CMake and pkg-config files.")

if(TARGET fse_python)
  list(APPEND CPACK_COMPONENTS_ALL python-deb)
  set(CPACK_DEBIAN_PYTHON-DEB_PACKAGE_NAME "python3-fcl-superellipsoid")
  set(CPACK_DEBIAN_PYTHON-DEB_PACKAGE_SECTION python)
  set(python_version ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR})
  math(EXPR python_next "${Python3_VERSION_MINOR} + 1")
  # The module's own links are libc, libstdc++ and the library: the first two come with the
  # library's package, which dpkg-shlibdeps cannot name for a package built beside it.
  set(CPACK_DEBIAN_PYTHON-DEB_PACKAGE_SHLIBDEPS OFF)
  set(CPACK_DEBIAN_PYTHON-DEB_PACKAGE_DEPENDS
    "libfcl-superellipsoid-dev (= ${PROJECT_VERSION}), python3 (>= ${python_version}), python3 (<< ${Python3_VERSION_MAJOR}.${python_next}), python3-numpy")
  set(CPACK_COMPONENT_PYTHON-DEB_DESCRIPTION
    "The superellipsoid collision geometry for FCL, from Python and numpy:\nthe module fcl_superellipsoid (signed distances of point arrays, pair\nqueries against FCL's shapes), with type stubs.")
endif()
include(CPack)
