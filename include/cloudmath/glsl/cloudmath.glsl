// cloudmath/glsl/cloudmath.glsl: every GLSL twin. Define configuration macros
// (CM_MS_OCTAVES, CM_MS_PHASE, CM_DIFFUSION_PHASE, CM_CONE_EXTINCTION, CM_CONE_SAMPLES) before including it.
#ifndef CM_CLOUDMATH_GLSL
#define CM_CLOUDMATH_GLSL

#include "core.glsl"
#include "phase.glsl"
#include "transmittance.glsl"
#include "integration.glsl"
#include "multiple_scattering.glsl"
#include "diffusion_lighting.glsl"
#include "cone_sampling.glsl"
#include "geometry.glsl"
#include "density.glsl"
#include "noise.glsl"
#include "sun.glsl"
#include "reprojection.glsl"
#include "shadow_map.glsl"
#include "texture_lod.glsl"
#include "atmosphere.glsl"

#endif  // CM_CLOUDMATH_GLSL
