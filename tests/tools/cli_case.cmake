# cli_case.cmake — one end-to-end case of the `tandem` command line (ctest
# runs it with cmake -P; see cli_tests.cmake).
#   TANDEM   the executable
#   ARGS     its arguments, separated by '|'
#   RC       the expected exit code
#   OUT/ERR  optional regular expressions stdout / stderr must match
#   NOT_ERR  optional regular expression stderr must not match
#   EXISTS   optional files ('|'-separated) that must exist afterwards (removed first)
#   SAME     optional second argument list ('|'): its stdout must equal the first's
string(REPLACE "|" ";" args "${ARGS}")
string(REPLACE "|" ";" files "${EXISTS}")
foreach(f IN LISTS files)
  file(REMOVE "${f}")
endforeach()
execute_process(COMMAND "${TANDEM}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(report "tandem ${args}\n--- exit code ${rc} (expected ${RC})\n--- stdout:\n${out}\n--- stderr:\n${err}")
if(NOT rc STREQUAL RC)
  message(FATAL_ERROR "wrong exit code\n${report}")
endif()
if(OUT AND NOT out MATCHES "${OUT}")
  message(FATAL_ERROR "stdout does not match '${OUT}'\n${report}")
endif()
if(ERR AND NOT err MATCHES "${ERR}")
  message(FATAL_ERROR "stderr does not match '${ERR}'\n${report}")
endif()
if(NOT_ERR AND err MATCHES "${NOT_ERR}")
  message(FATAL_ERROR "stderr matches '${NOT_ERR}'\n${report}")
endif()
if(RC STREQUAL "0" AND NOT OUT_ALLOW_STDERR AND NOT err STREQUAL "")
  message(FATAL_ERROR "a successful run wrote to stderr\n${report}")
endif()
foreach(f IN LISTS files)
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "missing output file ${f}\n${report}")
  endif()
endforeach()
if(SAME)
  string(REPLACE "|" ";" args2 "${SAME}")
  execute_process(COMMAND "${TANDEM}" ${args2} RESULT_VARIABLE rc2 OUTPUT_VARIABLE out2 ERROR_VARIABLE err2)
  if(NOT rc2 STREQUAL "0" OR NOT out STREQUAL out2)
    message(FATAL_ERROR "second run differs\n${report}\n--- second run (tandem ${args2}), exit code ${rc2}:\n${out2}\n${err2}")
  endif()
endif()
