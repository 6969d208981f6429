# C++/GLSL twin manifest check. Run as:
#   cmake -DHEADER_DIR=<dir with *.hpp> -DGLSL_DIR=<dir with *.glsl> -DTWINS=<twins.txt>
#         -DPARITY=<test_glsl_parity.cpp> [-DCALLS=<calls.txt>] [-DMIN_PUBLIC=<n>]
#         [-DMIN_GLSL=<n>] [-DHLSL_DIR=<dir>] [-DWGSL_DIR=<dir>] -P check_twins.cmake
#
# twins.txt has one line per C++ public function (blank lines and "#" comments ignored):
#   <cpp_name>: <cm_name> [<cm_name> ...]      its GLSL twin(s)
#   <cpp_name>: C++ only -- <reason>           no twin, and why
# Rules (every violation is listed, then the check fails):
# - every C++ public function (cloudmath_public_functions() of tests/public_functions.cmake:
#   any [[nodiscard]] function in HEADER_DIR/*.hpp) has a line. Other C++ names may have
#   one too (march_accumulator::add_segment is void, so it carries no [[nodiscard]]), but
#   they must be identifiers that occur in the headers (catches typos);
# - no C++ name has two lines;
# - every GLSL public function has a line: a definition at the start of a line,
#   `<type> cm_name(`, in GLSL_DIR/*.glsl (cmi_ helpers are internal);
# - every cm_ name of twins.txt is defined in the GLSL;
# - the twin's name is cm_<cpp_name>, or cm_<prefix>_<cpp_name> for members of a type
#   (is_opaque -> cm_march_is_opaque);
# - every cm_ name of twins.txt (that the GLSL defines) has a parity case: it occurs
#   followed by "(" in PARITY (comments removed);
# - with HLSL_DIR / WGSL_DIR: every twin is defined in the HLSL / WGSL twins too, with as
#   many overloads (a C++ function whose twin is missing in any language fails);
# - with CALLS: calls.txt has exactly one line per GLSL overload (as many lines naming a
#   function as it has definitions), and only names the GLSL defines.
# MIN_PUBLIC / MIN_GLSL (default 5) guard against a parse that silently finds nothing.
cmake_minimum_required(VERSION 3.20)

include("${CMAKE_CURRENT_LIST_DIR}/../public_functions.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/calls.cmake")

foreach(var HEADER_DIR GLSL_DIR)
  if(NOT IS_DIRECTORY "${${var}}")
    message(FATAL_ERROR "check_twins: ${var}='${${var}}' is not a directory")
  endif()
endforeach()
if(NOT EXISTS "${TWINS}")
  message(FATAL_ERROR "check_twins: TWINS='${TWINS}' does not exist")
endif()
if(NOT DEFINED PARITY OR PARITY STREQUAL "")
  message(FATAL_ERROR "check_twins: pass -DPARITY=<path of the parity test source>")
endif()
foreach(var MIN_PUBLIC MIN_GLSL)
  if(NOT DEFINED ${var})
    set(${var} 5)
  endif()
endforeach()

set(problems "")
macro(problem text)
  list(APPEND problems "${text}")
endmacro()

# --- C++ side -------------------------------------------------------------------------------
cloudmath_public_functions("${HEADER_DIR}" cpp_public)
list(LENGTH cpp_public cpp_count)
if(cpp_count LESS MIN_PUBLIC)
  message(FATAL_ERROR "check_twins: found only ${cpp_count} C++ public functions in "
    "${HEADER_DIR} (expected at least ${MIN_PUBLIC}); the parse is probably broken")
endif()
file(GLOB headers "${HEADER_DIR}/*.hpp")
set(all_headers "")
foreach(header IN LISTS headers)
  cloudmath_read_source("${header}" text)
  string(APPEND all_headers "\n${text}")
endforeach()

# --- GLSL side: name -> number of definitions (overloads) ----------------------------------
file(GLOB glsl_files "${GLSL_DIR}/*.glsl")
set(glsl_functions "")
foreach(glsl_file IN LISTS glsl_files)
  cloudmath_read_source("${glsl_file}" text)
  string(REGEX MATCHALL "\n[A-Za-z_][A-Za-z0-9_]*[ \t]+cm_[A-Za-z0-9_]*[ \t]*\\("
    definitions "\n${text}")
  foreach(definition IN LISTS definitions)
    string(REGEX REPLACE ".*[ \t](cm_[A-Za-z0-9_]*)[ \t]*\\($" "\\1" name "${definition}")
    list(APPEND glsl_functions "${name}")
    if(NOT DEFINED overloads_${name})
      set(overloads_${name} 0)
    endif()
    math(EXPR overloads_${name} "${overloads_${name}} + 1")
  endforeach()
endforeach()
list(REMOVE_DUPLICATES glsl_functions)
list(SORT glsl_functions)
list(LENGTH glsl_functions glsl_count)
if(glsl_count LESS MIN_GLSL)
  message(FATAL_ERROR "check_twins: found only ${glsl_count} cm_ functions in ${GLSL_DIR} "
    "(expected at least ${MIN_GLSL}); the parse is probably broken")
endif()

# --- the manifest -------------------------------------------------------------------------------
# One list element per line: ";" and square brackets (which CMake lists treat specially) can
# only occur in reasons, so they are softened first.
file(READ "${TWINS}" manifest_text)
string(REPLACE ";" "," manifest_text "${manifest_text}")
string(REPLACE "[" "(" manifest_text "${manifest_text}")
string(REPLACE "]" ")" manifest_text "${manifest_text}")
string(REPLACE "\n" ";" manifest_lines "${manifest_text}")
set(manifest_cpp "")
set(manifest_cm "")
set(line_number 0)
foreach(line IN LISTS manifest_lines)
  math(EXPR line_number "${line_number} + 1")
  string(STRIP "${line}" line)
  if(line STREQUAL "" OR line MATCHES "^#")
    continue()
  endif()
  if(NOT line MATCHES "^([A-Za-z_][A-Za-z0-9_]*)[ \t]*:[ \t]*(.*)$")
    problem("twins.txt:${line_number}: not '<cpp_name>: <cm_name> ...' or '<cpp_name>: C++ only -- <reason>': ${line}")
    continue()
  endif()
  set(cpp "${CMAKE_MATCH_1}")
  set(rest "${CMAKE_MATCH_2}")
  if(cpp IN_LIST manifest_cpp)
    problem("twins.txt:${line_number}: ${cpp} is listed twice")
  endif()
  list(APPEND manifest_cpp "${cpp}")
  if(NOT cpp IN_LIST cpp_public AND NOT all_headers MATCHES "(^|[^A-Za-z0-9_])${cpp}([^A-Za-z0-9_]|$)")
    problem("twins.txt:${line_number}: ${cpp} is not a name in ${HEADER_DIR}/*.hpp")
  endif()
  if(rest MATCHES "^C\\+\\+ only")
    if(NOT rest MATCHES "^C\\+\\+ only -- [^ \t]")
      problem("twins.txt:${line_number}: ${cpp}: 'C++ only' needs ' -- <reason>'")
    endif()
    continue()
  endif()
  string(REGEX REPLACE "[ \t]+" ";" twins "${rest}")
  if(twins STREQUAL "")
    problem("twins.txt:${line_number}: ${cpp} names no GLSL twin (or 'C++ only -- <reason>')")
  endif()
  foreach(twin IN LISTS twins)
    if(NOT twin MATCHES "^cm_[A-Za-z0-9_]+$")
      problem("twins.txt:${line_number}: '${twin}' is not a cm_ name")
      continue()
    endif()
    list(APPEND manifest_cm "${twin}")
    if(NOT twin IN_LIST glsl_functions)
      problem("twins.txt:${line_number}: ${twin} (twin of ${cpp}) is not defined in ${GLSL_DIR}/*.glsl")
    endif()
    if(NOT twin STREQUAL "cm_${cpp}" AND NOT twin MATCHES "^cm_[A-Za-z0-9_]+_${cpp}$")
      problem("twins.txt:${line_number}: ${twin} is not named after ${cpp} (cm_${cpp} or cm_<type>_${cpp})")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES manifest_cm)

foreach(name IN LISTS cpp_public)
  if(NOT name IN_LIST manifest_cpp)
    problem("C++ public function ${name} has no line in twins.txt")
  endif()
endforeach()
foreach(name IN LISTS glsl_functions)
  if(NOT name IN_LIST manifest_cm)
    problem("GLSL function ${name} is not the twin of anything in twins.txt")
  endif()
endforeach()

# --- HLSL and WGSL twins (generated from the GLSL by tools/shader_translate) ------------------
# With HLSL_DIR: every twin of the manifest is defined there as often as in the GLSL (HLSL
# keeps the GLSL overloads). With WGSL_DIR: `fn cm_name(` once and `fn cm_name_<types>(` for
# each further overload (WGSL has none; <types> are the parameter codes f i u b v3 iv2 ...).
set(language_count 0)
if(DEFINED HLSL_DIR AND NOT HLSL_DIR STREQUAL "")
  math(EXPR language_count "${language_count} + 1")
  file(GLOB hlsl_files "${HLSL_DIR}/*.hlsl")
  set(hlsl_text "")
  foreach(f IN LISTS hlsl_files)
    file(READ "${f}" t)
    string(APPEND hlsl_text "\n${t}")
  endforeach()
  foreach(name IN LISTS manifest_cm)
    if(NOT name IN_LIST glsl_functions)
      continue()
    endif()
    string(REGEX MATCHALL "\n[A-Za-z_][A-Za-z0-9_]*[ \t]+${name}[ \t]*\\(" defs "${hlsl_text}")
    list(LENGTH defs n)
    if(NOT n EQUAL overloads_${name})
      problem("HLSL: ${name} has ${n} definition(s) in ${HLSL_DIR}/*.hlsl, the GLSL ${overloads_${name}}")
    endif()
  endforeach()
endif()
if(DEFINED WGSL_DIR AND NOT WGSL_DIR STREQUAL "")
  math(EXPR language_count "${language_count} + 1")
  file(GLOB wgsl_files "${WGSL_DIR}/*.wgsl")
  list(FILTER wgsl_files EXCLUDE REGEX "/cloudmath\\.wgsl$")  # the modules concatenated
  set(wgsl_text "")
  foreach(f IN LISTS wgsl_files)
    file(READ "${f}" t)
    string(APPEND wgsl_text "\n${t}")
  endforeach()
  foreach(name IN LISTS manifest_cm)
    if(NOT name IN_LIST glsl_functions)
      continue()
    endif()
    string(REGEX MATCHALL "\nfn ${name}[ \t]*\\(" plain "${wgsl_text}")
    string(REGEX MATCHALL "\nfn ${name}_(f|i|u|b|[iub]?v[234]|[A-Z][A-Za-z0-9]*)+[ \t]*\\(" suffixed "${wgsl_text}")
    list(LENGTH plain n_plain)
    list(LENGTH suffixed n_suffixed)
    math(EXPR n "${n_plain} + ${n_suffixed}")
    if(NOT n_plain EQUAL 1 OR NOT n EQUAL overloads_${name})
      problem("WGSL: ${name} has ${n_plain} plain and ${n_suffixed} suffixed definition(s) in ${WGSL_DIR}/*.wgsl, the GLSL ${overloads_${name}} overload(s)")
    endif()
  endforeach()
endif()

# --- parity cases ---------------------------------------------------------------------------------
if(NOT EXISTS "${PARITY}")
  problem("${PARITY} does not exist (yet): no cm_ function has a parity case (each twin must be called there as `cm_name(`)")
else()
  cloudmath_read_source("${PARITY}" parity_text)
  foreach(name IN LISTS manifest_cm)
    if(NOT name IN_LIST glsl_functions)
      continue()  # already reported as not defined
    endif()
    if(NOT parity_text MATCHES "(^|[^A-Za-z0-9_])${name}[ \t]*\\(")
      problem("${name} has no parity case: no `${name}(` in ${PARITY}")
    endif()
  endforeach()
endif()

# --- calls.txt: one line per overload ------------------------------------------------------------
if(DEFINED CALLS AND NOT CALLS STREQUAL "")
  cloudmath_parse_calls("${CALLS}" call_names call_body)
  set(seen "")
  foreach(name IN LISTS call_names)
    if(NOT DEFINED calls_${name})
      set(calls_${name} 0)
      list(APPEND seen "${name}")
    endif()
    math(EXPR calls_${name} "${calls_${name}} + 1")
  endforeach()
  foreach(name IN LISTS seen)
    if(NOT name IN_LIST glsl_functions)
      problem("calls.txt names ${name}, which ${GLSL_DIR}/*.glsl does not define")
    endif()
  endforeach()
  foreach(name IN LISTS glsl_functions)
    if(NOT DEFINED calls_${name})
      set(calls_${name} 0)
    endif()
    if(NOT calls_${name} EQUAL overloads_${name})
      problem("calls.txt has ${calls_${name}} line(s) for ${name}, which has ${overloads_${name}} overload(s)")
    endif()
  endforeach()
endif()

# --- verdict ---------------------------------------------------------------------------------------
list(LENGTH manifest_cm twin_count)
if(problems)
  list(LENGTH problems problem_count)
  list(JOIN problems "\n  " listing)
  message(FATAL_ERROR "check_twins: ${problem_count} problem(s) (manifest ${TWINS}):\n  ${listing}")
endif()
message(STATUS "check_twins: ${cpp_count} C++ public functions and ${glsl_count} GLSL functions "
  "(${twin_count} twins) are all in ${TWINS}, each twin with a parity case"
  " and defined in ${language_count} more shading language(s)")
