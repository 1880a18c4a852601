# The Debian package: `cpack -G DEB` in the build folder makes
# fabmesh_VERSION_ARCH.deb installing under /usr what `cmake --install` installs
# (cmake/fabmeshInstall.cmake). Its Depends are computed from what the program,
# the library and the Python module link (dpkg-shlibdeps).
set(CPACK_PACKAGE_NAME fabmesh)
set(CPACK_PACKAGE_VENDOR fabmesh)
set(CPACK_PACKAGE_CONTACT "fabmesh maintainers <fabmesh@localhost>")
# The synopsis; CPACK_DEBIAN_PACKAGE_DESCRIPTION is the long description.
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "parametric product designs to fabrication-ready meshes")
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "fabmesh samples exact curve models, builds vessels, moulds, countertops and
surface shells, proves every mesh is a closed, outward, self-intersection-free
manifold, and writes STL, 3MF, glTF, Draco and cutting files.
.
This package holds the fabmesh program, the C++ library (fabmesh::fabmesh,
with its headers, CMake package and pkg-config file), the Python module, the
example designs, the documentation, the manual page and bash completion.")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# Without the debug information of a RelWithDebInfo build (a tenth of the size).
set(CPACK_STRIP_FILES ON)
set(CPACK_SOURCE_GENERATOR "")

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # fabmesh_0.4.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libfabmesh is in the package itself: dpkg-shlibdeps looks it up there, and the
# package gets the ldconfig trigger and shlibs file of a shared library.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR}/api)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
# lib3mf is loaded with dlopen when a 3MF file is written or read
# (io/mesh/threemf.cpp), so dpkg-shlibdeps cannot see it: named here. The
# modules in LIBDIR/fabmesh (OpenCASCADE, cpp-httplib) are ELF files of the
# package, so their libraries are found as the program's are.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "lib3mf1")
# The Python module is built for one Python version and imports numpy when
# used; the program and the library need neither, so these are recommended.
if(TARGET fabmesh_python AND Python3_VERSION_MAJOR)
  math(EXPR FABMESH_PYTHON_NEXT_MINOR "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
      "python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}~), python3 (<< ${Python3_VERSION_MAJOR}.${FABMESH_PYTHON_NEXT_MINOR}), python3-numpy")
endif()

include(CPack)
