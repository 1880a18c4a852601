# What `cmake --install build --prefix P` puts under P (docs/install.md):
#   bin/fabmesh                                the program (pipeline/CMakeLists.txt)
#   lib/libfabmesh.so.MAJOR.MINOR, .so         the library, fabmesh::fabmesh
#   include/fabmesh/*.h                        its public headers (version.h generated, errors.h geometry/core's)
#   lib/cmake/fabmesh/                         the CMake package: find_package(fabmesh 0.4 CONFIG)
#   lib/pkgconfig/fabmesh.pc                   the pkg-config file
#   lib/python3/dist-packages/fabmesh*.so      the Python module and its fabmesh.pyi
#   share/fabmesh/examples/                    the example designs (pipeline/CMakeLists.txt)
#   share/fabmesh/studio/                      the studio's page and three.js (pipeline/CMakeLists.txt)
#   share/doc/fabmesh/                         README.md, docs/, examples/consumer/, configs/examples (a link)
#   share/man/man1/fabmesh.1                   the manual page
#   share/bash-completion/completions/fabmesh  bash completion of commands and options
# Every path is relative to the prefix, so the same build installs anywhere
# (`--prefix` at install time, /usr in the Debian package). The pipeline's
# static libraries are linked into libfabmesh and the program; they are not
# installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(FABMESH_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/fabmesh CACHE STRING
    "Where the CMake package (fabmeshConfig.cmake) is installed, relative to the prefix")
# Debian's layout: /usr/bin/python3 imports from /usr/lib/python3/dist-packages.
set(FABMESH_INSTALL_PYTHONDIR lib/python3/dist-packages CACHE STRING
    "Where the Python module is installed, relative to the prefix")

# Installed modules that link libfabmesh find it relative to themselves,
# wherever the prefix is. The program links none of the prefix's libraries
# (the pipeline is linked in, its optional modules are loaded by their paths:
# io/module.h), so it has no run path at all.
#
# A module that links libfabmesh is built with a run path of its own making,
# relative to itself in the build tree, and `cmake --install` changes it to
# the install one. CMake's own way (a build run path rewritten at install)
# ends the build one with an empty entry, and pads it with more when the
# install one is longer: the loader takes each for the working folder, and
# would load anyone's library of the same name from wherever the module is
# imported. So the build run path is made long enough with "/." segments
# (the same folder), never with empty entries, and is changed in place.
function(fabmesh_origin_rpath target from_dir)
  file(RELATIVE_PATH rel ${CMAKE_INSTALL_PREFIX}/${from_dir} ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR})
  string(REGEX REPLACE "/$" "" rel "${rel}")
  set(install_rpath "$ORIGIN/${rel}")
  get_target_property(built_in ${target} LIBRARY_OUTPUT_DIRECTORY)
  get_target_property(lib_in fabmesh_lib LIBRARY_OUTPUT_DIRECTORY)
  if(NOT lib_in)
    get_target_property(lib_in fabmesh_lib BINARY_DIR)
  endif()
  file(RELATIVE_PATH build_rel ${built_in} ${lib_in})
  string(REGEX REPLACE "/$" "" build_rel "${build_rel}")
  set(build_rpath "$ORIGIN/${build_rel}")
  string(LENGTH "${install_rpath}" install_length)
  string(LENGTH "${build_rpath}" build_length)
  while(build_length LESS install_length)
    string(APPEND build_rpath "/.")
    string(LENGTH "${build_rpath}" build_length)
  endwhile()
  set_target_properties(${target} PROPERTIES BUILD_WITH_INSTALL_RPATH ON INSTALL_RPATH "${build_rpath}")
  install(CODE "file(RPATH_CHANGE FILE \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${from_dir}/$<TARGET_FILE_NAME:${target}>\"
  OLD_RPATH \"${build_rpath}\" NEW_RPATH \"${install_rpath}\")")
endfunction()

# --- the library, its headers and its CMake package ---
# (fabmesh_lib's INSTALL_INTERFACE include folder is the installed include/.)
install(TARGETS fabmesh_lib EXPORT fabmeshTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/api/include/fabmesh/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fabmesh
  FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/api/include/fabmesh/version.h ${PROJECT_BINARY_DIR}/api/include/fabmesh/errors.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fabmesh)

install(EXPORT fabmeshTargets
  NAMESPACE fabmesh::
  FILE fabmeshTargets.cmake
  DESTINATION ${FABMESH_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/fabmeshConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake/fabmeshConfig.cmake
  INSTALL_DESTINATION ${FABMESH_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the interface, so 0.4 accepts 0.4.y only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/fabmeshConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/fabmeshConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake/fabmeshConfigVersion.cmake
  DESTINATION ${FABMESH_INSTALL_CMAKEDIR})

# --- pkg-config: relocatable, the prefix found from the .pc file's own folder ---
file(RELATIVE_PATH FABMESH_PC_TO_PREFIX ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig
     ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" FABMESH_PC_TO_PREFIX "${FABMESH_PC_TO_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/fabmesh.pc.in ${PROJECT_BINARY_DIR}/cmake/fabmesh.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/cmake/fabmesh.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# --- the Python module, beside its type stub ---
if(TARGET fabmesh_python)
  install(TARGETS fabmesh_python LIBRARY DESTINATION ${FABMESH_INSTALL_PYTHONDIR})
  fabmesh_origin_rpath(fabmesh_python ${FABMESH_INSTALL_PYTHONDIR})
  install(FILES ${PROJECT_BINARY_DIR}/python/fabmesh.pyi DESTINATION ${FABMESH_INSTALL_PYTHONDIR})
endif()

# --- documentation, manual page, shell completion ---
# The README and docs/ keep the repository's layout under DOCDIR, so that
# their links resolve where they are installed: README.md, docs/*.md,
# examples/consumer/ (a complete program), and configs/examples, a link to
# the installed example designs (DATADIR/fabmesh/examples).
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs
  PATTERN man EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/consumer/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples/consumer)
file(RELATIVE_PATH FABMESH_DOC_TO_EXAMPLES ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DOCDIR}/configs
     ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/fabmesh/examples)
install(CODE "
  set(configs \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DOCDIR}/configs\")
  file(MAKE_DIRECTORY \"\${configs}\")
  file(REMOVE \"\${configs}/examples\")
  file(CREATE_LINK \"${FABMESH_DOC_TO_EXAMPLES}\" \"\${configs}/examples\" SYMBOLIC)
  message(STATUS \"Installing: \${configs}/examples -> ${FABMESH_DOC_TO_EXAMPLES}\")")
install(FILES ${PROJECT_SOURCE_DIR}/docs/man/fabmesh.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${PROJECT_SOURCE_DIR}/completion/fabmesh.bash
  DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
  RENAME fabmesh)
