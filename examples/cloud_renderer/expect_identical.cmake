# Runs COMMAND with ARGS (a ;-list) twice, writing WORK/first.png and WORK/second.png, and
# fails unless both runs succeed and the two files are byte-identical: the accumulation modes
# (--accumulate, --temporal) are deterministic. A third run with the same ARGS but one more
# frame (NEXT, the flag whose value goes up by one) must differ, so the check can fail.
file(MAKE_DIRECTORY "${WORK}")
foreach(name first second)
  execute_process(COMMAND "${COMMAND}" ${ARGS} --out "${WORK}/${name}.png"
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "run ${name} failed (${status}):\n${out}\n${err}")
  endif()
endforeach()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/first.png" "${WORK}/second.png"
  RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "two runs of ${ARGS} wrote different images")
endif()
execute_process(COMMAND "${COMMAND}" ${ARGS} ${NEXT} --out "${WORK}/third.png"
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/first.png" "${WORK}/third.png"
  RESULT_VARIABLE same)
if(NOT status EQUAL 0 OR same EQUAL 0)
  message(FATAL_ERROR "one more frame (${NEXT}) did not change the image: the check cannot fail")
endif()
message("identical: ${ARGS}")
