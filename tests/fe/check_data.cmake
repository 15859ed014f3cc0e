# SPDX-License-Identifier: MIT
# Regenerate the steering-column data and compare byte for byte with the committed file.
execute_process(COMMAND ${GEN} ${OUT} RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "make-steering-data failed (exit ${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${REF} RESULT_VARIABLE diff)
if(NOT diff EQUAL 0)
  message(FATAL_ERROR "${OUT} differs from the committed ${REF}: rerun make-steering-data and commit, or fix the generator")
endif()
