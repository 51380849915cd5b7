# Run by ctest: `cmake --install` into a temporary prefix, then import supermodal from the prefix's
# site-packages (SITE_DIR, relative to the prefix or absolute) in a fresh interpreter and step a scene.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}):\n${err}")
endif()
cmake_path(ABSOLUTE_PATH SITE_DIR BASE_DIRECTORY ${prefix} OUTPUT_VARIABLE site)
file(GLOB module ${site}/supermodal*.so)
if(NOT module OR NOT EXISTS ${site}/supermodal.pyi OR NOT EXISTS ${site}/_supermodal_sweep.py)
  message(FATAL_ERROR "no supermodal module, stubs and _supermodal_sweep.py in ${site}")
endif()
set(script "import supermodal as sm, sys
assert sm.__file__.startswith(sys.argv[1]), sm.__file__
assert sm.sweep.__module__ == '_supermodal_sweep' and sys.modules['_supermodal_sweep'].__file__.startswith(sys.argv[1])
w = sm.load_scene(sys.argv[2])
w.step(100)
print(sm.__version__, w.step_count, hex(w.state_hash()))")
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${site} PYTHONDONTWRITEBYTECODE=1
    ${PYTHON} -c "${script}" ${site} ${SOURCE_DIR}/tests/tools/scenes/projectile.json
  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^[0-9.]+ 100 0x[0-9a-f]+")
  message(FATAL_ERROR "importing the installed module failed (${rc}):\n${out}\n${err}")
endif()
message(STATUS "installed module: ${module}\n${out}")
