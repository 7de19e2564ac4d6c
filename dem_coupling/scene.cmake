# The FEM-DEM granular scene (dem_scene.h explains the split), included from the top level after
# dem_coupling/ so that sa_dem exists.
#  sa_dem_scene   tables + validation + dlopen of the plugin; linked into softact, no LIGGGHTS.
#  softact_dem    the plugin: the coupled run + the LIGGGHTS bridge objects. It does not link
#                 sa_core/sa_fem: it resolves them from the softact executable (ENABLE_EXPORTS,
#                 whole archives), so logging, errors, timers and signals are the program's own.
find_package(LIGGGHTS REQUIRED) # imported targets are directory-scoped
set(_dem_dir ${CMAKE_SOURCE_DIR}/dem_coupling)
add_library(sa_dem_scene STATIC ${_dem_dir}/dem_scene.c)
target_include_directories(sa_dem_scene PUBLIC ${_dem_dir})
target_link_libraries(sa_dem_scene PUBLIC sa_fem sa_core PRIVATE ${CMAKE_DL_LIBS} m)

add_library(softact_dem MODULE ${_dem_dir}/dem_granular.c ${_dem_dir}/dem_checks.c ${_dem_dir}/dem_iqn.c ${_dem_dir}/dem_piston.c $<TARGET_OBJECTS:sa_dem>)
target_include_directories(softact_dem PRIVATE ${_dem_dir}
  $<TARGET_PROPERTY:sa_core,INTERFACE_INCLUDE_DIRECTORIES>
  $<TARGET_PROPERTY:sa_fem,INTERFACE_INCLUDE_DIRECTORIES>
  $<TARGET_PROPERTY:sa_fem_mesh,INTERFACE_INCLUDE_DIRECTORIES>
  $<TARGET_PROPERTY:sa_fem_kernels,INTERFACE_INCLUDE_DIRECTORIES>)
target_link_libraries(softact_dem PRIVATE LIGGGHTS::LIGGGHTS m)
set_target_properties(softact_dem PROPERTIES LINKER_LANGUAGE CXX)
target_compile_definitions(sa_dem_scene PRIVATE
  SOFTACT_DEM_PLUGIN="$<TARGET_FILE:softact_dem>")
