# cloudmath_strict_warnings(<target>)
# Every target we compile (tests, header checks, examples, benchmarks) treats warnings as
# errors: the headers are meant to be dropped into engines that build with strict flags,
# so a conversion or shadowing warning in them is a bug for our users.
# Only GCC and Clang are handled; other compilers get their default warnings.
function(cloudmath_strict_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow -Werror)
  endif()
endfunction()
