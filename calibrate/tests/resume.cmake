# Interrupt + resume + reproducibility through the program itself:
#   1. a full run (OUT/full) and a second full run (OUT/again): identical best_params.txt and
#      residual tables (same config and seed -> same result);
#   2. a run stopped after 25 evaluations (--stop-after: the code path of SIGINT/SIGTERM),
#      exit status 130; the last cache line is then cut in half (a kill during a write);
#   3. --resume in the same folder: the same best_params.txt as the full run.
foreach(d full again part)
  file(REMOVE_RECURSE ${OUT}/${d})
endforeach()
execute_process(COMMAND ${PROG} --builtin ${CASE} --out ${OUT}/full --quiet --no-plots RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "full run failed (${rc})")
endif()
execute_process(COMMAND ${PROG} --builtin ${CASE} --out ${OUT}/again --quiet --no-plots RESULT_VARIABLE rc)
foreach(f best_params.txt residuals_${TARGET}.csv)
  file(READ ${OUT}/full/${f} a)
  file(READ ${OUT}/again/${f} b)
  if(NOT a STREQUAL b)
    message(FATAL_ERROR "same config and seed gave different ${f}")
  endif()
endforeach()
execute_process(COMMAND ${PROG} --builtin ${CASE} --out ${OUT}/part --quiet --no-plots --stop-after 25
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 130)
  message(FATAL_ERROR "interrupted run: expected exit 130, got ${rc}")
endif()
file(READ ${OUT}/part/eval_cache.txt cache)
string(LENGTH "${cache}" len)
math(EXPR cut "${len} - 9")
string(SUBSTRING "${cache}" 0 ${cut} cache)
file(WRITE ${OUT}/part/eval_cache.txt "${cache}")
execute_process(COMMAND ${PROG} --builtin ${CASE} --out ${OUT}/part --quiet --no-plots --resume --json
                RESULT_VARIABLE rc OUTPUT_VARIABLE json)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "resumed run failed (${rc})")
endif()
file(READ ${OUT}/full/best_params.txt a)
file(READ ${OUT}/part/best_params.txt b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "the resumed run reached a different optimum:\n${a}\nvs\n${b}")
endif()
string(REGEX MATCH "\"cached_evaluations\": [0-9]+" cached "${json}")
message(STATUS "resume ok: ${cached}")
