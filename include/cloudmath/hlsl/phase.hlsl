// cloudmath/hlsl/phase.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/phase.hlsl: GLSL twin of cloudmath/phase.hpp (normalised phase functions
// and Henyey-Greenstein sampling). Float only; same forms and clamps as the C++.
//
// Convention: mu = dot(view_dir, light_dir), +1 looking into the light (forward).
// Domain:   mu clamped to [-1, 1], g to [-CM_PHASE_G_MAX, CM_PHASE_G_MAX] (0.9999).
// Accuracy: the HG-type base 1 + g^2 - 2 g mu is written (1-g)^2 + 2g(1-mu) for g >= 0 and
//           (1+g)^2 - 2g(1+mu) for g < 0, never pow(x, 1.5): full precision at the peaks.
#ifndef CM_PHASE_HLSL
#define CM_PHASE_HLSL

#include "core.hlsl"

#define CM_PHASE_G_MAX 0.9999

// cmi_ functions are internal helpers (the C++ detail namespace); cm_ functions are the
// public twins.
float cmi_clamp_g(float g) { return clamp(g, -CM_PHASE_G_MAX, CM_PHASE_G_MAX); }

// (1 + g^2 - 2 g mu)^(-3/2) for clamped mu, g, as 1 / (d sqrt(d)).
float cmi_hg_denominator_pow(float mu, float g) {
    float d = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu) : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu);
    return 1.0 / (d * sqrt(d));
}

float cm_phase_isotropic() { return CM_INV_FOUR_PI; }

float cm_phase_rayleigh(float mu) {
    mu = clamp(mu, -1.0, 1.0);
    return 3.0 / (16.0 * CM_PI) * (1.0 + mu * mu);
}

// Henyey-Greenstein 1941: (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)).
float cm_phase_hg(float mu, float g) {
    mu = clamp(mu, -1.0, 1.0);
    g = cmi_clamp_g(g);
    return CM_INV_FOUR_PI * ((1.0 - g) * (1.0 + g)) * cmi_hg_denominator_pow(mu, g);
}

// (1 - w) HG(g0) + w HG(g1), w clamped to [0, 1] (Hillaire 2016).
float cm_phase_hg_dual(float mu, float g0, float g1, float w) {
    w = cm_saturate(w);
    return (1.0 - w) * cm_phase_hg(mu, g0) + w * cm_phase_hg(mu, g1);
}

// Cornette & Shanks 1992, normalised: 3/(8 pi) (1-g^2)/(2+g^2) (1+mu^2) / (...)^(3/2).
float cm_phase_cornette_shanks(float mu, float g) {
    mu = clamp(mu, -1.0, 1.0);
    g = cmi_clamp_g(g);
    float k = 3.0 / (8.0 * CM_PI) * ((1.0 - g) * (1.0 + g)) / (2.0 + g * g);
    return k * (1.0 + mu * mu) * cmi_hg_denominator_pow(mu, g);
}

// Draine 2003; alpha clamped to >= 0.
float cm_phase_draine(float mu, float g, float alpha) {
    mu = clamp(mu, -1.0, 1.0);
    g = cmi_clamp_g(g);
    alpha = max(alpha, 0.0);
    float norm = 1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0;
    return CM_INV_FOUR_PI * ((1.0 - g) * (1.0 + g)) * (1.0 + alpha * mu * mu) / norm * cmi_hg_denominator_pow(mu, g);
}

// Jendersie & d'Eon 2023 HG + Draine fit to Mie for droplet diameter d in um, d clamped to
// [0, 50]. Parameters depend on d only: compute them once per medium.
struct CmMieApproxParams {
    float g_hg;
    float g_draine;
    float alpha;
    float w_draine;
};
// CmMieApproxParams(...) of the GLSL: HLSL has no struct constructors.
CmMieApproxParams cm_make_CmMieApproxParams(float g_hg, float g_draine, float alpha, float w_draine) {
    CmMieApproxParams r;
    r.g_hg = g_hg;
    r.g_draine = g_draine;
    r.alpha = alpha;
    r.w_draine = w_draine;
    return r;
}

CmMieApproxParams cm_mie_approx_params(float d) {
    d = clamp(d, 0.0, 50.0);
    CmMieApproxParams p;
    if (d <= 0.1) {
        p.g_hg = 13.8 * d * d;
        p.g_draine = 1.1456 * d * cmi_sin_cos(9.29044 * d).x; // core.hlsl's accurate sin
        p.alpha = 250.0;
        // d^4.3 via exp/log only for d > 0: pow(0, y) is left undefined by some specs.
        p.w_draine = 0.252977 - (d > 0.0 ? 312.983 * exp(4.3 * log(d)) : 0.0);
    } else if (d < 1.5) {
        float L = log(d);
        p.g_hg = 0.862 - 0.143 * L * L;
        float inner = (L - 0.238604) * (L + 1.00667) / (0.507522 - 0.15677 * L);
        p.g_draine = 0.379685 * cmi_sin_cos(1.19692 * cmi_sin_cos(inner).y + 1.37932 * L + 0.0625835).y + 0.344213;
        p.alpha = 250.0;
        p.w_draine = 0.146209 * cmi_sin_cos(3.38707 * L + 2.11193).y + 0.316072 + 0.0778917 * L;
    } else if (d < 5.0) {
        float L = log(d);
        p.g_hg = 0.0604931 * log(L) + 0.940256;
        float2 sc = cmi_sin_cos(L);
        p.g_draine = 0.500411 - 0.081287 / (-2.0 * L + sc.x / sc.y + 1.27551);
        p.alpha = 7.30354 * L + 6.31675;
        p.w_draine = 0.026914 * (L - cmi_sin_cos(5.68947 * (log(L) - 0.0292149)).y) + 0.3764;
    } else {
        p.g_hg = exp(-0.0990567 / (d - 1.67154));
        p.g_draine = exp(-2.20679 / (d + 3.91029) - 0.428934);
        p.alpha = exp(3.62489 - 8.29288 / (d + 5.52825));
        p.w_draine = exp(-0.599085 / (d - 0.641583) - 0.665888);
    }
    return p;
}

float cm_phase_mie_approx(float mu, CmMieApproxParams p) {
    return (1.0 - p.w_draine) * cm_phase_hg(mu, p.g_hg) + p.w_draine * cm_phase_draine(mu, p.g_draine, p.alpha);
}

float cm_phase_mie_approx(float mu, float droplet_diameter_um) {
    return cm_phase_mie_approx(mu, cm_mie_approx_params(droplet_diameter_um));
}

// Schlick (Blasi et al. 1993): (1 - k^2) / (4 pi (1 - k mu)^2), exactly normalised.
float cm_phase_schlick(float mu, float k) {
    mu = clamp(mu, -1.0, 1.0);
    k = cmi_clamp_g(k);
    float d = k >= 0.0 ? (1.0 - k) + k * (1.0 - mu) : (1.0 + k) - k * (1.0 + mu);
    return CM_INV_FOUR_PI * ((1.0 - k) * (1.0 + k)) / (d * d);
}

float cm_schlick_k_from_hg_g(float g) { return 1.55 * g - 0.55 * g * g * g; }

// Cheap HG stand-in: max relative error 9% (|g| <= 0.3) to 90% (|g| <= 0.9).
float cm_phase_hg_schlick(float mu, float g) {
    return cm_phase_schlick(mu, cm_schlick_k_from_hg_g(cmi_clamp_g(g)));
}

// mu distributed as HG(mu, g) for u uniform in [0, 1): the inverse CDF of phase.hpp,
// 1 - mu = (1-g)^2 (1-u) (1+g+t) / t^2 with t = (1-g) + 2 g u, mirrored for g < 0, written
// as (1 - u) (w (w (1+g) + (1-g))) with w = (1-g) / t: every factor shrinks as u grows, so
// mu is monotonic in u (with correctly rounded arithmetic; phase.hpp).
float cm_sample_phase_hg(float g, float u) {
    g = cmi_clamp_g(g);
    u = cm_saturate(u);
    float a = abs(g);
    float v = g >= 0.0 ? u : 1.0 - u;
    float one_minus_v = g >= 0.0 ? 1.0 - u : u;
    float t = (1.0 - a) + 2.0 * a * v;
    float w = (1.0 - a) / t;
    float one_minus_m = one_minus_v * (w * (w * (1.0 + a) + (1.0 - a)));
    float m = v <= 0.0 ? -1.0 : clamp(1.0 - one_minus_m, -1.0, 1.0);
    return g >= 0.0 ? m : -m;
}

#endif // CM_PHASE_HLSL
