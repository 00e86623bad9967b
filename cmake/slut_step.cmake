# step(COMMAND ARGS…): runs a command in a CMake -P script and stops the script with the
# command's output when it fails. Shared by the CTest driver scripts under tests/.
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
