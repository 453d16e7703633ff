# SPDX-License-Identifier: MIT
# cleave_add_library(<name> [HEADER_ONLY] [COMPONENT <package component>] [PUBLIC_LIBS ...]
#                    [PRIVATE_LIBS ...] [INTERNAL_HEADERS <file.h> ...])
# Builds every .cpp of the calling folder into static library cleave_<name>, exported as Cleave::<name>
# in the package component COMPONENT (default engine; see cmake/CleavePackage.cmake). HEADER_ONLY: an
# INTERFACE library instead (the base layer). Every layer but base links Cleave::base.
# Headers are included as <cleave/<name>/<file>.h>, in the build tree as when installed: the build
# tree's include/cleave/<name> is a link to the folder. INTERNAL_HEADERS are not installed (headers
# that name a private dependency, or helpers of the folder's own sources); neither are the headers
# of sub-folders (detail/).
function(cleave_add_library name)
  cmake_parse_arguments(ARG "HEADER_ONLY" "COMPONENT" "PUBLIC_LIBS;PRIVATE_LIBS;EXTRA_SOURCES;INTERNAL_HEADERS" ${ARGN})
  if(NOT ARG_COMPONENT)
    set(ARG_COMPONENT engine)
  endif()
  if(ARG_HEADER_ONLY)
    cleave_add_header_library(${name} ${ARG_COMPONENT})
    return()
  endif()
  if(NOT name STREQUAL "base")
    list(APPEND ARG_PUBLIC_LIBS cleave_base)
  endif()
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
  cleave_include_link(${name} ${CMAKE_CURRENT_SOURCE_DIR})
  target_include_directories(cleave_${name} PUBLIC
    $<BUILD_INTERFACE:${CLEAVE_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:include>)
  target_link_libraries(cleave_${name} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  cleave_warnings(cleave_${name})
  set(installed)
  foreach(header IN LISTS headers)
    get_filename_component(file ${header} NAME)
    if(NOT file IN_LIST ARG_INTERNAL_HEADERS)
      list(APPEND installed ${header})
    endif()
  endforeach()
  install(FILES ${installed} DESTINATION include/cleave/${name} COMPONENT ${ARG_COMPONENT})
  set_property(GLOBAL APPEND PROPERTY CLEAVE_TARGETS_${ARG_COMPONENT} cleave_${name})
endfunction()

# The INTERFACE library cleave_<name> of a folder without sources: its headers, installed in component.
function(cleave_add_header_library name component)
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.h)
  add_library(cleave_${name} INTERFACE)
  add_library(Cleave::${name} ALIAS cleave_${name})
  set_target_properties(cleave_${name} PROPERTIES EXPORT_NAME ${name})
  cleave_include_link(${name} ${CMAKE_CURRENT_SOURCE_DIR})
  target_include_directories(cleave_${name} INTERFACE
    $<BUILD_INTERFACE:${CLEAVE_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:include>)
  install(FILES ${headers} DESTINATION include/cleave/${name} COMPONENT ${component})
  set_property(GLOBAL APPEND PROPERTY CLEAVE_TARGETS_${component} cleave_${name})
endfunction()

# The build tree's include/cleave/<name>: a link to the source folder `dir` (made at configure time).
set(CLEAVE_INCLUDE_DIR ${PROJECT_BINARY_DIR}/include)
function(cleave_include_link name dir)
  set(link ${CLEAVE_INCLUDE_DIR}/cleave/${name})
  file(MAKE_DIRECTORY ${CLEAVE_INCLUDE_DIR}/cleave)
  if(EXISTS ${link} AND NOT IS_SYMLINK ${link})
    file(REMOVE_RECURSE ${link})
  endif()
  file(CREATE_LINK ${dir} ${link} SYMBOLIC)
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
