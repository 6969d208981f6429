// cloudmath/wgsl/phase.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/phase.glsl: GLSL twin of cloudmath/phase.hpp (normalised phase functions
// and Henyey-Greenstein sampling). Float only; same forms and clamps as the C++.
//
// Convention: mu = dot(view_dir, light_dir), +1 looking into the light (forward).
// Domain:   mu clamped to [-1, 1], g to [-CM_PHASE_G_MAX, CM_PHASE_G_MAX] (0.9999).
// Accuracy: the HG-type base 1 + g^2 - 2 g mu is written (1-g)^2 + 2g(1-mu) for g >= 0 and
//           (1+g)^2 - 2g(1+mu) for g < 0, never pow(x, 1.5): full precision at the peaks.

const CM_PHASE_G_MAX = 0.9999;

// cmi_ functions are internal helpers (the C++ detail namespace); cm_ functions are the
// public twins.
fn cmi_clamp_g(g: f32) -> f32 { return clamp(g, -CM_PHASE_G_MAX, CM_PHASE_G_MAX); }

// (1 + g^2 - 2 g mu)^(-3/2) for clamped mu, g, as 1 / (d sqrt(d)).
fn cmi_hg_denominator_pow(mu: f32, g: f32) -> f32 {
    let d: f32 = select((1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu), (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu), g >= 0.0);
    return 1.0 / (d * sqrt(d));
}

fn cm_phase_isotropic() -> f32 { return CM_INV_FOUR_PI; }

fn cm_phase_rayleigh(mu_in: f32) -> f32 {
    var mu: f32 = mu_in;
    mu = clamp(mu, -1.0, 1.0);
    return 3.0 / (16.0 * CM_PI) * (1.0 + mu * mu);
}

// Henyey-Greenstein 1941: (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)).
fn cm_phase_hg(mu_in: f32, g_in: f32) -> f32 {
    var mu: f32 = mu_in;
    var g: f32 = g_in;
    mu = clamp(mu, -1.0, 1.0);
    g = cmi_clamp_g(g);
    return CM_INV_FOUR_PI * ((1.0 - g) * (1.0 + g)) * cmi_hg_denominator_pow(mu, g);
}

// (1 - w) HG(g0) + w HG(g1), w clamped to [0, 1] (Hillaire 2016).
fn cm_phase_hg_dual(mu: f32, g0: f32, g1: f32, w_in: f32) -> f32 {
    var w: f32 = w_in;
    w = cm_saturate(w);
    return (1.0 - w) * cm_phase_hg(mu, g0) + w * cm_phase_hg(mu, g1);
}

// Cornette & Shanks 1992, normalised: 3/(8 pi) (1-g^2)/(2+g^2) (1+mu^2) / (...)^(3/2).
fn cm_phase_cornette_shanks(mu_in: f32, g_in: f32) -> f32 {
    var mu: f32 = mu_in;
    var g: f32 = g_in;
    mu = clamp(mu, -1.0, 1.0);
    g = cmi_clamp_g(g);
    let k: f32 = 3.0 / (8.0 * CM_PI) * ((1.0 - g) * (1.0 + g)) / (2.0 + g * g);
    return k * (1.0 + mu * mu) * cmi_hg_denominator_pow(mu, g);
}

// Draine 2003; alpha clamped to >= 0.
fn cm_phase_draine(mu_in: f32, g_in: f32, alpha_in: f32) -> f32 {
    var mu: f32 = mu_in;
    var g: f32 = g_in;
    var alpha: f32 = alpha_in;
    mu = clamp(mu, -1.0, 1.0);
    g = cmi_clamp_g(g);
    alpha = max(alpha, 0.0);
    let norm: f32 = 1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0;
    return CM_INV_FOUR_PI * ((1.0 - g) * (1.0 + g)) * (1.0 + alpha * mu * mu) / norm * cmi_hg_denominator_pow(mu, g);
}

// Jendersie & d'Eon 2023 HG + Draine fit to Mie for droplet diameter d in um, d clamped to
// [0, 50]. Parameters depend on d only: compute them once per medium.
struct CmMieApproxParams {
    g_hg: f32,
    g_draine: f32,
    alpha: f32,
    w_draine: f32,
}

fn cm_mie_approx_params(d_in: f32) -> CmMieApproxParams {
    var d: f32 = d_in;
    d = clamp(d, 0.0, 50.0);
    var p: CmMieApproxParams;
    if (d <= 0.1) {
        p.g_hg = 13.8 * d * d;
        p.g_draine = 1.1456 * d * cmi_sin_cos(9.29044 * d).x; // core.glsl's accurate sin
        p.alpha = 250.0;
        // d^4.3 via exp/log only for d > 0: pow(0, y) is left undefined by some specs.
        p.w_draine = 0.252977 - (select(0.0, 312.983 * exp(4.3 * log(d)), d > 0.0));
    } else if (d < 1.5) {
        let L: f32 = log(d);
        p.g_hg = 0.862 - 0.143 * L * L;
        let inner: f32 = (L - 0.238604) * (L + 1.00667) / (0.507522 - 0.15677 * L);
        p.g_draine = 0.379685 * cmi_sin_cos(1.19692 * cmi_sin_cos(inner).y + 1.37932 * L + 0.0625835).y + 0.344213;
        p.alpha = 250.0;
        p.w_draine = 0.146209 * cmi_sin_cos(3.38707 * L + 2.11193).y + 0.316072 + 0.0778917 * L;
    } else if (d < 5.0) {
        let L: f32 = log(d);
        p.g_hg = 0.0604931 * log(L) + 0.940256;
        let sc: vec2f = cmi_sin_cos(L);
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

fn cm_phase_mie_approx(mu: f32, p: CmMieApproxParams) -> f32 {
    return (1.0 - p.w_draine) * cm_phase_hg(mu, p.g_hg) + p.w_draine * cm_phase_draine(mu, p.g_draine, p.alpha);
}

fn cm_phase_mie_approx_ff(mu: f32, droplet_diameter_um: f32) -> f32 {
    return cm_phase_mie_approx(mu, cm_mie_approx_params(droplet_diameter_um));
}

// Schlick (Blasi et al. 1993): (1 - k^2) / (4 pi (1 - k mu)^2), exactly normalised.
fn cm_phase_schlick(mu_in: f32, k_in: f32) -> f32 {
    var mu: f32 = mu_in;
    var k: f32 = k_in;
    mu = clamp(mu, -1.0, 1.0);
    k = cmi_clamp_g(k);
    let d: f32 = select((1.0 + k) - k * (1.0 + mu), (1.0 - k) + k * (1.0 - mu), k >= 0.0);
    return CM_INV_FOUR_PI * ((1.0 - k) * (1.0 + k)) / (d * d);
}

fn cm_schlick_k_from_hg_g(g: f32) -> f32 { return 1.55 * g - 0.55 * g * g * g; }

// Cheap HG stand-in: max relative error 9% (|g| <= 0.3) to 90% (|g| <= 0.9).
fn cm_phase_hg_schlick(mu: f32, g: f32) -> f32 {
    return cm_phase_schlick(mu, cm_schlick_k_from_hg_g(cmi_clamp_g(g)));
}

// mu distributed as HG(mu, g) for u uniform in [0, 1): the inverse CDF of phase.hpp,
// 1 - mu = (1-g)^2 (1-u) (1+g+t) / t^2 with t = (1-g) + 2 g u, mirrored for g < 0, written
// as (1 - u) (w (w (1+g) + (1-g))) with w = (1-g) / t: every factor shrinks as u grows, so
// mu is monotonic in u (with correctly rounded arithmetic; phase.hpp).
fn cm_sample_phase_hg(g_in: f32, u_in: f32) -> f32 {
    var g: f32 = g_in;
    var u: f32 = u_in;
    g = cmi_clamp_g(g);
    u = cm_saturate(u);
    let a: f32 = abs(g);
    let v: f32 = select(1.0 - u, u, g >= 0.0);
    let one_minus_v: f32 = select(u, 1.0 - u, g >= 0.0);
    let t: f32 = (1.0 - a) + 2.0 * a * v;
    let w: f32 = (1.0 - a) / t;
    let one_minus_m: f32 = one_minus_v * (w * (w * (1.0 + a) + (1.0 - a)));
    let m: f32 = select(clamp(1.0 - one_minus_m, -1.0, 1.0), -1.0, v <= 0.0);
    return select(-m, m, g >= 0.0);
}
