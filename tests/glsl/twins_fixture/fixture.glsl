// Input of glsl.twins_detects_missing (read by check_twins.cmake, never compiled).
float cmi_fixture_helper(float x) { return x; }  // internal: needs no manifest line
float cm_fixture_alpha(float x) { return cmi_fixture_helper(x); }
float cm_fixture_beta(float x) { return x; }
vec2 cm_fixture_beta(vec2 x) { return x; }
void cm_fixture_add(inout float sum, float x) { sum += x; }
float cm_fixture_delta(float x) { return x; }
