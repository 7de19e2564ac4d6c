# Element and material kernels of the FEM solver (library sa_fem_kernels).
add_library(sa_fem_kernels
  ${CMAKE_CURRENT_LIST_DIR}/fem_material.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_law.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_element.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_kernel_quad.c)
target_include_directories(sa_fem_kernels PUBLIC ${CMAKE_CURRENT_LIST_DIR})
find_package(Threads REQUIRED)
target_link_libraries(sa_fem_kernels PUBLIC sa_core m Threads::Threads)
# Mohr-Coulomb finite-strain elastoplasticity kernel (docs/mohr_coulomb.md)
target_sources(sa_fem_kernels PRIVATE ${CMAKE_CURRENT_LIST_DIR}/fem_mohr_coulomb.c)
