# The list of cloudmath's public C++ functions, shared by the checks that need it
# (check_coverage.cmake, glsl/check_twins.cmake). include() it from a cmake -P script.
#
# Rule, kept deliberately simple so it needs no C++ parser:
# - A public function is any function declared with [[nodiscard]] in <header_dir>/*.hpp
#   (not recursive: glsl/ and other subfolders are not C++ API). Its name is the identifier
#   immediately before the first "(" after the attribute; the declaration may span lines.
#   Operators are skipped, overloads count once. Helpers in `namespace detail` carry no
#   [[nodiscard]] by convention, so they are not public and need no namespace parsing.
# - Comments are removed first, so a "[[nodiscard]]" in prose changes nothing. (A "/*"
#   inside a "//" comment, as in "glsl/*.glsl", does not open a block comment.)
# void functions (march_accumulator::add_segment) have no [[nodiscard]], so they are not
# in the list.

# cloudmath_read_source(<path> <out_var>): the file's text with comments removed.
# Semicolons become "}" because CMake treats ";" as a list separator (and "}" still ends a
# declaration for the regexes here); the other square brackets become spaces so that "x[i]"
# cannot read as a call to x. [[nodiscard]] becomes " CLOUDMATH_NODISCARD ".
function(cloudmath_read_source path out)
  file(READ "${path}" text)
  # Left to right, whichever comment starts first: a "//" comment runs to the end of its
  # line (so "glsl/*.glsl" inside one opens no block comment), a "/*" comment to the next
  # "*/". Text already scanned moves to `kept`, so each step searches only the rest.
  set(kept "")
  while(1)
    string(FIND "${text}" "//" line_start)
    string(FIND "${text}" "/*" block_start)
    if(line_start EQUAL -1 AND block_start EQUAL -1)
      break()
    endif()
    if(NOT line_start EQUAL -1 AND (block_start EQUAL -1 OR line_start LESS block_start))
      string(SUBSTRING "${text}" 0 ${line_start} head)
      string(SUBSTRING "${text}" ${line_start} -1 text)
      string(FIND "${text}" "\n" end)
      if(end EQUAL -1)
        set(text "")
      else()
        string(SUBSTRING "${text}" ${end} -1 text)  # keeps the newline
      endif()
      string(APPEND kept "${head}")
    else()
      string(SUBSTRING "${text}" 0 ${block_start} head)
      string(SUBSTRING "${text}" ${block_start} -1 text)
      string(FIND "${text}" "*/" end)
      if(end EQUAL -1)
        set(text "")
      else()
        math(EXPR after "${end} + 2")
        string(SUBSTRING "${text}" ${after} -1 text)
      endif()
      string(APPEND kept "${head} ")
    endif()
  endwhile()
  set(text "${kept}${text}")
  string(REPLACE ";" "}" text "${text}")
  string(REPLACE "[[nodiscard]]" " CLOUDMATH_NODISCARD " text "${text}")
  string(REPLACE "[" " " text "${text}")
  string(REPLACE "]" " " text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# cloudmath_public_functions(<header_dir> <out_var>): sorted, duplicate-free names of the
# public functions declared in <header_dir>/*.hpp (rule above). Stops with an error when a
# declaration's name cannot be found.
function(cloudmath_public_functions header_dir out)
  file(GLOB headers "${header_dir}/*.hpp")
  set(names "")
  foreach(header IN LISTS headers)
    cloudmath_read_source("${header}" text)
    # Attribute, then anything up to the first "(" that does not cross a "}" or "{".
    string(REGEX MATCHALL " CLOUDMATH_NODISCARD [^(){}]*\\(" declarations "${text}")
    foreach(declaration IN LISTS declarations)
      if(declaration MATCHES "(^|[^A-Za-z0-9_])operator([^A-Za-z0-9_]|$)")
        continue()
      endif()
      if(declaration MATCHES "([A-Za-z_][A-Za-z0-9_]*)[ \t\r\n]*\\($")
        list(APPEND names "${CMAKE_MATCH_1}")
      else()
        message(FATAL_ERROR "public_functions: cannot find the name in '${declaration}' (${header})")
      endif()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES names)
  list(SORT names)
  set(${out} "${names}" PARENT_SCOPE)
endfunction()
