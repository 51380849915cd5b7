# Run by ctest (and by tests/install): runs the C sample on samples/demo.json and checks its exit status
# and output: every body of the scene, the step count and hash, and the bad scene's JSON pointer.
execute_process(COMMAND ${PROGRAM} ${SCENE} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "c_minimal exited with ${rc}:\n${out}\n${err}")
endif()
foreach(expected "ground position 0\\.000000 0\\.000000 0\\.000000" "\nball position " "\nboard position "
    "\negg position " "\nsteps [0-9]+ hash [0-9a-f]+\n"
    "bad scene refused: <string>: /bodies/0/shape/radii/1: ")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "c_minimal output lacks '${expected}':\n${out}")
  endif()
endforeach()
message(STATUS "c_minimal output:\n${out}")
