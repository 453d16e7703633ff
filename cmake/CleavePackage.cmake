# SPDX-License-Identifier: MIT
# The installed package, in components a user asks for one by one:
#   find_package(Cleave 0.2 REQUIRED COMPONENTS geometry)
# geometry: the split core (GLM and the standard library) and base (Status, Expected: the standard
# library only); anim: skeletons and clips (GLM; + geometry for base);
# physics: the Bullet bridge (+ geometry, Bullet); assets: glTF and mesh files (+ geometry, anim,
# tinygltf, stb); engine: everything (ECS, input, render, app, components; GL, EGL, GLFW, JSON).
# Each component has an export set of its own (CleaveTargets-<component>.cmake), and the package's
# config finds only the dependencies of the components asked for (cmake/CleaveConfig.cmake.in).
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)
set(CLEAVE_PACKAGE_COMPONENTS geometry anim physics assets engine)
set_property(GLOBAL APPEND PROPERTY CLEAVE_TARGETS_engine cleave_engine cleave_glad)
if(CLEAVE_HAVE_IMGUI)
  set_property(GLOBAL APPEND PROPERTY CLEAVE_TARGETS_engine cleave_imgui)  # the inspector's backends
endif()
foreach(component IN LISTS CLEAVE_PACKAGE_COMPONENTS)
  get_property(targets GLOBAL PROPERTY CLEAVE_TARGETS_${component})
  install(TARGETS ${targets} EXPORT CleaveTargets-${component} COMPONENT ${component}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT CleaveTargets-${component} NAMESPACE Cleave:: COMPONENT ${component}
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Cleave)
endforeach()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/CleaveConfig.cmake.in
  ${PROJECT_BINARY_DIR}/CleaveConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Cleave)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/CleaveConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/CleaveConfig.cmake ${PROJECT_BINARY_DIR}/CleaveConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Cleave)
