# Rewrites include/cloudmath/glsl_embedded.hpp from include/cloudmath/glsl/*.glsl (after a
# .glsl edit), or checks it:
#   cmake -P cmake/UpdateGlslEmbedded.cmake               rewrite the committed header
#   cmake -DCHECK=ON -DWORK=<dir> -P cmake/UpdateGlslEmbedded.cmake
#                                                         fail if it is stale (the test
#                                                         glsl.embedded_current)
cmake_minimum_required(VERSION 3.20)
get_filename_component(root "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
include("${CMAKE_CURRENT_LIST_DIR}/EmbedGlsl.cmake")
set(committed "${root}/include/cloudmath/glsl_embedded.hpp")
if(CHECK)
  if(NOT WORK)
    message(FATAL_ERROR "UpdateGlslEmbedded: CHECK needs -DWORK=<scratch directory>")
  endif()
  set(fresh "${WORK}/glsl_embedded.hpp")
  file(REMOVE "${fresh}")
  cloudmath_embed_glsl("${root}/include/cloudmath/glsl" "${fresh}")
  file(READ "${fresh}" want)
  set(have "")
  if(EXISTS "${committed}")
    file(READ "${committed}" have)
  endif()
  if(NOT have STREQUAL want)
    message(FATAL_ERROR "include/cloudmath/glsl_embedded.hpp is stale (a .glsl file changed): "
                        "run `cmake -P cmake/UpdateGlslEmbedded.cmake` and commit the result")
  endif()
  message(STATUS "include/cloudmath/glsl_embedded.hpp matches include/cloudmath/glsl/*.glsl")
else()
  cloudmath_embed_glsl("${root}/include/cloudmath/glsl" "${committed}")
  message(STATUS "wrote ${committed}")
endif()
