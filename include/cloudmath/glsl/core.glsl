// cloudmath/glsl/core.glsl: GLSL twin of cloudmath/core.hpp (constants, saturate, remap,
// smoothstep_safe, stable exponential helpers).
//
// Use:      #include "cloudmath/glsl/core.glsl"   (GL_GOOGLE_include_directive, shaderc,
//           GL_ARB_shading_language_include), or cloudmath::glsl_source("core") for raw GL.
// Targets:  function bodies valid in GLSL 3.30 core, GLSL ES 3.00 and Vulkan GLSL 4.50;
//           float only. Same names as the C++ with the cm_ prefix, same argument order.
// Bad input: handled with comparisons, as in C++; nothing relies on NaN or Inf behaviour,
//           which differs between drivers.
#ifndef CM_CORE_GLSL
#define CM_CORE_GLSL

#define CM_PI 3.14159265358979
#define CM_TWO_PI 6.28318530717959
#define CM_FOUR_PI 12.5663706143592
#define CM_INV_PI 0.318309886183791
#define CM_INV_FOUR_PI 0.0795774715459477

float cm_saturate(float x) { return clamp(x, 0.0, 1.0); }
vec2 cm_saturate(vec2 x) { return clamp(x, 0.0, 1.0); }
vec3 cm_saturate(vec3 x) { return clamp(x, 0.0, 1.0); }
vec4 cm_saturate(vec4 x) { return clamp(x, 0.0, 1.0); }

// Unclamped remap; a degenerate old range is the step of the clamped remap (finite).
float cm_remap(float x, float old_min, float old_max, float new_min, float new_max) {
    if (old_max == old_min) return x < old_min ? new_min : new_max;
    return new_min + (x - old_min) / (old_max - old_min) * (new_max - new_min);
}

// Remap clamped to the new range; t is clamped before scaling, end points exact.
float cm_remap_clamped(float x, float old_min, float old_max, float new_min, float new_max) {
    if (old_max == old_min) return x < old_min ? new_min : new_max;
    float t = cm_saturate((x - old_min) / (old_max - old_min));
    return (1.0 - t) * new_min + t * new_max;
}

// GLSL smoothstep defined for every pair of edges (GLSL leaves edge0 >= edge1 undefined).
float cm_smoothstep_safe(float edge0, float edge1, float x) {
    float t = cm_remap_clamped(x, edge0, edge1, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// (1 - exp(-x)) / x, 1 at x = 0. GLSL has no expm1, and the u = exp(-x); (u - 1) / log(u)
// trick fails where exp and log are approximations near 0 and 1 (measured on Mesa llvmpipe:
// errors up to 1e23). Below |x| = 0.25 the degree-6 Taylor polynomial in Horner form
// (truncation error below 1.6e-9); above, the quotient, whose cancellation is then at most
// a factor 4.5. Agrees with the C++ expm1 form to about 1e-7.
float cm_one_minus_exp_neg_over_x(float x) {
    if (abs(x) < 0.25) {
        return 1.0 + x * (-1.0 / 2.0 + x * (1.0 / 6.0 + x * (-1.0 / 24.0 + x * (1.0 / 120.0 +
               x * (-1.0 / 720.0 + x * (1.0 / 5040.0))))));
    }
    return (1.0 - exp(-x)) / x;
}
vec3 cm_one_minus_exp_neg_over_x(vec3 x) {
    return vec3(cm_one_minus_exp_neg_over_x(x.x), cm_one_minus_exp_neg_over_x(x.y),
                cm_one_minus_exp_neg_over_x(x.z));
}

// 1 - exp(-x) with full relative precision for tiny x: x (1 - exp(-x)) / x.
float cm_one_minus_exp_neg(float x) { return x * cm_one_minus_exp_neg_over_x(x); }
vec3 cm_one_minus_exp_neg(vec3 x) { return x * cm_one_minus_exp_neg_over_x(x); }

#endif  // CM_CORE_GLSL
