# hlsl.compile: every shipped HLSL twin (include/cloudmath/hlsl/*.hlsl and CloudMath.ush)
# compiles alone, included the way users include it, in a compute and a pixel shader, with
# glslang's HLSL front end (-D) to SPIR-V that spirv-val accepts. The shader calls one
# function of the module so that the module is not compiled away unchecked: glslang checks
# every function body it parses, used or not, which is what this relies on.
#   cmake -DGLSLANG=<glslangValidator> -DSPIRV_VAL=<spirv-val> -DINCLUDE_DIR=<repo>/include
#         -DWORK_DIR=<scratch> -P compile_modules.cmake
foreach(tool GLSLANG SPIRV_VAL)
  if(NOT ${tool})
    message(FATAL_ERROR "hlsl.compile: ${tool} not found; bash scripts/install-deps.sh installs glslang-tools and spirv-tools")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(GLOB modules RELATIVE "${INCLUDE_DIR}" "${INCLUDE_DIR}/cloudmath/hlsl/*.hlsl" "${INCLUDE_DIR}/cloudmath/hlsl/*.ush")
list(LENGTH modules count)
if(count LESS 10)
  message(FATAL_ERROR "hlsl.compile: found only ${count} HLSL files in ${INCLUDE_DIR}/cloudmath/hlsl")
endif()
set(failures "")
foreach(module IN LISTS modules)
  string(MAKE_C_IDENTIFIER "${module}" name)
  file(WRITE "${WORK_DIR}/${name}_comp.hlsl"
    "#include \"${module}\"\nRWStructuredBuffer<float> result;\n"
    "[numthreads(8, 1, 1)] void main(uint3 id : SV_DispatchThreadID) { result[id.x] = cm_saturate(float(id.x)); }\n")
  file(WRITE "${WORK_DIR}/${name}_frag.hlsl"
    "#include \"${module}\"\nfloat4 main(float4 position : SV_Position) : SV_Target { return cm_saturate(position); }\n")
  foreach(stage comp frag)
    execute_process(COMMAND "${GLSLANG}" -D -V -S ${stage} -e main --auto-map-bindings --auto-map-locations
        "-I${INCLUDE_DIR}" "${WORK_DIR}/${name}_${stage}.hlsl" -o "${WORK_DIR}/${name}_${stage}.spv"
      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc EQUAL 0)
      execute_process(COMMAND "${SPIRV_VAL}" "${WORK_DIR}/${name}_${stage}.spv" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    endif()
    if(NOT rc EQUAL 0)
      string(APPEND failures "\n${module} (${stage}):\n${out}${err}")
    endif()
  endforeach()
endforeach()
if(failures)
  message(FATAL_ERROR "hlsl.compile: failures:${failures}")
endif()
message(STATUS "hlsl.compile: ${count} HLSL files compile as compute and pixel shaders and validate")
