# Install rules and Debian packages (included at the end of the top CMakeLists.txt).
#
#   cmake --install build --prefix /opt/srp     # bin/srp, share/srp, lib/, include/srp, lib/cmake/srp
#   cmake --build build --target package        # (cpack) srp, srp-data and libsrp-dev .deb in build/
#
# Installed layout (prefix /usr in the .deb):
#   bin/srp                       the executable; it reads its data from ../share/srp
#   share/srp/{datasets,sim,calib} the data of the source tree, same layout (srp/core/DataPaths.h)
#   lib/libsrp_<m>.a, include/srp/<m>/*.h, lib/cmake/srp/   srp::<m> for find_package(srp)
include(CMakePackageConfigHelpers)
# `make install` / CPack install what is built, without building every test first
# (make package builds the srp target, then packages).
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY TRUE)

set(SRP_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/srp)
set(SRP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/srp)

# --- data: what the commands read by default and what the docs' examples use
install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/datasets ${CMAKE_CURRENT_SOURCE_DIR}/sim ${CMAKE_CURRENT_SOURCE_DIR}/calib
        DESTINATION ${SRP_INSTALL_DATADIR} COMPONENT data)
install(FILES ${CMAKE_CURRENT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT data)

# --- CMake package: srp::<module> targets with their third-party dependencies
install(EXPORT srpTargets NAMESPACE srp:: DESTINATION ${SRP_INSTALL_CMAKEDIR} FILE srpTargets.cmake COMPONENT dev)
configure_package_config_file(${CMAKE_CURRENT_SOURCE_DIR}/cmake/srpConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/srpConfig.cmake
  INSTALL_DESTINATION ${SRP_INSTALL_CMAKEDIR}
  PATH_VARS SRP_INSTALL_DATADIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/srpConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/srpConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/srpConfigVersion.cmake
              ${CMAKE_CURRENT_SOURCE_DIR}/cmake/FindVISP.cmake
        DESTINATION ${SRP_INSTALL_CMAKEDIR} COMPONENT dev)

# `cmake --install --strip` (and CPack) also drops the static libraries' debug
# information (CMake strips only executables and shared libraries).
get_property(_srp_modules GLOBAL PROPERTY SRP_MODULES)
foreach(_m ${_srp_modules})
  install(CODE "
    if(CMAKE_INSTALL_DO_STRIP)
      execute_process(COMMAND \"${CMAKE_STRIP}\" --strip-debug
        \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/$<TARGET_FILE_NAME:${_m}>\")
    endif()" COMPONENT dev)
endforeach()

# --- Debian packages: srp (the executable), srp-data (share/srp), libsrp-dev
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME srp)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "srp maintainers <srp@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime data dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME srp)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
# Read at run time, not linked: WordNet's dictionary, Mesa's EGL for off-screen rendering.
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "srp-data (= ${PROJECT_VERSION}), wordnet-base, libegl-mesa0, libgl1-mesa-dri")
set(CPACK_DEBIAN_DATA_PACKAGE_NAME srp-data)
set(CPACK_DEBIAN_DATA_PACKAGE_ARCHITECTURE all)
set(CPACK_DEBIAN_DEV_PACKAGE_NAME libsrp-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
# find_package(srp) finds the libraries srp's static libraries link (srpConfig.cmake).
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
  "srp-data (= ${PROJECT_VERSION}), libeigen3-dev, nlohmann-json3-dev, libsqlite3-dev, libsqlitecpp-dev, \
libvisp-core-dev, libvisp-detection-dev, libvisp-vision-dev, libvisp-mbt-dev, libvisp-klt-dev, libvisp-me-dev, \
libopencv-dev, libopencv-contrib-dev, libmrpt-poses-dev, libmrpt-obs-dev, libmrpt-opengl-dev, libmrpt-img-dev, \
libmrpt-hwdrivers-dev, libegl-dev, libdlib-dev, wordnet-dev, libnlopt-cxx-dev, libsimbody-dev, liburdfdom-dev, \
libapriltag-dev, libdeflate-dev, libassimp-dev, libyaml-cpp-dev, libspdlog-dev, zlib1g-dev")
include(CPack)
