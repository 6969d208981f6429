# docs.snippets: every ```cpp, ```glsl, ```hlsl and ```wgsl block of the given Markdown files
# compiles, so the code a user copies from the README works as written.
#   cpp blocks:  compiled alone as a translation unit (-std=c++17 -fsyntax-only, -I include),
#                so each block is complete: its #includes, its declarations, no free names.
#   glsl blocks: compiled by glslangValidator to OpenGL SPIR-V as a fragment shader (#version 450 and
#                GL_GOOGLE_include_directive prepended, -I include, so
#                #include "cloudmath/glsl/..." resolves); each block declares what it uses.
#   hlsl blocks: compiled by glslang's HLSL front end to SPIR-V (-D -V, checked by spirv-val)
#                as the engines lay the files out: a Unity block (#pragma kernel K: a compute
#                shader, entry K) finds "Assets/CloudMath/hlsl/..." and an Unreal block (a pixel
#                shader, entry MainPS) finds "/Plugin/CloudMath/CloudMath.ush" (glslang has no
#                virtual shader paths, so the leading / is dropped and -I points at a copy).
#   wgsl blocks: validated by Chromium's WebGPU (web/test/wgsl_validate.mjs) after
#                include/cloudmath/wgsl/cloudmath.wgsl, which each block says it assumes.
# cmake -DCXX=<compiler> -DGLSLANG=<glslangValidator or empty> [-DSPIRV_VAL=<spirv-val>]
#       [-DNODE=<node> -DCHROMIUM=<chromium>] -DSRC=<repository> -DWORK=<scratch dir>
#       -DFILES=README.md;docs/integration.md -P doc_snippets.cmake
# A missing tool for a block's language fails the test (the block would go unchecked).
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/TextLines.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
# The engines' layouts of the shipped HLSL (see above).
file(COPY "${SRC}/include/cloudmath/hlsl" DESTINATION "${WORK}/unity/Assets/CloudMath")
file(COPY "${SRC}/include/cloudmath/hlsl/CloudMath.ush" DESTINATION "${WORK}/unreal/Plugin/CloudMath")
set(failures "")
set(count 0)
foreach(doc IN LISTS FILES)
  file(READ "${SRC}/${doc}" text)
  set(lang "")
  set(block "")
  set(line_no 0)
  set(start 0)
  while(NOT text STREQUAL "")
    cloudmath_pop_line(text line)
    math(EXPR line_no "${line_no} + 1")
    if(lang STREQUAL "")
      if(line MATCHES "^```(cpp|glsl|hlsl|wgsl)[ \t]*$")
        set(lang "${CMAKE_MATCH_1}")
        set(block "")
        set(start ${line_no})
      endif()
    elseif(line MATCHES "^```[ \t]*$")
      math(EXPR count "${count} + 1")
      string(MAKE_C_IDENTIFIER "${doc}_${start}" name)
      if(lang STREQUAL "cpp")
        file(WRITE "${WORK}/${name}.cpp" "${block}")
        execute_process(COMMAND "${CXX}" -std=c++17 -fsyntax-only -Wall -Wextra -I "${SRC}/include" "${WORK}/${name}.cpp"
          RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
      elseif(lang STREQUAL "hlsl")
        if(block MATCHES "#pragma kernel ([A-Za-z_0-9]+)")
          set(stage comp)
          set(entry "${CMAKE_MATCH_1}")
          set(include_root "${WORK}/unity")
        else()
          set(stage frag)
          set(entry MainPS)
          set(include_root "${WORK}/unreal")
        endif()
        string(REPLACE "#include \"/Plugin/" "#include \"Plugin/" hlsl_block "${block}")
        file(WRITE "${WORK}/${name}.hlsl" "${hlsl_block}")
        if(NOT GLSLANG OR NOT SPIRV_VAL)
          message(FATAL_ERROR "doc_snippets: ${doc}:${start}: an hlsl block needs glslangValidator and spirv-val")
        endif()
        execute_process(COMMAND "${GLSLANG}" -D -V -S ${stage} -e ${entry} --auto-map-bindings --auto-map-locations
            "-I${include_root}" "${WORK}/${name}.hlsl" -o "${WORK}/${name}.spv"
          RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
        if(rc EQUAL 0)
          execute_process(COMMAND "${SPIRV_VAL}" "${WORK}/${name}.spv" RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
        endif()
      elseif(lang STREQUAL "wgsl")
        if(NOT NODE OR NOT CHROMIUM)
          message(FATAL_ERROR "doc_snippets: ${doc}:${start}: a wgsl block needs node and chromium")
        endif()
        file(WRITE "${WORK}/${name}.wgsl" "${block}")
        execute_process(COMMAND "${NODE}" "${SRC}/web/test/wgsl_validate.mjs" --chromium "${CHROMIUM}"
            --prepend "${SRC}/include/cloudmath/wgsl/cloudmath.wgsl" "${WORK}/${name}.wgsl"
          RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
      elseif(GLSLANG)
        file(WRITE "${WORK}/${name}.frag"
          "#version 450\n#extension GL_GOOGLE_include_directive : require\n${block}")
        execute_process(COMMAND "${GLSLANG}" -G --auto-map-locations "-I${SRC}/include" "${WORK}/${name}.frag" -o "${WORK}/${name}.spv"
          RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
      else()
        set(rc 0)
        message(STATUS "${doc}:${start}: glsl block not checked (no glslangValidator)")
      endif()
      if(NOT rc EQUAL 0)
        string(APPEND failures "\n${doc}:${start}: the ${lang} block does not compile:\n${out}${err}")
      endif()
      set(lang "")
    else()
      string(APPEND block "${line}\n")
    endif()
  endwhile()
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "doc_snippets: no code block found in ${FILES}")
endif()
if(NOT failures STREQUAL "")
  message(FATAL_ERROR "doc_snippets:${failures}")
endif()
message(STATUS "doc_snippets: ${count} code blocks compile")
