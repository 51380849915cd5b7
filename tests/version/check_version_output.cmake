# Run by ctest: PROGRAM --version must exit 0 and print exactly "supermodal VERSION" and a newline on
# stdout, and nothing on stderr.
execute_process(COMMAND ${PROGRAM} --version RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out STREQUAL "supermodal ${VERSION}\n" OR NOT err STREQUAL "")
  message(FATAL_ERROR "${PROGRAM} --version: exit ${rc}, stdout '${out}', stderr '${err}'; expected exit 0 "
    "and 'supermodal ${VERSION}'")
endif()
