# version.consistent: every place that states cloudmath's version agrees with project(VERSION).
#   cmake -DPROJECT_VERSION=<X.Y.Z> -DSOURCE_DIR=<repository root> -P check_version.cmake
# Checked: include/cloudmath/version.hpp (CLOUDMATH_VERSION_MAJOR/MINOR/PATCH and
# CLOUDMATH_VERSION_STRING), web/package.json and web/package-lock.json (the npm package,
# which also puts the version into web/dist/index.js; web.package_fresh checks that file),
# and CHANGELOG.md (a "## [X.Y.Z] - date" section and an "## [Unreleased]" section).
# The CMake package and the pkg-config file take PROJECT_VERSION directly. Every mismatch is
# reported, then the script fails. docs/releasing.md lists the steps of a release.
cmake_minimum_required(VERSION 3.20)

if(NOT PROJECT_VERSION MATCHES "^([0-9]+)\\.([0-9]+)\\.([0-9]+)$")
  message(FATAL_ERROR "check_version: PROJECT_VERSION '${PROJECT_VERSION}' is not X.Y.Z")
endif()
set(expected_MAJOR "${CMAKE_MATCH_1}")
set(expected_MINOR "${CMAKE_MATCH_2}")
set(expected_PATCH "${CMAKE_MATCH_3}")
set(problems "")

# version.hpp
set(header "${SOURCE_DIR}/include/cloudmath/version.hpp")
file(READ "${header}" text)
foreach(part MAJOR MINOR PATCH)
  if(text MATCHES "#define CLOUDMATH_VERSION_${part} ([0-9]+)\n")
    if(NOT CMAKE_MATCH_1 STREQUAL expected_${part})
      string(APPEND problems "\n  version.hpp says CLOUDMATH_VERSION_${part} ${CMAKE_MATCH_1}, project(VERSION) says ${PROJECT_VERSION}")
    endif()
  else()
    string(APPEND problems "\n  version.hpp has no '#define CLOUDMATH_VERSION_${part} <number>' line")
  endif()
endforeach()
if(text MATCHES "#define CLOUDMATH_VERSION_STRING \"([^\"]*)\"")
  if(NOT CMAKE_MATCH_1 STREQUAL PROJECT_VERSION)
    string(APPEND problems "\n  version.hpp says CLOUDMATH_VERSION_STRING \"${CMAKE_MATCH_1}\", project(VERSION) says ${PROJECT_VERSION}")
  endif()
else()
  string(APPEND problems "\n  version.hpp has no '#define CLOUDMATH_VERSION_STRING \"X.Y.Z\"' line")
endif()

# The npm package: package.json, and package-lock.json's two copies of the version (the
# root package is the member "" of "packages").
function(check_npm_version file label value error)
  if(error)
    string(APPEND problems "\n  ${file}: no ${label} (${error})")
  elseif(NOT value STREQUAL PROJECT_VERSION)
    string(APPEND problems "\n  ${file} says ${label} ${value}, project(VERSION) says ${PROJECT_VERSION}")
  endif()
  set(problems "${problems}" PARENT_SCOPE)
endfunction()
file(READ "${SOURCE_DIR}/web/package.json" json)
string(JSON value ERROR_VARIABLE error GET "${json}" version)
check_npm_version(web/package.json "version" "${value}" "${error}")
file(READ "${SOURCE_DIR}/web/package-lock.json" json)
string(JSON value ERROR_VARIABLE error GET "${json}" version)
check_npm_version(web/package-lock.json "version" "${value}" "${error}")
string(JSON value ERROR_VARIABLE error GET "${json}" packages "" version)
check_npm_version(web/package-lock.json "packages[\"\"].version" "${value}" "${error}")

# CHANGELOG.md (Keep a Changelog).
file(READ "${SOURCE_DIR}/CHANGELOG.md" changelog)
string(REPLACE "." "\\." escaped "${PROJECT_VERSION}")
if(NOT changelog MATCHES "\n## \\[${escaped}\\] - [0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]\n")
  string(APPEND problems "\n  CHANGELOG.md has no '## [${PROJECT_VERSION}] - YYYY-MM-DD' section")
endif()
if(NOT changelog MATCHES "\n## \\[Unreleased\\]\n")
  string(APPEND problems "\n  CHANGELOG.md has no '## [Unreleased]' section")
endif()

if(problems)
  message(FATAL_ERROR "check_version: the version is not the same everywhere:${problems}\n"
    "(docs/releasing.md lists every place a release changes)")
endif()
message(STATUS "check_version: ${PROJECT_VERSION} in version.hpp, web/package.json, web/package-lock.json and CHANGELOG.md")
