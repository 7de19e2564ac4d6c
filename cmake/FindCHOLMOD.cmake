# FindCHOLMOD.cmake - CHOLMOD sparse Cholesky (SuiteSparse 5.x, no CMake config on Debian 12).
# Defines SuiteSparse::CHOLMOD (with its ordering libraries AMD, CAMD, COLAMD, CCOLAMD, METIS
# and SuiteSparse_config as interface dependencies).
find_package(SuiteSparseConfig REQUIRED)
find_package(METIS REQUIRED)
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY NAMES cholmod)
set(_cholmod_deps "")
foreach(_lib amd camd colamd ccolamd)
  string(TOUPPER ${_lib} _LIB)
  find_library(CHOLMOD_${_LIB}_LIBRARY NAMES ${_lib})
  mark_as_advanced(CHOLMOD_${_LIB}_LIBRARY)
  if(CHOLMOD_${_LIB}_LIBRARY)
    list(APPEND _cholmod_deps ${CHOLMOD_${_LIB}_LIBRARY})
  endif()
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR)
if(CHOLMOD_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_cholmod_deps};METIS::METIS;SuiteSparse::Config")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY)
