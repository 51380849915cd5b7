# Run by ctest: install, configure and build a host sample (SAMPLE, default embed_minimal) against the
# installed package, run it on a scene, check its output.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
if(NOT DEFINED SAMPLE)
  set(SAMPLE embed_minimal)
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/samples/${SAMPLE} -B ${WORK_DIR}/host -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/host)
if(SAMPLE STREQUAL "c_minimal") # the C host: its own output checks
  run(${CMAKE_COMMAND} -DPROGRAM=${WORK_DIR}/host/c_minimal -DSCENE=${SOURCE_DIR}/samples/demo.json
      -P ${SOURCE_DIR}/tests/capi/run_c_minimal.cmake)
  return()
endif()
run(${WORK_DIR}/host/embed_minimal ${SOURCE_DIR}/tests/tools/scenes/projectile.json)
if(NOT last_output MATCHES "ball position (2\\.99|3\\.00)")
  message(FATAL_ERROR "unexpected host output:\n${last_output}")
endif()
message(STATUS "host output:\n${last_output}")
