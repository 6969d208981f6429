// cloudmath/wgsl/texture_lod.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/texture_lod.glsl: GLSL twin of cloudmath/texture_lod.hpp: a pixel's
// footprint at a distance and the mip level that matches it, for textureLod in a march loop.
// Use: float lod = cm_texture_lod(cm_pixel_footprint(t, tan_half_fov, u_resolution.y), tile / size);

// distance * 2 tan_half_fov / image_height.
fn cm_pixel_footprint(distance: f32, tan_half_fov: f32, image_height: f32) -> f32 {
    return distance * (2.0 * tan_half_fov / image_height);
}

// log2(footprint / texel_size), 0 for magnification, non-positive or NaN footprints.
fn cm_texture_lod(footprint: f32, texel_size: f32) -> f32 {
    let ratio: f32 = footprint / texel_size;
    return select(0.0, log2(ratio), ratio > 1.0);
}
