# FindSuiteSparseConfig.cmake - SuiteSparse_config (shared by every SuiteSparse library).
# Debian's SuiteSparse 5.x ships no CMake config. Defines SuiteSparse::Config.
find_path(SUITESPARSE_CONFIG_INCLUDE_DIR SuiteSparse_config.h PATH_SUFFIXES suitesparse)
find_library(SUITESPARSE_CONFIG_LIBRARY NAMES suitesparseconfig)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparseConfig
  REQUIRED_VARS SUITESPARSE_CONFIG_LIBRARY SUITESPARSE_CONFIG_INCLUDE_DIR)
if(SuiteSparseConfig_FOUND AND NOT TARGET SuiteSparse::Config)
  add_library(SuiteSparse::Config UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::Config PROPERTIES
    IMPORTED_LOCATION "${SUITESPARSE_CONFIG_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${SUITESPARSE_CONFIG_INCLUDE_DIR}")
endif()
mark_as_advanced(SUITESPARSE_CONFIG_INCLUDE_DIR SUITESPARSE_CONFIG_LIBRARY)
