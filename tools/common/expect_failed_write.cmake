# Regression test of a program's failed writes (tools/common/atomic_file.hpp). Run as
#   cmake -DCOMMAND=<program> "-DARGS=<a;;-list>" -DWORK=<scratch dir> "-DFILES=<names>"
#         [-DSTATUS=1] -P expect_failed_write.cmake
# ARGS may contain @WORK@ (replaced by WORK). FILES are the names, relative to WORK, of the
# files the run writes. Three runs, each must exit with STATUS (default 1) and print a
# message that names the file:
#   1. the files exist and the file-size limit is 0 (sh's ulimit -f 0, SIGXFSZ ignored:
#      every write to a regular file fails, even for root, as on a full disk): every old
#      file must be untouched and WORK must hold nothing else (no temporary left behind);
#   2. no old files, the same limit: WORK must stay empty;
#   3. every file is a symbolic link to /dev/full (where there is one): the writes go to the
#      device and fail (ENOSPC), and the links must still be links (a rename over them
#      would have replaced them).
cmake_minimum_required(VERSION 3.20)
if(NOT DEFINED STATUS)
  set(STATUS 1)
endif()
string(REPLACE "@WORK@" "${WORK}" args "${ARGS}")

function(run label limit)
  if(limit)
    # No ';' in the script: it would split the CMake list.
    set(prefix sh -c "ulimit -f 0 && trap '' XFSZ && exec \"$@\"" sh)
  else()
    set(prefix "")
  endif()
  execute_process(COMMAND ${prefix} "${COMMAND}" ${args}
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status STREQUAL "${STATUS}")
    message(FATAL_ERROR "${label}: exit status ${status}, expected ${STATUS}\n--- stdout:\n${out}\n--- stderr:\n${err}")
  endif()
  list(GET FILES 0 first)
  get_filename_component(first_name "${first}" NAME)
  string(FIND "${err}" "${first_name}" named)
  if(named EQUAL -1)
    message(FATAL_ERROR "${label}: the message does not name ${first_name}:\n${err}")
  endif()
  message(STATUS "${label}: exit ${status} as expected")
endfunction()

# The names now in WORK (recursively, relative), sorted.
function(listing var)
  file(GLOB_RECURSE names LIST_DIRECTORIES false RELATIVE "${WORK}" "${WORK}/*")
  list(SORT names)
  set(${var} "${names}" PARENT_SCOPE)
endfunction()

# 1. Old files, writes failing.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
foreach(name IN LISTS FILES)
  file(WRITE "${WORK}/${name}" "old contents of ${name}\n")
endforeach()
run("old files, file-size limit 0" ON)
foreach(name IN LISTS FILES)
  file(READ "${WORK}/${name}" contents)
  if(NOT contents STREQUAL "old contents of ${name}\n")
    message(FATAL_ERROR "a failed write changed ${name}: now '${contents}'")
  endif()
endforeach()
listing(left)
set(expected ${FILES})
list(SORT expected)
if(NOT left STREQUAL expected)
  message(FATAL_ERROR "a failed write left other files behind: '${left}', expected '${expected}'")
endif()

# 2. No old files, writes failing: nothing at all may be left.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
run("no old files, file-size limit 0" ON)
listing(left)
if(left)
  message(FATAL_ERROR "a failed write left files behind: '${left}'")
endif()

# 3. Links to /dev/full.
if(EXISTS /dev/full)
  file(REMOVE_RECURSE "${WORK}")
  file(MAKE_DIRECTORY "${WORK}")
  foreach(name IN LISTS FILES)
    file(CREATE_LINK /dev/full "${WORK}/${name}" SYMBOLIC)
  endforeach()
  run("links to /dev/full" OFF)
  foreach(name IN LISTS FILES)
    if(NOT IS_SYMLINK "${WORK}/${name}")
      message(FATAL_ERROR "${name} was a link to /dev/full and is not one any more")
    endif()
  endforeach()
endif()
file(REMOVE_RECURSE "${WORK}")
