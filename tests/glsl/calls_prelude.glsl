// Prelude of the test shaders built from calls.txt: goes after the #version line and
// before the cloudmath module. Defines the configuration macros that enable the generic
// forms, and declares their user functions, which calls_helpers.glsl defines after the
// module (a function named by CM_MS_PHASE, CM_CONE_EXTINCTION or CM_ATMOSPHERE_TABLE only has to be declared
// before the include, so it can itself use cloudmath).
float cm_test_phase(float mu, float scale);
float cm_test_extinction(vec3 p, int i);
#define CM_MS_PHASE cm_test_phase
#define CM_DIFFUSION_PHASE cm_test_phase
#define CM_CONE_EXTINCTION cm_test_extinction
vec3 cm_test_atmosphere_table(int part, int x, int y);
#define CM_ATMOSPHERE_TABLE cm_test_atmosphere_table

// Vector results as one float: the sum of the components (one dot product).
float cm_test_sum(vec2 v) { return dot(v, vec2(1.0)); }
float cm_test_sum(vec3 v) { return dot(v, vec3(1.0)); }
float cm_test_sum(vec4 v) { return dot(v, vec4(1.0)); }
