// cloudmath/hlsl/texture_lod.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/texture_lod.hlsl: GLSL twin of cloudmath/texture_lod.hpp: a pixel's
// footprint at a distance and the mip level that matches it, for textureLod in a march loop.
// Use: float lod = cm_texture_lod(cm_pixel_footprint(t, tan_half_fov, u_resolution.y), tile / size);
#ifndef CM_TEXTURE_LOD_HLSL
#define CM_TEXTURE_LOD_HLSL

#include "core.hlsl"

// distance * 2 tan_half_fov / image_height.
float cm_pixel_footprint(float distance, float tan_half_fov, float image_height) {
    return distance * (2.0 * tan_half_fov / image_height);
}

// log2(footprint / texel_size), 0 for magnification, non-positive or NaN footprints.
float cm_texture_lod(float footprint, float texel_size) {
    float ratio = footprint / texel_size;
    return ratio > 1.0 ? log2(ratio) : 0.0;
}

#endif // CM_TEXTURE_LOD_HLSL
