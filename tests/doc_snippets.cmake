# docs.snippets: every ```cpp and ```glsl block of the given Markdown files compiles, so the
# code a user copies from the README works as written.
#   cpp blocks:  compiled alone as a translation unit (-std=c++17 -fsyntax-only, -I include),
#                so each block is complete: its #includes, its declarations, no free names.
#   glsl blocks: compiled by glslangValidator to OpenGL SPIR-V as a fragment shader (#version 450 and
#                GL_GOOGLE_include_directive prepended, -I include, so
#                #include "cloudmath/glsl/..." resolves); each block declares what it uses.
# cmake -DCXX=<compiler> -DGLSLANG=<glslangValidator or empty> -DSRC=<repository>
#       -DWORK=<scratch dir> -DFILES=README.md;docs/integration.md -P doc_snippets.cmake
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/TextLines.cmake")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
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
      if(line MATCHES "^```(cpp|glsl)[ \t]*$")
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
  message(FATAL_ERROR "doc_snippets: no cpp or glsl block found in ${FILES}")
endif()
if(NOT failures STREQUAL "")
  message(FATAL_ERROR "doc_snippets:${failures}")
endif()
message(STATUS "doc_snippets: ${count} code blocks compile")
