# Meshes through the Gmsh C API (library sa_fem_mesh): generation from meshes/*.geo, .msh reading,
# node-order conversion to VTK, outward boundary faces, quality checks.
find_library(GMSH_LIBRARY gmsh REQUIRED)
find_path(GMSH_INCLUDE_DIR gmshc.h REQUIRED)
add_library(sa_fem_mesh
  ${CMAKE_CURRENT_LIST_DIR}/fem_mesh.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_mesh_block.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_mesh_swept.c)
target_include_directories(sa_fem_mesh PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_include_directories(sa_fem_mesh PRIVATE ${GMSH_INCLUDE_DIR})
# det J checks use the kernels' reference element and quadrature rules (one copy).
target_link_libraries(sa_fem_mesh PUBLIC sa_core m PRIVATE sa_fem_kernels ${GMSH_LIBRARY} Threads::Threads)
