# HLSL parity: the HLSL twins (made from the GLSL ones by tools/shader_translate) against the
# C++ float functions, on the OpenGL driver that glsl.parity uses. Run as:
#   cmake -DPARITY=<test_glsl_parity> -DNODE=<node> -DMAKE_SHADER=<make_parity_shader.mjs>
#         -DGLSLANG=<glslangValidator> -DSPIRV_VAL=<spirv-val> -DSPIRV_CROSS=<spirv-cross>
#         -DWORK_DIR=<scratch dir> [-DMARKDOWN=<file.md>] -P hlsl_parity.cmake
# or, to compile one hand-written body only (no cases, no driver):
#   cmake -DBODY=<body.hlsl> -DGLSLANG=... -DSPIRV_VAL=... -DSPIRV_CROSS=... -DWORK_DIR=...
#         [-DEXPECT_FAILURE=ON] -P hlsl_parity.cmake
#
# For each program of test_glsl_parity's cases (at most 64 cases each, main then config):
#   1. test_glsl_parity --dump-cases cases.json   (once: every case, its program, C++ results)
#   2. node make_parity_shader.mjs --target hlsl --cases cases.json --program K
#      --out body_K.hlsl: the library, the prelude/after helpers and cm_test_case (HLSL)
#   3. program_K.hlsl = body + the entry point below (gl_compute's contract)
#   4. glslangValidator -D -V -S comp -e main (HLSL front end to SPIR-V), spirv-val,
#      spirv-cross --version 430 --no-es (back to GLSL), u_case made a plain uniform
#   5. test_glsl_parity --program program_K.comp... --config-program ... --language HLSL
# Every file stays in WORK_DIR for inspection. Any failing step fails with the tool's
# output (and, for compile errors, the HLSL lines they name); a missing tool fails and says
# what to install. No OpenGL context (outside CI) prints "hlsl_parity: SKIPPED", which
# ctest's SKIP_REGULAR_EXPRESSION turns into a skip (cmake -P cannot exit 77).
# EXPECT_FAILURE=ON inverts only the compile verdict of the BODY mode (the body must be
# rejected), for the test that proves the compile gate can fail; set-up errors still fail.
include("${CMAKE_CURRENT_LIST_DIR}/../../cmake/TextLines.cmake")
cmake_minimum_required(VERSION 3.20)

function(hlsl_require var what)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "hlsl_parity: pass -D${var}=<${what}>")
  endif()
endfunction()
function(hlsl_require_tool var tool package)
  hlsl_require(${var} ${tool})
  if(NOT EXISTS "${${var}}")
    message(FATAL_ERROR "hlsl_parity: ${tool} not found ('${${var}}'); install the Debian package "
      "${package} (bash scripts/install-deps.sh) and reconfigure")
  endif()
endfunction()

hlsl_require(WORK_DIR "scratch dir")
hlsl_require_tool(GLSLANG glslangValidator glslang-tools)
hlsl_require_tool(SPIRV_VAL spirv-val spirv-tools)
hlsl_require_tool(SPIRV_CROSS spirv-cross spirv-cross)
file(MAKE_DIRECTORY "${WORK_DIR}")

# gl_compute's contract (tests/glsl/gl_compute.hpp): binding 0 std430 vec4 inputs, a then b
# per evaluation; binding 1 std430 vec4 outputs; uniform int u_case; local size (N, 1, 1);
# buffers padded to the dispatched count, so the bound check only mirrors the GLSL harness.
# DXC-compatible too: [[vk::binding]] for SPIR-V, register() for D3D.
set(entry_point [=[

// ---- entry point (tests/hlsl/hlsl_parity.cmake): gl_compute's buffers and u_case
[[vk::binding(0)]] StructuredBuffer<float4> inputs : register(t0);
[[vk::binding(1)]] RWStructuredBuffer<float4> outputs : register(u1);
[[vk::binding(2)]] cbuffer CmTestCase : register(b0) { int u_case; };

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
    uint count, stride;
    inputs.GetDimensions(count, stride);
    if (id.x >= count / 2u) return;
    outputs[id.x] = cm_test_case(u_case, inputs[2u * id.x], inputs[2u * id.x + 1u]);
}
]=])

# Appends to report_var the text of the lines of `text` that glslang's messages in `output`
# name ("ERROR: <file>:<line>:" or "WARNING: <file>:<line>:").
function(hlsl_named_lines output file text report_var)
  string(REPLACE "${file}:" "0:" located "${output}")
  string(REGEX MATCHALL "(ERROR|WARNING): 0:[0-9]+:" locations "${located}")
  list(REMOVE_DUPLICATES locations)
  set(report "${${report_var}}")
  if(locations)
    string(APPEND report "HLSL lines named above (${file}):\n")
  endif()
  list(LENGTH locations count)
  if(count GREATER 20)
    list(SUBLIST locations 0 20 locations)
  endif()
  foreach(location IN LISTS locations)
    string(REGEX REPLACE ".*: 0:([0-9]+):" "\\1" number "${location}")
    cloudmath_text_line("${text}" ${number} line)
    string(APPEND report "  ${number}: ${line}\n")
  endforeach()
  set(${report_var} "${report}" PARENT_SCOPE)
endfunction()

# Compiles <name>.hlsl (body + entry point) in WORK_DIR to <name>.comp, the GLSL the harness
# runs. Sets ok_var to TRUE/FALSE and report_var to the commands and the tools' output.
function(hlsl_build name body_file ok_var report_var)
  file(READ "${body_file}" body)
  set(hlsl "${WORK_DIR}/${name}.hlsl")
  set(spv "${WORK_DIR}/${name}.spv")
  set(cross "${WORK_DIR}/${name}.spirv-cross.comp")
  set(comp "${WORK_DIR}/${name}.comp")
  set(text "${body}${entry_point}")
  file(WRITE "${hlsl}" "${text}")
  file(REMOVE "${spv}" "${cross}" "${comp}")
  set(${ok_var} FALSE PARENT_SCOPE)

  # No -Od: glslang's default spirv-opt passes are what an HLSL user gets, and they may fuse
  # a * b + c into fma where the source is not `precise` (HLSL allows it, as DXC does).
  set(command "${GLSLANG}" -D -V -S comp -e main "${hlsl}" -o "${spv}")
  execute_process(COMMAND ${command} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(REPLACE ";" " " shown "${command}")
  set(report "$ ${shown}\n${output}")
  # Warnings fail too, as everywhere in this project.
  if(NOT result EQUAL 0 OR output MATCHES "WARNING|ERROR")
    hlsl_named_lines("${output}" "${hlsl}" "${text}" report)
    set(${report_var} "${report}" PARENT_SCOPE)
    return()
  endif()

  execute_process(COMMAND "${SPIRV_VAL}" "${spv}" RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(APPEND report "$ ${SPIRV_VAL} ${spv}\n${output}")
  if(NOT result EQUAL 0 OR output MATCHES "WARNING|ERROR|error")
    set(${report_var} "${report}" PARENT_SCOPE)
    return()
  endif()

  set(command "${SPIRV_CROSS}" --version 430 --no-es "${spv}" --output "${cross}")
  execute_process(COMMAND ${command} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(REPLACE ";" " " shown "${command}")
  string(APPEND report "$ ${shown}\n${output}")
  if(NOT result EQUAL 0 OR NOT EXISTS "${cross}")
    set(${report_var} "${report}" PARENT_SCOPE)
    return()
  endif()

  # spirv-cross turns the cbuffer into a UBO block with a generated instance name
  # ("uniform CmTestCase { int u_case; } _99;", read as _99.u_case); gl_compute sets u_case
  # with glUniform1i(glGetUniformLocation(p, "u_case")), so it must be a plain uniform. No
  # spirv-cross option does that (--glsl-emit-ubo-as-plain-uniforms gives "_99.u_case").
  # Replace that one block and its uses; any other shape fails here, not as wrong results.
  file(READ "${cross}" glsl)
  string(REGEX MATCH "layout\\([^)\n]*\\) uniform CmTestCase\n{\n    int u_case;\n} ([A-Za-z_][A-Za-z0-9_]*);\n" block "${glsl}")
  set(instance "${CMAKE_MATCH_1}")
  if(block STREQUAL "")
    string(APPEND report "hlsl_parity: no 'uniform CmTestCase { int u_case; } <name>;' block in ${cross}: "
      "spirv-cross's output changed shape; adapt the replacement in tests/hlsl/hlsl_parity.cmake\n")
    set(${report_var} "${report}" PARENT_SCOPE)
    return()
  endif()
  string(REPLACE "${block}" "@CM_U_CASE@" glsl "${glsl}")
  string(REPLACE "${instance}.u_case" "u_case" glsl "${glsl}")
  if(glsl MATCHES "CmTestCase|(^|[^A-Za-z0-9_.])${instance}([^A-Za-z0-9_]|$)" OR NOT glsl MATCHES "(^|[^A-Za-z0-9_.])u_case([^A-Za-z0-9_]|$)")
    string(APPEND report "hlsl_parity: after the replacement, CmTestCase or ${instance} is still there, or u_case "
      "is never used (${cross}); adapt the replacement in tests/hlsl/hlsl_parity.cmake\n")
    set(${report_var} "${report}" PARENT_SCOPE)
    return()
  endif()
  string(REPLACE "@CM_U_CASE@" "uniform int u_case;  // was a UBO block (hlsl_parity.cmake)\n" glsl "${glsl}")
  file(WRITE "${comp}" "${glsl}")
  set(${ok_var} TRUE PARENT_SCOPE)
  set(${report_var} "${report}" PARENT_SCOPE)
endfunction()

# --- BODY mode: the compile gate alone ---------------------------------------------------
if(DEFINED BODY)
  if(NOT EXISTS "${BODY}")
    message(FATAL_ERROR "hlsl_parity: body '${BODY}' not found")
  endif()
  hlsl_build(body "${BODY}" ok report)
  message("${report}")
  if(EXPECT_FAILURE)
    if(ok)
      message(FATAL_ERROR "hlsl_parity: ${BODY} was accepted, but it holds a deliberate error the "
        "compile step must reject")
    endif()
    message(STATUS "hlsl_parity: ${BODY} rejected, as expected")
  elseif(NOT ok)
    message(FATAL_ERROR "hlsl_parity: ${BODY} does not compile (output above; ${WORK_DIR}/body.hlsl)")
  else()
    message(STATUS "hlsl_parity: ${BODY} compiled to ${WORK_DIR}/body.comp")
  endif()
  return()
endif()

# --- the parity run --------------------------------------------------------------------------
hlsl_require(PARITY "test_glsl_parity")
hlsl_require_tool(NODE node nodejs)
hlsl_require(MAKE_SHADER "make_parity_shader.mjs")
if(NOT EXISTS "${MAKE_SHADER}")
  message(FATAL_ERROR "hlsl_parity: ${MAKE_SHADER} not found: the GLSL->HLSL generator of the parity "
    "shader (tools/shader_translate) is missing")
endif()

# All cases in one file, and the program list.
set(command "${PARITY}" --dump-cases "${WORK_DIR}/cases.json")
execute_process(COMMAND ${command} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  string(REPLACE ";" " " shown "${command}")
  message(FATAL_ERROR "hlsl_parity: '${shown}' failed (${result}):\n${output}")
endif()
# The "programs" line alone: string(JSON) reparses its whole input on every call, and the
# file has megabytes.
file(STRINGS "${WORK_DIR}/cases.json" programs_line REGEX "^  \"programs\": ")
string(REGEX REPLACE ",$" "" programs_json "${programs_line}")
string(JSON program_count LENGTH "{${programs_json}}" programs)
if(program_count LESS 1)
  message(FATAL_ERROR "hlsl_parity: no programs in ${WORK_DIR}/cases.json")
endif()

math(EXPR last "${program_count} - 1")
set(main_programs "")
set(config_programs "")
foreach(k RANGE ${last})
  string(JSON config GET "{${programs_json}}" programs ${k} config)
  set(body "${WORK_DIR}/body_${k}.hlsl")
  file(REMOVE "${body}")
  set(command "${NODE}" "${MAKE_SHADER}" --target hlsl --cases "${WORK_DIR}/cases.json" --program ${k} --out "${body}")
  execute_process(COMMAND ${command} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(REPLACE ";" " " shown "${command}")
  if(NOT result EQUAL 0 OR NOT EXISTS "${body}")
    message(FATAL_ERROR "hlsl_parity: '${shown}' failed (${result}):\n${output}")
  endif()

  hlsl_build(program_${k} "${body}" ok report)
  if(NOT ok)
    message(FATAL_ERROR "hlsl_parity: program ${k} does not compile to GLSL:\n$ ${shown}\n${report}")
  endif()
  if(config)
    list(APPEND config_programs --config-program "${WORK_DIR}/program_${k}.comp")
  else()
    list(APPEND main_programs --program "${WORK_DIR}/program_${k}.comp")
  endif()
endforeach()
message(STATUS "hlsl_parity: ${program_count} programs compiled in ${WORK_DIR} (program_K.hlsl -> program_K.comp)")

set(command "${PARITY}" ${main_programs} ${config_programs} --language HLSL)
if(DEFINED MARKDOWN AND NOT MARKDOWN STREQUAL "")
  list(APPEND command --markdown "${MARKDOWN}")
endif()
execute_process(COMMAND ${command} RESULT_VARIABLE result)
if(result EQUAL 77)
  message("hlsl_parity: SKIPPED (no OpenGL context; see above)")
elseif(NOT result EQUAL 0)
  string(REPLACE ";" " " shown "${command}")
  message(FATAL_ERROR "hlsl_parity: '${shown}' failed (${result}); table above")
endif()
