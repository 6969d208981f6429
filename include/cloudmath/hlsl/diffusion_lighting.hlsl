// cloudmath/hlsl/diffusion_lighting.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/diffusion_lighting.hlsl: GLSL twin of cloudmath/diffusion_lighting.hpp,
// multiple scattering from diffusion along the sun's chord with a fitted correction table.
// The formulas, their sources and the inputs are documented in the C++ header.
//
// Use:      float M = cm_diffusion_scattering(tau_sun, tau_behind, tau_view, mu, g, albedo,
//                                             CM_DIFFUSION_MODEL_FITTED);
//           // tau_behind: optical depth behind the sample along the sun direction (a second
//           // short march away from the sun); tau_view: optical depth from the camera.
// Configuration (#define before the include):
//   CM_DIFFUSION_PHASE  name of a user function `float f(float mu, float scale)` returning the
//                       phase function with eccentricities scaled by `scale` (1, 0.5, 0.8).
//                       When defined, cm_diffusion_scattering_with(...) is available (the C++
//                       generic form); g is then that phase function's mean cosine.
// Models:   CM_DIFFUSION_MODEL_FITTED (fitted to homogeneous media), CM_DIFFUSION_MODEL_CLOUDS
//           (fitted to whole-cloud images: the one for cloud fields, the example renderer's
//           default), CM_DIFFUSION_MODEL_PHYSICAL (plain diffusion, for comparison), generated
//           in diffusion_lighting_models.hlsl; errors in the C++ header.
// GLSL 3.30 / ES 3.00: const arrays inside a struct, indexed at run time.
#ifndef CM_DIFFUSION_LIGHTING_HLSL
#define CM_DIFFUSION_LIGHTING_HLSL

#include "core.hlsl"
#include "phase.hlsl"

// The table layout (CM_DIFFUSION_SIZE_*, CM_DIFFUSION_EXTRAPOLATION), CmDiffusionModel and
// the fitted models, generated from the C++ side with the fit.
#include "diffusion_lighting_models.hlsl"

float cmi_diffusion_depth(float tau) { return clamp(tau, 0.0, 1e6); }

// (1 - albedo g, kappa): the similarity relations with absorption (C++ diffusion_similarity).
float2 cm_diffusion_similarity(float g, float albedo) {
    float gc = clamp(g, -0.999, 0.999);
    float w = clamp(albedo, 0.0, 1.0);
    float s = max(1.0 - w * gc, 0.001);
    return float2(s, min(sqrt(3.0 * (1.0 - w) / s), 0.9));
}

// Fluence U (returned) and net flux F of the chord's diffusion solution with absorption
// kappa (the C++ diffusion_chord_fluence, same stable forms).
float cm_diffusion_chord_fluence(float x, float y, float exp_neg_x, float kappa, out float flux) {
    float z = CM_DIFFUSION_EXTRAPOLATION;
    float ez = exp(z);
    float L = x + y;
    float W = L + 2.0 * z;
    float a1 = x + z;
    float a2 = y + z;
    float e_far = exp(-(L + z));
    float k = clamp(kappa, 0.0, 0.9);
    float R1;
    float R2;
    float kQ1;
    float kQ2;
    if (k * W < 1e-4) {
        float k2 = k * k;
        float W2 = W * W;
        R1 = a1 / W * (1.0 + k2 * (a1 * a1 - W2) / 6.0);
        R2 = a2 / W * (1.0 + k2 * (a2 * a2 - W2) / 6.0);
        kQ1 = (1.0 + k2 * (a1 * a1 / 2.0 - W2 / 6.0)) / W;
        kQ2 = (1.0 + k2 * (a2 * a2 / 2.0 - W2 / 6.0)) / W;
    } else {
        float e1 = exp(-k * a1);
        float e2 = exp(-k * a2);
        float inv_denominator = 1.0 / cm_one_minus_exp_neg(2.0 * k * W);
        R1 = e2 * cm_one_minus_exp_neg(2.0 * k * a1) * inv_denominator;
        R2 = e1 * cm_one_minus_exp_neg(2.0 * k * a2) * inv_denominator;
        kQ1 = k * e2 * (1.0 + e1 * e1) * inv_denominator;
        kQ2 = k * e1 * (1.0 + e2 * e2) * inv_denominator;
    }
    float scale = 1.0 / (1.0 - k * k);
    flux = scale * (ez * kQ2 - e_far * kQ1 - exp_neg_x);
    return max(3.0 * scale * (e_far * R1 + ez * R2 - exp_neg_x), 0.0);
}

// (u_sun, u_behind, u_mu, u_surface), each in [0, 1].
float4 cm_diffusion_table_coordinates(float tau_sun, float tau_behind, float tau_view, float mu, float g, float albedo) {
    float s = cm_diffusion_similarity(g, albedo).x;
    float x = s * cmi_diffusion_depth(tau_sun);
    float y = s * cmi_diffusion_depth(tau_behind);
    float z = CM_DIFFUSION_EXTRAPOLATION;
    float t = (x + z) * (y + z) / (x + y + 2.0 * z);
    float d = s * cmi_diffusion_depth(tau_view) + z;
    return float4(x / (1.0 + x), y / (1.0 + y), 0.5 * clamp(mu, -1.0, 1.0) + 0.5, d / (d + t));
}

// Lower node and upper weight of u over n equally spaced nodes.
void cmi_diffusion_hat(float u, int n, out int i0, out float w1) {
    float p = clamp(u, 0.0, 1.0) * float(n - 1);
    // An integer clamp: int(NaN) is undefined (INT_MIN on common GPUs), and the node indexes
    // the table; [0, n - 2] whatever u is.
    int i = clamp(int(p), 0, n - 2);
    i0 = i;
    w1 = p - float(i);
}

float cm_diffusion_table_lookup(CmDiffusionModel m, float4 u) {
    int ix;
    int iy;
    int im;
    int id;
    float wx;
    float wy;
    float wm;
    float wd;
    cmi_diffusion_hat(u.x, CM_DIFFUSION_SIZE_X, ix, wx);
    cmi_diffusion_hat(u.y, CM_DIFFUSION_SIZE_Y, iy, wy);
    cmi_diffusion_hat(u.z, CM_DIFFUSION_SIZE_MU, im, wm);
    cmi_diffusion_hat(u.w, CM_DIFFUSION_SIZE_D, id, wd);
    float sum = 0.0;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c)
                for (int e = 0; e < 2; ++e) {
                    float w = (a == 1 ? wx : 1.0 - wx) * (b == 1 ? wy : 1.0 - wy) * (c == 1 ? wm : 1.0 - wm) * (e == 1 ? wd : 1.0 - wd);
                    int index = (((ix + a) * CM_DIFFUSION_SIZE_Y + iy + b) * CM_DIFFUSION_SIZE_MU + im + c) * CM_DIFFUSION_SIZE_D + id + e;
                    sum += w * m.table[index];
                }
    return sum;
}

// The model with the three phase values it needs (scales 1, 0.5 and 0.8) given.
float cmi_diffusion_scattering_phases(float tau_sun, float tau_behind, float tau_view, float mu, float g, float albedo, CmDiffusionModel m, float p1, float p_half, float p_four_fifths) {
    float mc = clamp(mu, -1.0, 1.0);
    float gc = clamp(g, -0.999, 0.999);
    float w = clamp(albedo, 0.0, 1.0);
    float2 medium = cm_diffusion_similarity(gc, w);
    float ts = cmi_diffusion_depth(tau_sun);
    float x = medium.x * ts;
    float y = medium.x * cmi_diffusion_depth(tau_behind);
    float direct = exp(-ts);
    float e_half = exp(-0.5 * x);
    float e_one = e_half * e_half;
    float3 beams = max(float3(e_half, e_one, e_one * e_one) - direct, float3(0.0, 0.0, 0.0));
    float w_half = m.peak[0] * beams.x + m.peak[2] * beams.y + m.peak[4] * beams.z;
    float w_four_fifths = m.peak[1] * beams.x + m.peak[3] * beams.y + m.peak[5] * beams.z;
    float peak = w_half * p_half + w_four_fifths * p_four_fifths;
    float source = w * (1.0 - gc) / medium.x;
    float flux;
    float U = cm_diffusion_chord_fluence(x, y, e_one, medium.y, flux);
    float D = source * max(U + 3.0 * gc * flux * mc, 0.0) * CM_INV_FOUR_PI;
    float C = cm_diffusion_table_lookup(m, cm_diffusion_table_coordinates(ts, tau_behind, tau_view, mc, gc, w));
    return max(p1 * direct + peak + D * max(C, 0.0), 0.0);
}

// With the Henyey-Greenstein phase function of asymmetry g.
float cm_diffusion_scattering(float tau_sun, float tau_behind, float tau_view, float mu, float g, float albedo, CmDiffusionModel m) {
    float mc = clamp(mu, -1.0, 1.0);
    return cmi_diffusion_scattering_phases(tau_sun, tau_behind, tau_view, mu, g, albedo, m, cm_phase_hg(mc, g), cm_phase_hg(mc, 0.5 * g), cm_phase_hg(mc, 0.8 * g));
}

#ifdef CM_DIFFUSION_PHASE
float cm_diffusion_scattering_with(float tau_sun, float tau_behind, float tau_view, float mu, float g, float albedo, CmDiffusionModel m) {
    float mc = clamp(mu, -1.0, 1.0);
    return cmi_diffusion_scattering_phases(tau_sun, tau_behind, tau_view, mu, g, albedo, m, CM_DIFFUSION_PHASE(mc, 1.0), CM_DIFFUSION_PHASE(mc, 0.5), CM_DIFFUSION_PHASE(mc, 0.8));
}
#endif

#endif // CM_DIFFUSION_LIGHTING_HLSL
