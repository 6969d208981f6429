# Shared by the consumer test drivers (cmake -P scripts).
# consumer_step(<what> <command> [args...]): runs the command and stops the test with the
# command's full output if it fails. The output is also returned in consumer_step_output.
function(consumer_step what)
  execute_process(COMMAND ${ARGN}
    RESULT_VARIABLE result
    OUTPUT_VARIABLE output
    ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "consumer test: ${what} failed (${result})\n"
      "command: ${command}\n${output}")
  endif()
  message(STATUS "consumer test: ${what}: ok")
  set(consumer_step_output "${output}" PARENT_SCOPE)
endfunction()

# Arguments that make a nested configure use the same toolchain as the main build.
function(consumer_configure_args out)
  set(args -G "${GENERATOR}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -DCMAKE_BUILD_TYPE=Release)
  if(MAKE_PROGRAM)
    list(APPEND args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
  endif()
  set(${out} ${args} PARENT_SCOPE)
endfunction()

# consumer_install(<prefix>): installs the main build tree (MAIN_BUILD_DIR, for CONFIG when
# set) into <prefix>, the first step of every test that consumes an install.
function(consumer_install prefix)
  set(config_args "")
  if(CONFIG)
    set(config_args --config "${CONFIG}")
  endif()
  consumer_step("install into ${prefix}"
    "${CMAKE_COMMAND}" --install "${MAIN_BUILD_DIR}" --prefix "${prefix}" ${config_args})
endfunction()
