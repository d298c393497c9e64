# Finds the ViSP module libraries installed by Debian's libvisp-<module>-dev
# packages (the VISPConfig.cmake ships only with the libvisp-dev meta package,
# which would pull in every module). Defines imported targets visp::<module>
# for the requested COMPONENTS (core, detection, vision, io, ...).
find_path(VISP_INCLUDE_DIR visp3/core/vpConfig.h PATH_SUFFIXES x86_64-linux-gnu ${CMAKE_LIBRARY_ARCHITECTURE})
set(VISP_FOUND TRUE)
if(NOT VISP_INCLUDE_DIR)
  set(VISP_FOUND FALSE)
endif()
foreach(comp ${VISP_FIND_COMPONENTS})
  string(REPLACE "visp_" "" comp ${comp})
  find_library(VISP_${comp}_LIBRARY NAMES visp_${comp})
  if(VISP_${comp}_LIBRARY AND VISP_FOUND)
    if(NOT TARGET visp::${comp})
      add_library(visp::${comp} SHARED IMPORTED)
      set_target_properties(visp::${comp} PROPERTIES
        IMPORTED_LOCATION ${VISP_${comp}_LIBRARY}
        INTERFACE_INCLUDE_DIRECTORIES ${VISP_INCLUDE_DIR})
    endif()
  else()
    set(VISP_FOUND FALSE)
    message(STATUS "ViSP module '${comp}' not found: install libvisp-${comp}-dev (scripts/install-deps.sh)")
  endif()
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(VISP REQUIRED_VARS VISP_INCLUDE_DIR VISP_FOUND)
