// cloudmath/hlsl/cone_sampling.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/cone_sampling.hlsl: GLSL twin of cloudmath/cone_sampling.hpp, Schneider's
// cone of light samples toward the sun (near samples at (i + 1/2) step_length, offset across
// the light by a Vogel spiral scaled with distance; the last one far away on the axis).
//
// Configuration (#define before the include):
//   CM_CONE_EXTINCTION  name of a user function `float f(vec3 p, int i)` giving the
//                       extinction (1/m) at sample i; when defined, cm_cone_optical_depth()
//                       is available.
//   CM_CONE_SAMPLES     when defined, cm_cone_optical_depth uses this compile-time sample
//                       count (the driver can unroll the loop) in place of cfg.sample_count
//                       (default: not defined; cfg.sample_count is used).
#ifndef CM_CONE_SAMPLING_HLSL
#define CM_CONE_SAMPLING_HLSL

#include "core.hlsl"

struct CmConeLightConfig {
    int sample_count; // all samples, the far one included
    float step_length; // length of each near segment
    float cone_spread; // cone radius per unit distance (tan of the half-angle)
    float far_distance; // distance of the far sample; <= 0: no far sample
    float far_segment_length; // optical-depth weight of the far sample
};
// CmConeLightConfig(...) of the GLSL: HLSL has no struct constructors.
CmConeLightConfig cm_make_CmConeLightConfig(int sample_count, float step_length, float cone_spread, float far_distance, float far_segment_length) {
    CmConeLightConfig r;
    r.sample_count = sample_count;
    r.step_length = step_length;
    r.cone_spread = cone_spread;
    r.far_distance = far_distance;
    r.far_segment_length = far_segment_length;
    return r;
}

bool cmi_cone_has_far(CmConeLightConfig cfg) { return cfg.far_distance > 0.0 && cfg.sample_count > 0; }
int cmi_cone_near_count(CmConeLightConfig cfg) {
    return max(cmi_cone_has_far(cfg) ? cfg.sample_count - 1 : cfg.sample_count, 0);
}

// Point i of n of the Vogel spiral in the unit disc; i modulo n, n < 1 treated as 1; every
// int i and n (GLSL leaves % of negative operands undefined, hence the explicit wrap, which
// never overflows: -(i + 1) >= 0 for every negative i).
float2 cm_cone_kernel_offset(int i, int n) {
    int count = max(n, 1);
    int k = i >= 0 ? i % count : count - 1 - (-(i + 1)) % count;
    float radius = sqrt((float(k) + 0.5) / float(count));
    float2 sc = cmi_sin_cos(float(k) * 2.39996322972865); // the golden angle, k times
    return radius * float2(sc.y, sc.x);
}

float cm_cone_sample_distance(CmConeLightConfig cfg, int i) {
    int n_near = cmi_cone_near_count(cfg);
    if (cmi_cone_has_far(cfg) && i >= n_near) return cfg.far_distance;
    int k = clamp(i, 0, max(n_near - 1, 0));
    return (float(k) + 0.5) * cfg.step_length;
}

float cm_cone_sample_length(CmConeLightConfig cfg, int i) {
    return cmi_cone_has_far(cfg) && i >= cmi_cone_near_count(cfg) ? cfg.far_segment_length : cfg.step_length;
}

// Orthonormal u, v across the unit vector n (Duff et al., JCGT 2017).
void cmi_orthonormal_basis(float3 n, out float3 u, out float3 v) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float b = n.x * n.y * a;
    u = float3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    v = float3(b, s + n.y * n.y * a, -n.y);
}

float3 cm_cone_sample_position(float3 origin, float3 light_dir, CmConeLightConfig cfg, int i) {
    float d = cm_cone_sample_distance(cfg, i);
    int n_near = cmi_cone_near_count(cfg);
    if (cmi_cone_has_far(cfg) && i >= n_near) return origin + light_dir * d;
    float3 u;
    float3 v;
    cmi_orthonormal_basis(light_dir, u, v);
    float2 k = cm_cone_kernel_offset(i, n_near);
    return origin + light_dir * d + (u * k.x + v * k.y) * (cfg.cone_spread * d);
}

#ifdef CM_CONE_EXTINCTION
// Optical depth toward the light: sum of CM_CONE_EXTINCTION(p_i, i) * length_i.
float cm_cone_optical_depth(float3 origin, float3 light_dir, CmConeLightConfig cfg) {
    float tau = 0.0;
#ifdef CM_CONE_SAMPLES
    cfg.sample_count = CM_CONE_SAMPLES; // one count for the loop and the sample layout
    const int count = CM_CONE_SAMPLES; // a constant loop bound: the driver can unroll
#else
    int count = cfg.sample_count;
#endif
    for (int i = 0; i < count; ++i) {
        float3 p = cm_cone_sample_position(origin, light_dir, cfg, i);
        tau += CM_CONE_EXTINCTION(p, i) * cm_cone_sample_length(cfg, i);
    }
    return tau;
}
#endif

#endif // CM_CONE_SAMPLING_HLSL
