# Runs one libFuzzer target in fork mode (ctest -L fuzz) and decides the result
# from its own counters: the test fails on any crash or timeout (the inputs
# are in ${ARTIFACTS}), not on out-of-memory, which fork mode skips: MRPT
# allocates whatever a corrupt rawlog claims (regressions/rawlog/oom-*), an
# MRPT limitation rather than a finding. libFuzzer 14 still exits non-zero
# after skipped OOMs, hence this script instead of its exit code.
#   cmake -DFUZZER=... -DARGS="a|b|..." -P RunFuzzer.cmake
string(REPLACE "|" ";" ARGS "${ARGS}")
execute_process(COMMAND ${FUZZER} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(log "${out}${err}")
string(REGEX MATCHALL "oom/timeout/crash: [0-9]+/[0-9]+/[0-9]+" counts "${log}")
list(LENGTH counts n)
if(n EQUAL 0)
  message("${log}")
  message(FATAL_ERROR "${FUZZER}: no fork-mode status (exit ${rc}); it did not run")
endif()
list(GET counts -1 last)
string(REGEX MATCH "([0-9]+)/([0-9]+)/([0-9]+)" _ "${last}")
set(ooms ${CMAKE_MATCH_1})
set(timeouts ${CMAKE_MATCH_2})
set(crashes ${CMAKE_MATCH_3})
string(REGEX MATCH "stat::number_of_executed_units: [0-9]+" units "${log}")
message("${FUZZER}: ${last} (out-of-memory skipped), ${units}")
if(NOT timeouts EQUAL 0 OR NOT crashes EQUAL 0)
  message("${log}")
  message(FATAL_ERROR "${FUZZER}: ${crashes} crash(es), ${timeouts} timeout(s): see the artifacts")
endif()
