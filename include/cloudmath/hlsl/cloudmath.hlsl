// cloudmath/hlsl/cloudmath.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/cloudmath.hlsl: every GLSL twin. Define configuration macros
// (CM_MS_OCTAVES, CM_MS_PHASE, CM_DIFFUSION_PHASE, CM_CONE_EXTINCTION, CM_CONE_SAMPLES) before including it.
#ifndef CM_CLOUDMATH_HLSL
#define CM_CLOUDMATH_HLSL

#include "core.hlsl"
#include "phase.hlsl"
#include "transmittance.hlsl"
#include "integration.hlsl"
#include "multiple_scattering.hlsl"
#include "diffusion_lighting.hlsl"
#include "cone_sampling.hlsl"
#include "geometry.hlsl"
#include "density.hlsl"
#include "noise.hlsl"
#include "sun.hlsl"
#include "reprojection.hlsl"
#include "shadow_map.hlsl"
#include "texture_lod.hlsl"
#include "atmosphere.hlsl"

#endif // CM_CLOUDMATH_HLSL
