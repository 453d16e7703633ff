# SPDX-License-Identifier: MIT
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)
get_property(cleave_targets GLOBAL PROPERTY CLEAVE_EXPORTED_TARGETS)
if(CLEAVE_HAVE_IMGUI)
  list(APPEND cleave_targets cleave_imgui)  # the ImGui backends the app and render layers link
endif()
install(TARGETS ${cleave_targets} cleave_engine cleave_glad EXPORT CleaveTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT CleaveTargets NAMESPACE Cleave:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Cleave)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/CleaveConfig.cmake.in
  ${PROJECT_BINARY_DIR}/CleaveConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Cleave)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/CleaveConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/CleaveConfig.cmake ${PROJECT_BINARY_DIR}/CleaveConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Cleave)
