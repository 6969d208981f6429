# Test of cloudmath_bake_textures. Run as:
#   cmake -DTOOL=<path of cloudmath_bake_textures> -DOUT=<scratch dir> -P test_bake_textures.cmake
# Bakes a tiny set (8^3 base and detail, 16^2 curl and weather), checks that every raw file
# has the right byte count and every PNG exists, that the same seed reproduces the bytes and
# another seed does not, and that bad command lines exit with status 2 and print the usage.
cmake_minimum_required(VERSION 3.20)

file(REMOVE_RECURSE "${OUT}")
set(small --base-size 8 --detail-size 8 --curl-size 16 --weather-size 16)

function(run_tool out_dir)
  execute_process(COMMAND "${TOOL}" --out "${out_dir}" ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cloudmath_bake_textures ${ARGN} failed (${rc}):\n${stdout}\n${stderr}")
  endif()
  if(NOT stdout MATCHES "total bake")
    message(FATAL_ERROR "no bake times in the output:\n${stdout}")
  endif()
  if(NOT stderr MATCHES "baking base 8x8x8 rgba8: 100%")
    message(FATAL_ERROR "no progress line on stderr:\n${stderr}")
  endif()
endfunction()

run_tool("${OUT}/a" ${small} --seed 5 --threads 2)
foreach(entry
    "base_8x8x8_rgba8.raw=2048" "detail_8x8x8_rgb8.raw=1536"
    "curl_16x16_rgb8.raw=768" "weather_16x16_rgb8.raw=768")
  string(REPLACE "=" ";" pair "${entry}")
  list(GET pair 0 name)
  list(GET pair 1 bytes)
  file(SIZE "${OUT}/a/${name}" size)
  if(NOT size EQUAL bytes)
    message(FATAL_ERROR "${name}: ${size} bytes, expected ${bytes}")
  endif()
endforeach()
foreach(png base_r_z0 base_a_z4 base_r_z0_tiled2x2 detail_b_z4 curl_16x16 weather_16x16)
  if(NOT EXISTS "${OUT}/a/${png}.png")
    message(FATAL_ERROR "missing ${png}.png")
  endif()
endforeach()

# Same seed, one thread: identical bytes. Another seed: different bytes.
run_tool("${OUT}/b" ${small} --seed 5 --threads 1)
run_tool("${OUT}/c" ${small} --seed=6)
file(SHA256 "${OUT}/a/base_8x8x8_rgba8.raw" a)
file(SHA256 "${OUT}/b/base_8x8x8_rgba8.raw" b)
file(SHA256 "${OUT}/c/base_8x8x8_rgba8.raw" c)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "the same seed gave different bytes with 1 and 2 threads")
endif()
if(a STREQUAL c)
  message(FATAL_ERROR "seeds 5 and 6 gave the same bytes")
endif()

# Bad command lines: exit status 2 and the usage on stderr.
foreach(bad "--bogus" "--seed;abc" "--seed;-1" "--seed;4294967296" "--threads" "--base-size;513"
            "--weather-size;1e3" "--curl-size=" "extra")
  execute_process(COMMAND "${TOOL}" --out "${OUT}/bad" ${bad}
    RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  if(NOT rc EQUAL 2 OR NOT stderr MATCHES "usage: cloudmath_bake_textures")
    message(FATAL_ERROR "'${bad}': expected exit 2 and the usage, got ${rc}:\n${stderr}")
  endif()
endforeach()
if(EXISTS "${OUT}/bad")
  message(FATAL_ERROR "a rejected command line created its output directory")
endif()
message(STATUS "cloudmath_bake_textures: files, determinism and errors as expected")
