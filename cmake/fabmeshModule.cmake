# fabmesh_add_module(TARGET FILE_NAME LAYER SOURCE...): one of fabmesh's own modules
# (io/module.h): a shared object loaded with dlopen the first time a run needs
# it, so that other runs do not load the libraries it links. Built to
# lib/fabmesh of the build folder and installed to LIBDIR/fabmesh, where
# find_module looks for FILE_NAME.so; it exports only its entry function. It
# includes what LAYER (io, pipeline) may include.
include(GNUInstallDirs)
function(fabmesh_add_module target file_name layer)
  add_library(${target} MODULE ${ARGN})
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME ${file_name}
    PREFIX ""
    LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib/fabmesh
    CXX_VISIBILITY_PRESET hidden)
  target_include_directories(${target} PRIVATE ${PROJECT_BINARY_DIR}/layers/${layer})
  target_link_libraries(${target} PRIVATE fabmesh_options)
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/fabmesh)
endfunction()
