# SPDX-License-Identifier: MIT
# cleave_add_library(<name> [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# Builds every .cpp of the calling folder into static library cleave_<name>, exported as Cleave::<name>.
# Headers are included from the repository root: #include "engine/<layer>/<file>.h".
function(cleave_add_library name)
  cmake_parse_arguments(ARG "" "" "PUBLIC_LIBS;PRIVATE_LIBS;EXTRA_SOURCES" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.h)
  if(NOT sources AND NOT ARG_EXTRA_SOURCES)
    # A header-only layer still gets a real archive so that every layer installs the same way.
    set(stub ${CMAKE_CURRENT_BINARY_DIR}/cleave_${name}_unit.cpp)
    file(WRITE ${stub} "// This layer has no compiled sources yet.\n")
    set(sources ${stub})
  endif()
  add_library(cleave_${name} STATIC ${sources} ${headers} ${ARG_EXTRA_SOURCES})
  add_library(Cleave::${name} ALIAS cleave_${name})
  set_target_properties(cleave_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME cleave_${name})
  target_include_directories(cleave_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<INSTALL_INTERFACE:include/cleave>)
  target_link_libraries(cleave_${name} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  cleave_warnings(cleave_${name})
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  install(FILES ${headers} DESTINATION include/cleave/${rel})
  set_property(GLOBAL APPEND PROPERTY CLEAVE_EXPORTED_TARGETS cleave_${name})
endfunction()

function(cleave_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra $<$<BOOL:${CLEAVE_WERROR}>:-Werror>)
endfunction()

# cleave_add_test_suite(<name> LIBS ...): every *_test.cpp of the calling folder in one GoogleTest
# executable cleave_<name>_tests, registered with ctest.
function(cleave_add_test_suite name)
  cmake_parse_arguments(ARG "" "" "LIBS;ENVIRONMENT" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(NOT sources)
    return()
  endif()
  add_executable(cleave_${name}_tests ${sources})
  target_link_libraries(cleave_${name}_tests PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  target_include_directories(cleave_${name}_tests PRIVATE ${PROJECT_SOURCE_DIR})
  target_compile_definitions(cleave_${name}_tests PRIVATE
    CLEAVE_SOURCE_DIR="${PROJECT_SOURCE_DIR}" CLEAVE_BINARY_DIR="${PROJECT_BINARY_DIR}"
    CLEAVE_BUILD_CONFIGURATION="${CMAKE_BUILD_TYPE}-${CMAKE_CXX_COMPILER_ID}${CLEAVE_COMPILER_MAJOR}-${CMAKE_SYSTEM_PROCESSOR}${CLEAVE_CONFIGURATION_SUFFIX}")
  cleave_warnings(cleave_${name}_tests)
  gtest_discover_tests(cleave_${name}_tests
    DISCOVERY_TIMEOUT 60
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
    PROPERTIES ENVIRONMENT "${CLEAVE_TEST_ENVIRONMENT};${ARG_ENVIRONMENT}" LABELS ${name})
endfunction()
