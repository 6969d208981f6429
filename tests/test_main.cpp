// doctest's main, compiled once per build variant (plain, fast-math, sanitizers).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
