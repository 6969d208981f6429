// cloudmath/hlsl/sun.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/sun.hlsl: GLSL twin of cloudmath/sun.hpp: the Sun's angular radius, the
// solid angle of a cone and the limb-darkened radiance of the sun disc for an irradiance.
// Use: sky += sun_color * cm_sun_disc_radiance(1.0, dot(view_dir, sun_dir), CM_SUN_ANGULAR_RADIUS, 0.6);
#ifndef CM_SUN_HLSL
#define CM_SUN_HLSL

#include "core.hlsl"

#define CM_SUN_ANGULAR_RADIUS 4.6524e-3

// 2 pi (1 - cos r) as 4 pi sin^2(r / 2): full precision for small cones.
float cm_cone_solid_angle(float angular_radius) {
    float s = cmi_sin_cos(angular_radius * 0.5).x; // core.hlsl: relative accuracy for small r
    return 4.0 * CM_PI * s * s;
}

// I0 (1 - u (1 - cos psi)) inside the disc, 0 outside; I0 = E / (solid angle (1 - u/3)).
float cm_sun_disc_radiance(float irradiance, float cos_angle, float angular_radius, float limb_darkening) {
    float c = clamp(cos_angle, -1.0, 1.0);
    float sin_r = cmi_sin_cos(angular_radius).x;
    float one_minus_c = 1.0 - c;
    float x2 = one_minus_c * (2.0 - one_minus_c) / (sin_r * sin_r);
    if (!(x2 <= 1.0) || c <= 0.0) return 0.0;
    float u = cm_saturate(limb_darkening);
    float peak = irradiance / (cm_cone_solid_angle(angular_radius) * (1.0 - u / 3.0));
    return peak * (1.0 - u + u * sqrt(1.0 - x2));
}

#endif // CM_SUN_HLSL
