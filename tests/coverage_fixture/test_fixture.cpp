// Input for coverage.detects_untested (read by check_coverage.cmake, never compiled).
// Calls foo_bar only. The mention of multi_line_name(1.0f, 2.0f) in this comment must not
// count as a use, because the checker strips comments.
#include "fixture.hpp"

/* multi_line_name(3.0, 4.0) inside a block comment does not count either. */
[[maybe_unused]] static const float used = fixture::foo_bar(2.0f);
[[maybe_unused]] static float multi_line_name_value = 0.0f;  // longer identifier, not a call
