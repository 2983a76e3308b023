# One benchmark slice as a test (bench/CMakeLists.txt): the program must exit
# 0 and print the row of its table that the slice asks for.
# -DPROGRAM=... -DROW=<regex> -DARGS=<arguments separated by |>
string(REPLACE "|" ";" ARGS "${ARGS}")
execute_process(COMMAND ${PROGRAM} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} exited with ${rc}:\n${err}")
endif()
if(NOT out MATCHES "${ROW}")
  message(FATAL_ERROR "${PROGRAM} printed no row matching '${ROW}':\n${err}")
endif()
