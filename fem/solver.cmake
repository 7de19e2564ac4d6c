# FEM solver, assembly, linear solvers and the module glue (library sa_fem).
# CHOLMOD/UMFPACK/METIS come from Debian's SuiteSparse 5.x without CMake configs: see
# cmake/FindCHOLMOD.cmake, FindUMFPACK.cmake, FindMETIS.cmake, FindOpenBLAS.cmake.
find_package(CHOLMOD REQUIRED)
find_package(UMFPACK REQUIRED)
find_package(METIS REQUIRED)
find_package(OpenBLAS REQUIRED)
find_package(OpenMP COMPONENTS C)
set(_sa_fem_sources
  ${CMAKE_CURRENT_LIST_DIR}/fem_linsolve.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_blas.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_solver.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_dofmap.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_assemble.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_newton.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_gmres.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_continuation.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_dynamics.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_checkpoint.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_bending.c
  ${CMAKE_CURRENT_LIST_DIR}/fem_contact.c)
foreach(_f fem_actuator.c fem_coupling.c fem_scene.c fem_fill.c fem_triaxial.c fem_footing.c fem_mc_scene.c)
  if(EXISTS ${CMAKE_CURRENT_LIST_DIR}/${_f})
    list(APPEND _sa_fem_sources ${CMAKE_CURRENT_LIST_DIR}/${_f})
  endif()
endforeach()
add_library(sa_fem ${_sa_fem_sources})
target_include_directories(sa_fem PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(sa_fem
  PUBLIC sa_fem_kernels sa_fem_mesh sa_core
  PRIVATE SuiteSparse::UMFPACK SuiteSparse::CHOLMOD METIS::METIS OpenBLAS::OpenBLAS m)
if(OpenMP_C_FOUND)
  # Element loop: coloured, 2 threads by default (docs/benchmarks.md has the measured gain).
  target_link_libraries(sa_fem PRIVATE OpenMP::OpenMP_C)
endif()
