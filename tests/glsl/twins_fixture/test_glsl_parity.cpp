// Input of glsl.twins_detects_missing (read by check_twins.cmake, never compiled).
// Parity cases for cm_fixture_alpha and cm_fixture_add; cm_fixture_beta(x) appears only in
// this comment, which does not count.
const char* const cases[] = {"cm_fixture_alpha(a.x)", "cm_fixture_add (s, a.x)"};
