// cloudmath/wgsl/sun.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/sun.glsl: GLSL twin of cloudmath/sun.hpp: the Sun's angular radius, the
// solid angle of a cone and the limb-darkened radiance of the sun disc for an irradiance.
// Use: sky += sun_color * cm_sun_disc_radiance(1.0, dot(view_dir, sun_dir), CM_SUN_ANGULAR_RADIUS, 0.6);

const CM_SUN_ANGULAR_RADIUS = 4.6524e-3;

// 2 pi (1 - cos r) as 4 pi sin^2(r / 2): full precision for small cones.
fn cm_cone_solid_angle(angular_radius: f32) -> f32 {
    let s: f32 = cmi_sin_cos(angular_radius * 0.5).x; // core.glsl: relative accuracy for small r
    return 4.0 * CM_PI * s * s;
}

// I0 (1 - u (1 - cos psi)) inside the disc, 0 outside; I0 = E / (solid angle (1 - u/3)).
fn cm_sun_disc_radiance(irradiance: f32, cos_angle: f32, angular_radius: f32, limb_darkening: f32) -> f32 {
    let c: f32 = clamp(cos_angle, -1.0, 1.0);
    let sin_r: f32 = cmi_sin_cos(angular_radius).x;
    let one_minus_c: f32 = 1.0 - c;
    let x2: f32 = one_minus_c * (2.0 - one_minus_c) / (sin_r * sin_r);
    if (!(x2 <= 1.0) || c <= 0.0) { return 0.0; }
    let u: f32 = cm_saturate(limb_darkening);
    let peak: f32 = irradiance / (cm_cone_solid_angle(angular_radius) * (1.0 - u / 3.0));
    return peak * (1.0 - u + u * sqrt(1.0 - x2));
}
