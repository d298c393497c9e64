# srp_add_module(NAME <m> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...]
#                [TEST_SOURCES ...] [TEST_DEPS ...] [TEST_LABELS ...])
#
# Defines the static library srp_<m> (alias srp::<m>, exported as srp::<m>) with
# headers under libs/<m>/include/srp/<m>/, installed with its headers into the
# export set srpTargets, and one GoogleTest executable srp_<m>_tests whose cases
# are registered in CTest. The module is appended to the global property
# SRP_MODULES, which apps/srp links.
#
# The libraries find their data at run time (srp/core/DataPaths.h): no source path
# is compiled into them. Tests may use SRP_SOURCE_DIR, SRP_DATASETS_DIR, SRP_SIM_DIR.
function(srp_add_module)
  cmake_parse_arguments(M "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;TEST_SOURCES;TEST_DEPS;TEST_LABELS" ${ARGN})
  set(target srp_${M_NAME})
  add_library(${target} STATIC ${M_SOURCES})
  add_library(srp::${M_NAME} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${M_NAME})
  set_property(GLOBAL APPEND PROPERTY SRP_MODULES ${target})
  install(TARGETS ${target} EXPORT srpTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)

  if(SRP_BUILD_TESTS AND M_TEST_SOURCES)
    set(test_target srp_${M_NAME}_tests)
    add_executable(${test_target} ${M_TEST_SOURCES})
    target_link_libraries(${test_target} PRIVATE ${target} ${M_TEST_DEPS} GTest::gtest GTest::gtest_main)
    target_compile_definitions(${test_target} PRIVATE
      SRP_SOURCE_DIR="${SRP_SOURCE_DIR}" SRP_DATASETS_DIR="${SRP_DATASETS_DIR}" SRP_SIM_DIR="${SRP_SIM_DIR}"
      SRP_BINARY_DIR="${CMAKE_BINARY_DIR}")
    set(labels ${M_NAME} ${M_TEST_LABELS})
    gtest_discover_tests(${test_target}
      WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
      PROPERTIES LABELS "${labels}"
      DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
