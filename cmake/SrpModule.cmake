# srp_add_module(NAME <m> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...]
#                [TEST_SOURCES ...] [TEST_DEPS ...] [TEST_LABELS ...])
#
# Defines the static library srp_<m> (alias srp::<m>) with headers under
# libs/<m>/include/srp/<m>/, and one GoogleTest executable srp_<m>_tests whose
# cases are registered in CTest. The module is appended to the global property
# SRP_MODULES, which apps/srp links.
function(srp_add_module)
  cmake_parse_arguments(M "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;TEST_SOURCES;TEST_DEPS;TEST_LABELS" ${ARGN})
  set(target srp_${M_NAME})
  add_library(${target} STATIC ${M_SOURCES})
  add_library(srp::${M_NAME} ALIAS ${target})
  target_include_directories(${target} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${target} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  target_compile_definitions(${target} PRIVATE
    SRP_SOURCE_DIR="${SRP_SOURCE_DIR}" SRP_DATASETS_DIR="${SRP_DATASETS_DIR}" SRP_SIM_DIR="${SRP_SIM_DIR}")
  set_property(GLOBAL APPEND PROPERTY SRP_MODULES ${target})

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
