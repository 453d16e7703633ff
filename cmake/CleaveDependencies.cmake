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

# Dear ImGui for the in-game inspector (F1 in the demo and the arena): libimgui-dev ships the
# library and headers, and its GLFW and OpenGL 3 backends as source files, built here from the
# package's folder. The OpenGL 3 backend uses glad's loader (the engine's), so it works on EGL and
# OSMesa contexts too. Without the package the build goes on without the inspector.
option(CLEAVE_INSPECTOR "Build the in-game inspector (needs libimgui-dev)" ON)
set(CLEAVE_HAVE_IMGUI OFF)
if(CLEAVE_INSPECTOR)
  pkg_check_modules(IMGUI IMPORTED_TARGET imgui)
  find_path(CLEAVE_IMGUI_BACKEND_DIR imgui_impl_opengl3.cpp
            PATHS /usr/share/doc/libimgui-dev/examples/backends NO_DEFAULT_PATH)
  find_path(CLEAVE_IMGUI_BACKEND_HEADERS imgui_impl_opengl3.h PATH_SUFFIXES imgui/backends)
  if(IMGUI_FOUND AND CLEAVE_IMGUI_BACKEND_DIR AND CLEAVE_IMGUI_BACKEND_HEADERS)
    set(CLEAVE_HAVE_IMGUI ON)
    add_library(cleave_imgui STATIC ${CLEAVE_IMGUI_BACKEND_DIR}/imgui_impl_opengl3.cpp
                                    ${CLEAVE_IMGUI_BACKEND_DIR}/imgui_impl_glfw.cpp)
    target_include_directories(cleave_imgui PUBLIC $<BUILD_INTERFACE:${CLEAVE_IMGUI_BACKEND_HEADERS}>)
    target_link_libraries(cleave_imgui PUBLIC PkgConfig::IMGUI PRIVATE cleave_glad glfw)
    # The GL 3.3 core entry points come from glad (loaded by the engine for its context).
    set_source_files_properties(${CLEAVE_IMGUI_BACKEND_DIR}/imgui_impl_opengl3.cpp PROPERTIES
      COMPILE_DEFINITIONS IMGUI_IMPL_OPENGL_LOADER_CUSTOM COMPILE_OPTIONS "-include;glad/gl.h")
    target_compile_definitions(cleave_imgui PUBLIC CLEAVE_HAVE_IMGUI=1)
    message(STATUS "Cleave: the inspector is built with Dear ImGui ${IMGUI_VERSION}")
  else()
    message(STATUS "Cleave: libimgui-dev (Dear ImGui and its backend sources) not found: the inspector "
                   "is not built (F1 says so; tools/install-deps.sh installs it)")
  endif()
else()
  message(STATUS "Cleave: CLEAVE_INSPECTOR=OFF: the inspector is not built (F1 says so)")
endif()
