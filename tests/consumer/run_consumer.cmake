# SPDX-License-Identifier: MIT
# cmake -DSTEP=install|geometry|physics|engine -DCLEAVE_BUILD=... -DPREFIX=... -DWORK=... -P this
#   install:  installs the build into PREFIX and checks what the tree holds
#   geometry: builds and runs the geometry-only consumer where the other dependencies are hidden
#   physics:  expects asking for physics to fail in that same configuration
#   engine:   builds and runs the engine consumer
# geometry and engine pass only when the program exits with 0 and its output matches -DEXPECT=<regex>.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

function(expect_output)
  if(NOT run_output MATCHES "${EXPECT}")
    message(FATAL_ERROR "the consumer's output does not match\n  ${EXPECT}")
  endif()
endfunction()

# Everything but GLM and threads out of reach: find_package of the others and pkg-config fail.
set(hide_others
  -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_glfw3=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenGL=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON -DCMAKE_DISABLE_FIND_PACKAGE_Bullet=ON)

function(configure project_dir build_dir)
  file(REMOVE_RECURSE ${build_dir})
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE}/${project_dir} -B ${build_dir} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_PREFIX_PATH=${PREFIX} -DEXAMPLES_DIR=${EXAMPLES} ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(configure_rc ${rc} PARENT_SCOPE)
  set(configure_log "${out}\n${err}" PARENT_SCOPE)
endfunction()

if(STEP STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  run(${CMAKE_COMMAND} --install ${CLEAVE_BUILD} --prefix ${PREFIX})
  foreach(present include/cleave/base/status.h include/cleave/geometry/mesh_splitter.h
          include/cleave/physics/physics_world.h include/cleave/assets/model.h include/cleave/components/split_system.h)
    if(NOT EXISTS ${PREFIX}/${present})
      message(FATAL_ERROR "the installed tree has no ${present}")
    endif()
  endforeach()
  foreach(absent include/cleave/assets/glb_builder.h include/cleave/assets/gltf_access.h
          include/cleave/physics/detail include/cleave/base/detail include/cleave/engine include/engine)
    if(EXISTS ${PREFIX}/${absent})
      message(FATAL_ERROR "the installed tree holds ${absent}, which is internal")
    endif()
  endforeach()
  file(GLOB_RECURSE headers ${PREFIX}/include/*.h)
  foreach(header IN LISTS headers)
    file(STRINGS ${header} private REGEX "#include [<\"](tiny_gltf|btBullet|LinearMath|BulletCollision|glad/|GLFW/|EGL/)")
    if(private)
      message(FATAL_ERROR "${header} names a private dependency: ${private}")
    endif()
  endforeach()
elseif(STEP STREQUAL "geometry")
  configure(geometry ${WORK}/geometry ${hide_others})
  if(NOT configure_rc EQUAL 0)
    message(FATAL_ERROR "the geometry consumer did not configure with only GLM:\n${configure_log}")
  endif()
  run(${CMAKE_COMMAND} --build ${WORK}/geometry)
  run(${WORK}/geometry/hello_split)
  expect_output()
elseif(STEP STREQUAL "physics")
  configure(physics ${WORK}/physics ${hide_others})
  if(configure_rc EQUAL 0)
    message(FATAL_ERROR "asking for physics configured although Bullet cannot be found")
  endif()
  if(NOT configure_log MATCHES "PkgConfig")
    message(FATAL_ERROR "the failure does not name the missing dependency:\n${configure_log}")
  endif()
  message(STATUS "physics refused as expected")
elseif(STEP STREQUAL "engine")
  configure(engine ${WORK}/engine)
  if(NOT configure_rc EQUAL 0)
    message(FATAL_ERROR "the engine consumer did not configure:\n${configure_log}")
  endif()
  run(${CMAKE_COMMAND} --build ${WORK}/engine)
  run(${WORK}/engine/hello_engine)
  expect_output()
else()
  message(FATAL_ERROR "unknown STEP '${STEP}'")
endif()
