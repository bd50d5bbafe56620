# Run PROG on a bad config CFG: it must exit non-zero and name the file and a line,
# "bad_x.cfg:<line>: <field>: ...", on stderr (the expected field is in the config's first
# line: "# expect: <regex>").
execute_process(COMMAND ${PROG} ${CFG} --quiet RESULT_VARIABLE rc ERROR_VARIABLE err
                OUTPUT_VARIABLE out)
file(STRINGS ${CFG} first LIMIT_COUNT 1)
string(REGEX REPLACE "^# expect: " "" expect "${first}")
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit, got 0; stderr: ${err}")
endif()
if(NOT err MATCHES "${expect}")
  message(FATAL_ERROR "stderr does not match '${expect}':\n${err}")
endif()
message(STATUS "ok (exit ${rc}): ${err}")
