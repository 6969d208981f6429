// cloudmath/wgsl/shadow_map.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/shadow_map.glsl: GLSL twin of cloudmath/shadow_map.hpp: the Beer shadow map's
// texel built by a march along the sunlight, the optical depth and transmittance it gives at a
// depth, and the projection of a point into the sun-aligned map.
// Use: CmBeerShadowAccumulator acc = cm_beer_shadow_accumulator();
//      cm_beer_shadow_add_step(acc, t, ds, sigma_t);  ...  out_texel = cm_beer_shadow_texel(acc);
//      vec3 uvd = cm_shadow_map_project(p, origin, right, up, toward_sun, half_extent);
//      float T = cm_beer_shadow_transmittance(texture(shadow_map, uvd.xy).xyz, uvd.z);

// front > back while the march has met no extinction; covered: the steps' length with extinction.
struct CmBeerShadowAccumulator {
    front: f32,
    back: f32,
    optical_depth: f32,
    covered: f32,
}

fn cm_beer_shadow_accumulator() -> CmBeerShadowAccumulator { return CmBeerShadowAccumulator(1.0, 0.0, 0.0, 0.0); }

// Adds the step [t, t + ds) of extinction sigma_t; steps without extinction change nothing.
fn cm_beer_shadow_add_step(acc: ptr<function, CmBeerShadowAccumulator>, t: f32, ds: f32, sigma_t: f32) {
    if (!(sigma_t > 0.0) || !(ds > 0.0)) { return; }
    if ((*acc).front > (*acc).back) { (*acc).front = t; }
    (*acc).back = t + ds;
    (*acc).optical_depth += sigma_t * ds;
    (*acc).covered += ds;
}

// (front depth, mean extinction over back - front, total optical depth); empty: 0. Steps
// shorter than the rounding of t (back == front): over their own length (finite, not +Inf).
fn cm_beer_shadow_texel(acc: CmBeerShadowAccumulator) -> vec3f {
    if (acc.front > acc.back) { return vec3f(0.0); }
    let column: f32 = select(acc.covered, acc.back - acc.front, acc.back > acc.front);
    return vec3f(acc.front, acc.optical_depth / column, acc.optical_depth);
}

// min(max(depth - front, 0) mean_extinction, total).
fn cm_beer_shadow_optical_depth(texel: vec3f, depth: f32) -> f32 {
    let d: f32 = depth - texel.x;
    if (d != d) { return d; }
    let tau: f32 = max(d, 0.0) * texel.y;
    return select(texel.z, tau, tau < texel.z);
}

fn cm_beer_shadow_transmittance(texel: vec3f, depth: f32) -> f32 {
    return exp(-cm_beer_shadow_optical_depth(texel, depth));
}

// (u, v) across the 2 half_extent square around origin, depth along the light from the plane.
fn cm_shadow_map_project(p: vec3f, origin: vec3f, right: vec3f, up: vec3f, toward_sun: vec3f, half_extent: f32) -> vec3f {
    let q: vec3f = p - origin;
    let s: f32 = 0.5 / half_extent;
    return vec3f(0.5 + dot(q, right) * s, 0.5 + dot(q, up) * s, -dot(q, toward_sun));
}
