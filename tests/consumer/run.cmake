# The installed package works for a project outside rigflex: install the
# build tree into WORK_DIR/prefix, configure and build tests/consumer against
# it with find_package(rigflex), run it on a model, and check its frequencies
# against the rigflex command line's modes.json of the same model (the same
# library code, so they agree to the printed 6 digits).
#   cmake -DBUILD_DIR=.. -DSOURCE_DIR=.. -DWORK_DIR=.. -DRIGFLEX=.. -DCXX_COMPILER=.. -P run.cmake
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
# With the build's compiler: a sanitized build's targets carry its
# -fsanitize flags, which only that compiler may know.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
set(model ${SOURCE_DIR}/examples/beam-frame/model.yaml)
run(${WORK_DIR}/build/first_modes ${model})
set(consumer "${run_output}")
run(${RIGFLEX} modes ${model} --count 3 --out ${WORK_DIR}/modes)
file(READ ${WORK_DIR}/modes/modes.json modes_json)
foreach(k 0 1 2)
  string(JSON f GET "${modes_json}" frequencies_hz ${k})
  math(EXPR mode "${k} + 1")
  # The consumer prints %.6g; format the CLI's value the same way.
  execute_process(COMMAND printf "mode %d %.6g Hz" ${mode} ${f} OUTPUT_VARIABLE expected)
  string(FIND "${consumer}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "consumer output lacks '${expected}' (modes.json: ${f}):\n${consumer}")
  endif()
endforeach()
message(STATUS "consumer built against the installed rigflex:\n${consumer}")
