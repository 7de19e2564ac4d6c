# FindLIGGGHTS - Debian's libliggghts-dev (no CMake config or pkg-config file is shipped).
# Defines LIGGGHTS::LIGGGHTS (headers in /usr/include/liggghts, library libliggghts, plus MPI,
# since LIGGGHTS' library.h and its C++ headers include mpi.h). The C++ MPI component is not
# needed: LIGGGHTS uses the C bindings only.
find_path(LIGGGHTS_INCLUDE_DIR library.h PATH_SUFFIXES liggghts)
find_library(LIGGGHTS_LIBRARY liggghts)
find_package(MPI COMPONENTS C)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LIGGGHTS REQUIRED_VARS LIGGGHTS_LIBRARY LIGGGHTS_INCLUDE_DIR MPI_C_FOUND)
if(LIGGGHTS_FOUND AND NOT TARGET LIGGGHTS::LIGGGHTS)
  add_library(LIGGGHTS::LIGGGHTS UNKNOWN IMPORTED)
  set_target_properties(LIGGGHTS::LIGGGHTS PROPERTIES
    IMPORTED_LOCATION ${LIGGGHTS_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${LIGGGHTS_INCLUDE_DIR}
    INTERFACE_LINK_LIBRARIES MPI::MPI_C)
endif()
