# glslang validation of the GLSL twins for one target. Run as:
#   cmake -DSHADER_TARGET=<330|450|es300|vulkan|include_directive> -DGLSLANG=<glslangValidator>
#         [-DSPIRV_VAL=<spirv-val>] -DFLATTEN=<cloudmath_glsl_flatten> -DINCLUDE_DIR=<repo>/include
#         -DWORK_DIR=<scratch dir> [-DCALLS=<calls.txt>] [-DEXPECT_FAILURE=ON]
#         -P validate_glsl.cmake
#
# Builds one fragment shader: the #version line (ES: + default precisions), the prelude
# (calls_prelude.glsl), the cloudmath module, the helpers (calls_helpers.glsl), and a main()
# that adds every expression of calls.txt into the output, so every public function and
# overload is compiled and type-checked. The module is what users compile:
#   330, 450, es300, vulkan   the flattened source (`cloudmath_glsl_flatten cloudmath`, i.e.
#                             cloudmath::glsl_source("cloudmath"), what raw OpenGL users get);
#   include_directive         the shipped files through GL_GOOGLE_include_directive and
#                             `#include "cloudmath/glsl/cloudmath.glsl"` with -I<INCLUDE_DIR>.
# 330 / 450 / es300 are validated as OpenGL GLSL; vulkan and include_directive are compiled
# to SPIR-V with `glslangValidator -V` and checked with `spirv-val --target-env vulkan1.0`.
#
# Fails, printing the tools' output and the shader lines the errors point at, when a tool
# exits non-zero or prints a line containing "WARNING" or "ERROR".
# EXPECT_FAILURE=ON inverts only that verdict (the shader must be rejected), for the test
# that proves a broken expression is caught; set-up errors still fail.
include("${CMAKE_CURRENT_LIST_DIR}/../../cmake/TextLines.cmake")
cmake_minimum_required(VERSION 3.20)

include("${CMAKE_CURRENT_LIST_DIR}/calls.cmake")

foreach(var SHADER_TARGET GLSLANG WORK_DIR INCLUDE_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "validate_glsl: pass -D${var}=...")
  endif()
endforeach()
if(NOT DEFINED CALLS)
  set(CALLS "${CMAKE_CURRENT_LIST_DIR}/calls.txt")
endif()
set(prelude_file "${CMAKE_CURRENT_LIST_DIR}/calls_prelude.glsl")
set(helpers_file "${CMAKE_CURRENT_LIST_DIR}/calls_helpers.glsl")

if(NOT EXISTS "${GLSLANG}")
  message(FATAL_ERROR "validate_glsl: glslangValidator not found ('${GLSLANG}'); "
    "install glslang-tools (scripts/install-deps.sh)")
endif()

set(spirv OFF)
set(uniform_layout "std140")
if(SHADER_TARGET STREQUAL "330")
  set(header "#version 330 core\n")
elseif(SHADER_TARGET STREQUAL "450")
  set(header "#version 450 core\n")
elseif(SHADER_TARGET STREQUAL "es300")
  set(header "#version 300 es\nprecision highp float;\nprecision highp int;\n")
elseif(SHADER_TARGET STREQUAL "vulkan")
  set(header "#version 450\n")
  set(spirv ON)
elseif(SHADER_TARGET STREQUAL "include_directive")
  set(header "#version 450\n#extension GL_GOOGLE_include_directive : require\n")
  set(spirv ON)
else()
  message(FATAL_ERROR "validate_glsl: unknown SHADER_TARGET '${SHADER_TARGET}'")
endif()
if(spirv)
  set(uniform_layout "std140, set = 0, binding = 0")
  if(NOT EXISTS "${SPIRV_VAL}")
    message(FATAL_ERROR "validate_glsl: spirv-val not found ('${SPIRV_VAL}'); "
      "install spirv-tools (scripts/install-deps.sh)")
  endif()
endif()

# --- the module --------------------------------------------------------------------------
if(SHADER_TARGET STREQUAL "include_directive")
  set(module "#include \"cloudmath/glsl/cloudmath.glsl\"\n")
else()
  if(NOT EXISTS "${FLATTEN}")
    message(FATAL_ERROR "validate_glsl: flatten tool '${FLATTEN}' not found; "
      "build the target cloudmath_glsl_flatten first")
  endif()
  execute_process(COMMAND "${FLATTEN}" cloudmath
    RESULT_VARIABLE result OUTPUT_VARIABLE module ERROR_VARIABLE error)
  if(NOT result EQUAL 0 OR module STREQUAL "")
    message(FATAL_ERROR "validate_glsl: '${FLATTEN} cloudmath' failed (${result}): ${error}")
  endif()
endif()

# --- the shader ---------------------------------------------------------------------------
cloudmath_parse_calls("${CALLS}" names body)
list(LENGTH names call_count)
file(READ "${prelude_file}" prelude)
file(READ "${helpers_file}" helpers)
set(shader "${header}")
string(APPEND shader "// ---- calls_prelude.glsl\n${prelude}")
string(APPEND shader "// ---- cloudmath module\n${module}")
string(APPEND shader "// ---- calls_helpers.glsl\n${helpers}")
string(APPEND shader "// ---- main: every expression of ${CALLS}
layout(${uniform_layout}) uniform CmTestInputs {
    vec4 a;
    vec4 b;
    int n;
};
layout(location = 0) out vec4 cm_test_out;

void main() {
    float cm_test_s = 0.0;
${body}    cm_test_out = vec4(cm_test_s);
}
")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(shader_file "${WORK_DIR}/cloudmath_${SHADER_TARGET}.frag")
file(WRITE "${shader_file}" "${shader}")

# --- compile -------------------------------------------------------------------------------
if(spirv)
  set(spv "${WORK_DIR}/cloudmath_${SHADER_TARGET}.spv")
  file(REMOVE "${spv}")
  set(glslang_command "${GLSLANG}" -V "${shader_file}" -o "${spv}")
  if(SHADER_TARGET STREQUAL "include_directive")
    list(APPEND glslang_command "-I${INCLUDE_DIR}")
  endif()
else()
  set(glslang_command "${GLSLANG}" "${shader_file}")
endif()
execute_process(COMMAND ${glslang_command}
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
string(REPLACE ";" " " shown "${glslang_command}")
set(report "$ ${shown}\n${output}")
set(failed OFF)
if(NOT result EQUAL 0 OR output MATCHES "WARNING|ERROR")
  set(failed ON)
endif()
if(spirv AND NOT failed)
  execute_process(COMMAND "${SPIRV_VAL}" --target-env vulkan1.0 "${spv}"
    RESULT_VARIABLE result OUTPUT_VARIABLE val_output ERROR_VARIABLE val_output)
  string(APPEND report "$ ${SPIRV_VAL} --target-env vulkan1.0 ${spv}\n${val_output}")
  if(NOT result EQUAL 0 OR val_output MATCHES "WARNING|ERROR|error")
    set(failed ON)
  endif()
endif()

# The shader lines that glslang's messages name: "ERROR: 0:<line>:" (OpenGL) or
# "ERROR: <shader file>:<line>:" (-V); lines of included files are not looked up.
if(failed)
  string(REPLACE "${shader_file}:" "0:" located "${output}")
  string(REGEX MATCHALL "(ERROR|WARNING): 0:[0-9]+:" locations "${located}")
  list(REMOVE_DUPLICATES locations)
  if(locations)
    string(APPEND report "Shader lines named above (${shader_file}):\n")
    foreach(location IN LISTS locations)
      string(REGEX REPLACE ".*: 0:([0-9]+):" "\\1" number "${location}")
      cloudmath_text_line("${shader}" ${number} text)
      string(APPEND report "  ${number}: ${text}\n")
    endforeach()
  endif()
endif()

message("${report}")
if(EXPECT_FAILURE)
  if(NOT failed)
    message(FATAL_ERROR "validate_glsl: ${SHADER_TARGET}: the shader was accepted, but ${CALLS} "
      "contains a deliberately broken expression that glslang must reject")
  endif()
  message(STATUS "validate_glsl: ${SHADER_TARGET}: broken expression rejected, as expected")
elseif(failed)
  message(FATAL_ERROR "validate_glsl: ${SHADER_TARGET}: glslang or spirv-val reported a problem "
    "(output above; shader ${shader_file})")
else()
  message(STATUS "validate_glsl: ${SHADER_TARGET}: ${call_count} expressions compiled cleanly")
endif()
