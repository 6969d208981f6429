# cloudmath_pop_line(<text_var> <line_var>): moves the first line of ${text_var} (without its
# newline) into ${line_var} and removes it from ${text_var}. Walking text this way, instead
# of as a CMake list, keeps the ';' and '[' of GLSL lines intact. A macro, so it sets the
# caller's variables.
macro(cloudmath_pop_line text_var line_var)
  string(FIND "${${text_var}}" "\n" _cm_eol)
  if(_cm_eol EQUAL -1)
    set(${line_var} "${${text_var}}")
    set(${text_var} "")
  else()
    string(SUBSTRING "${${text_var}}" 0 ${_cm_eol} ${line_var})
    math(EXPR _cm_next "${_cm_eol} + 1")
    string(SUBSTRING "${${text_var}}" ${_cm_next} -1 ${text_var})
  endif()
endmacro()

# cloudmath_text_line(<text> <number> <line_var>): line <number> (1-based) of <text>, without
# its newline ("" past the end), for reports that quote the lines a compiler names.
function(cloudmath_text_line text number line_var)
  set(current 1)
  while(current LESS number AND NOT text STREQUAL "")
    cloudmath_pop_line(text skipped)
    math(EXPR current "${current} + 1")
  endwhile()
  cloudmath_pop_line(text line)
  set(${line_var} "${line}" PARENT_SCOPE)
endfunction()
