# Finds GiNaC (and CLN) through pkg-config and defines the imported target GiNaC::GiNaC.
find_package(PkgConfig QUIET REQUIRED)
pkg_check_modules(PC_GINAC QUIET ginac)
find_path(GiNaC_INCLUDE_DIR ginac/ginac.h HINTS ${PC_GINAC_INCLUDE_DIRS})
find_library(GiNaC_LIBRARY ginac HINTS ${PC_GINAC_LIBRARY_DIRS})
find_library(CLN_LIBRARY cln HINTS ${PC_GINAC_LIBRARY_DIRS})
set(GiNaC_VERSION ${PC_GINAC_VERSION})
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(GiNaC REQUIRED_VARS GiNaC_LIBRARY GiNaC_INCLUDE_DIR CLN_LIBRARY
  VERSION_VAR GiNaC_VERSION)
if(GiNaC_FOUND AND NOT TARGET GiNaC::GiNaC)
  add_library(GiNaC::GiNaC UNKNOWN IMPORTED)
  set_target_properties(GiNaC::GiNaC PROPERTIES
    IMPORTED_LOCATION ${GiNaC_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${GiNaC_INCLUDE_DIR}
    INTERFACE_LINK_LIBRARIES ${CLN_LIBRARY})
endif()
mark_as_advanced(GiNaC_INCLUDE_DIR GiNaC_LIBRARY CLN_LIBRARY)
