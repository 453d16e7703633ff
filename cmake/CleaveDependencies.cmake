# SPDX-License-Identifier: MIT
# Every dependency comes from a Debian package (see tools/install-deps.sh).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(OpenGL REQUIRED COMPONENTS EGL)
find_package(glfw3 3.3 CONFIG REQUIRED)                 # target: glfw
find_package(TinyGLTF CONFIG REQUIRED)                  # target: TinyGLTF::TinyGLTF (prebuilt)
find_package(nlohmann_json CONFIG REQUIRED)
# Debian's BulletConfig.cmake has relative paths; pkg-config is the reliable way in.
pkg_check_modules(BULLET REQUIRED IMPORTED_TARGET bullet)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)     # libstb.so carries the implementations
pkg_check_modules(OSMESA IMPORTED_TARGET osmesa)        # optional headless fallback
find_program(GLAD_EXE glad REQUIRED)

if(CLEAVE_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
  include(GoogleTest)
endif()
if(CLEAVE_BUILD_BENCHMARKS)
  find_package(benchmark CONFIG REQUIRED)
endif()

# glad2 generated offline from the Khronos XML bundled in python3-glad.
set(CLEAVE_GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${CLEAVE_GLAD_DIR}/src/gl.c ${CLEAVE_GLAD_DIR}/include/glad/gl.h
  COMMAND ${GLAD_EXE} --quiet --api gl:core=3.3 --extensions "" --out-path ${CLEAVE_GLAD_DIR} --reproducible c
  COMMENT "Generating the OpenGL 3.3 core loader with glad"
  VERBATIM)
add_library(cleave_glad STATIC ${CLEAVE_GLAD_DIR}/src/gl.c)
target_include_directories(cleave_glad PUBLIC $<BUILD_INTERFACE:${CLEAVE_GLAD_DIR}/include>)
target_link_libraries(cleave_glad PUBLIC ${CMAKE_DL_LIBS})
