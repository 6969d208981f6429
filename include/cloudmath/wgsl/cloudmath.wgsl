// cloudmath/wgsl/cloudmath.wgsl: generated from the GLSL twins (every module, in dependency order) by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires nothing else.
//
// cloudmath/glsl/core.glsl: GLSL twin of cloudmath/core.hpp (constants, saturate, remap,
// smoothstep_safe, stable exponential helpers).
//
// Use:      #include "cloudmath/glsl/core.glsl"   (GL_GOOGLE_include_directive, shaderc,
//           GL_ARB_shading_language_include), or cloudmath::glsl_source("core") for raw GL.
// Targets:  function bodies valid in GLSL 3.30 core, GLSL ES 3.00 and Vulkan GLSL 4.50;
//           float only. Same names as the C++ with the cm_ prefix, same argument order.
// Bad input: handled with comparisons, as in C++; nothing relies on NaN or Inf behaviour,
//           which differs between drivers.

const CM_PI = 3.14159265358979;
const CM_TWO_PI = 6.28318530717959;
const CM_FOUR_PI = 12.5663706143592;
const CM_INV_PI = 0.318309886183791;
const CM_INV_FOUR_PI = 0.0795774715459477;

fn cm_saturate(x: f32) -> f32 { return clamp(x, 0.0, 1.0); }
fn cm_saturate_v2(x: vec2f) -> vec2f { return clamp(x, vec2f(0.0), vec2f(1.0)); }
fn cm_saturate_v3(x: vec3f) -> vec3f { return clamp(x, vec3f(0.0), vec3f(1.0)); }
fn cm_saturate_v4(x: vec4f) -> vec4f { return clamp(x, vec4f(0.0), vec4f(1.0)); }

// Unclamped remap; a degenerate old range is the step of the clamped remap (finite).
fn cm_remap(x: f32, old_min: f32, old_max: f32, new_min: f32, new_max: f32) -> f32 {
    if (old_max == old_min) { return select(new_max, new_min, x < old_min); }
    return new_min + (x - old_min) / (old_max - old_min) * (new_max - new_min);
}

// saturate((x - old_min) / (old_max - old_min)), a degenerate range as cm_remap's step:
// cm_remap_clamped to [0, 1] (core.hpp's detail::remap_unit). When an input exceeds
// FLT_MAX / 4 the halved inputs are used, so the differences cannot overflow to Inf / Inf
// (the C++ uses double there). A driver that re-associated x/2 - m/2 into (x - m)/2 would
// lose that (Mesa keeps it: the parity cases with inputs up to FLT_MAX).
fn cmi_remap_unit(x: f32, old_min: f32, old_max: f32) -> f32 {
    if (old_max == old_min) { return select(1.0, 0.0, x < old_min); }
    let s: f32 = select(1.0, 0.5, max(max(abs(x), abs(old_min)), abs(old_max)) > 8.50705917e37);
    return cm_saturate((x * s - old_min * s) / (old_max * s - old_min * s));
}

// Remap clamped to the new range; t is clamped before scaling, end points exact. Finite
// and inside [min(new_min, new_max), max(new_min, new_max)] for every finite input: the
// blend, which can round an ulp past an end, is clamped (core.hpp).
fn cm_remap_clamped(x: f32, old_min: f32, old_max: f32, new_min: f32, new_max: f32) -> f32 {
    let t: f32 = cmi_remap_unit(x, old_min, old_max);
    return clamp((1.0 - t) * new_min + t * new_max, min(new_min, new_max), max(new_min, new_max));
}

// GLSL smoothstep defined for every pair of edges (GLSL leaves edge0 >= edge1 undefined).
fn cm_smoothstep_safe(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t: f32 = cmi_remap_unit(x, edge0, edge1); // cm_remap_clamped(x, edge0, edge1, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t);
}

// (1 - exp(-x)) / x, 1 at x = 0. GLSL has no expm1, and the u = exp(-x); (u - 1) / log(u)
// trick fails where exp and log are approximations near 0 and 1 (measured on Mesa llvmpipe:
// errors up to 1e23). Below |x| = 0.25 the degree-6 Taylor polynomial in Horner form
// (truncation error below 1.6e-9); above, the quotient, whose cancellation is then at most
// a factor 4.5. Agrees with the C++ expm1 form to about 1e-7.
fn cmi_one_minus_exp_neg_over_x_taylor(x: f32) -> f32 {
    return 1.0 + x * (-1.0 / 2.0 + x * (1.0 / 6.0 + x * (-1.0 / 24.0 + x * (1.0 / 120.0 + x * (-1.0 / 720.0 + x * (1.0 / 5040.0))))));
}
fn cm_one_minus_exp_neg_over_x(x: f32) -> f32 {
    if (abs(x) < 0.25) {
        return cmi_one_minus_exp_neg_over_x_taylor(x);
    }
    return (1.0 - exp(-x)) / x;
}
fn cm_one_minus_exp_neg_over_x_v3(x: vec3f) -> vec3f {
    return vec3f(cm_one_minus_exp_neg_over_x(x.x), cm_one_minus_exp_neg_over_x(x.y), cm_one_minus_exp_neg_over_x(x.z));
}

// 1 - exp(-x) with full relative precision for tiny x: below |x| = 0.25, x times the Taylor
// polynomial above; from there, 1 - exp(-x) itself (its cancellation is at most a factor
// 3.5). Not x * cm_one_minus_exp_neg_over_x(x) for all x: above 8.5e37 the quotient's 1/x
// is a denormal that GPUs flush to 0 (result 0), and at x = Inf, where 2 tau or k tau
// overflowed, it is Inf * 0 = NaN (cm_beer_powder from tau = 1.7e38, cm_powder(1e30,
// 1e10)); this form gives 1 there, as the C++ does.
// Domain: every finite x (1 for x >= 17; below x = -88.7 exp(-x) overflows and the result
// is -Inf, as the C++ -expm1 gives).
fn cm_one_minus_exp_neg(x: f32) -> f32 {
    if (abs(x) < 0.25) {
        return x * cmi_one_minus_exp_neg_over_x_taylor(x);
    }
    return 1.0 - exp(-x);
}
fn cm_one_minus_exp_neg_v3(x: vec3f) -> vec3f {
    return vec3f(cm_one_minus_exp_neg(x.x), cm_one_minus_exp_neg(x.y), cm_one_minus_exp_neg(x.z));
}

// (sin x, cos x) to about 2 float ulps for |x| <= 8192. Why not sin() and cos(): Vulkan, GLSL
// and WGSL promise only an absolute error of 2^-11 on [-pi, pi], and drivers use it
// (measured: SwiftShader's sin(0.0023262) is 1.6e-4 off relative, which moved the Sun's disc
// radiance 4% near its limb). Cody-Waite reduction by pi/2 in three parts whose products
// with the quadrant n are exact for |n| < 2^13 (Moshier's Cephes constants, doubled), then
// Taylor polynomials on [-pi/4, pi/4] (truncation below 2.2e-9 relative). Beyond 8192 the
// reduction is inexact, so the built-ins are used (finite, in [-1, 1]).
fn cmi_sin_cos(x: f32) -> vec2f {
    if (!(abs(x) <= 8192.0)) { return vec2f(sin(x), cos(x)); }
    let n: f32 = floor(x * 0.636619772367581 + 0.5);
    let r: f32 = ((x - n * 1.5703125) - n * 4.837512969970703125e-4) - n * 7.54978995489188216e-8;
    let r2: f32 = r * r;
    let s: f32 = r + r * r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362880.0))));
    let c: f32 = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0 + r2 * (-1.0 / 3628800.0)))));
    let q: f32 = n - 4.0 * floor(n * 0.25); // the quadrant, 0 to 3
    if (q == 0.0) { return vec2f(s, c); }
    if (q == 1.0) { return vec2f(c, -s); }
    if (q == 2.0) { return vec2f(-s, -c); }
    return vec2f(-c, s);
}
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
// cloudmath/glsl/transmittance.glsl: GLSL twin of cloudmath/transmittance.hpp.
// Optical depth tau >= 0; negative tau is clamped to 0. float and vec3 (RGB) overloads.

// exp(-tau), in [0, 1].
fn cm_beer_lambert(optical_depth: f32) -> f32 { return exp(-max(optical_depth, 0.0)); }
fn cm_beer_lambert_v3(optical_depth: vec3f) -> vec3f { return exp(-max(optical_depth, vec3f(0.0))); }

// 1 - exp(-k tau) (Schneider 2015), full precision for tiny tau; every finite input, 1 where
// k tau overflows (cm_one_minus_exp_neg of Inf is 1).
fn cm_powder(optical_depth: f32, k: f32) -> f32 { return cm_one_minus_exp_neg(max(k * optical_depth, 0.0)); }
fn cm_powder_v3f(optical_depth: vec3f, k: f32) -> vec3f {
    return cm_one_minus_exp_neg_v3(max(k * optical_depth, vec3f(0.0)));
}

// 2 exp(-tau) (1 - exp(-2 tau)) (Schneider, GPU Pro 7): peak 0.7698 at ln(3)/2; every
// finite tau, 0 for huge tau (also where 2 tau overflows, from 1.7e38).
fn cm_beer_powder(optical_depth: f32) -> f32 {
    let tau: f32 = max(optical_depth, 0.0);
    return 2.0 * exp(-tau) * cm_one_minus_exp_neg(2.0 * tau);
}
fn cm_beer_powder_v3(optical_depth: vec3f) -> vec3f {
    let tau: vec3f = max(optical_depth, vec3f(0.0));
    return 2.0 * exp(-tau) * cm_one_minus_exp_neg_v3(2.0 * tau);
}

// max(exp(-tau), 0.7 exp(-0.25 tau)) (Schneider, Nubis 2017).
fn cm_nubis_attenuation(optical_depth: f32) -> f32 {
    let tau: f32 = max(optical_depth, 0.0);
    return max(exp(-tau), 0.7 * exp(-0.25 * tau));
}
fn cm_nubis_attenuation_v3(optical_depth: vec3f) -> vec3f {
    let tau: vec3f = max(optical_depth, vec3f(0.0));
    return max(exp(-tau), 0.7 * exp(-0.25 * tau));
}

// 1 / (1 + 3/4 (1 - g) tau): isotropic light through a conservative layer (two-stream).
fn cm_diffuse_transmittance(optical_depth: f32, g: f32) -> f32 {
    return 1.0 / (1.0 + 0.75 * (1.0 - clamp(g, -1.0, 1.0)) * max(optical_depth, 0.0));
}
fn cm_diffuse_transmittance_v3f(optical_depth: vec3f, g: f32) -> vec3f {
    return 1.0 / (1.0 + 0.75 * (1.0 - clamp(g, -1.0, 1.0)) * max(optical_depth, vec3f(0.0)));
}
// cloudmath/glsl/integration.glsl: GLSL twin of cloudmath/integration.hpp: the
// energy-conserving step integral (Hillaire 2015) and a front-to-back march accumulator.
//
// Use:      CmMarchAccumulator acc = cm_march_accumulator();
//           for (...) { cm_march_add_segment(acc, S, sigma_t, ds); if (cm_march_is_opaque(acc, 0.01)) break; }
//           color = background * acc.transmittance + acc.luminance;
// S is radiance per metre (sigma_s * phase * light); sigma_t in 1/m; ds in m.

// S (1 - exp(-sigma_t ds)) / sigma_t, exactly S ds at sigma_t = 0, no clamp constant.
fn cm_integrate_scattering(S: f32, sigma_t: f32, ds: f32) -> f32 {
    return S * ds * cm_one_minus_exp_neg_over_x(max(sigma_t * ds, 0.0));
}
fn cm_integrate_scattering_v3v3f(S: vec3f, sigma_t: vec3f, ds: f32) -> vec3f {
    return S * ds * cm_one_minus_exp_neg_over_x_v3(max(sigma_t * ds, vec3f(0.0)));
}
fn cm_integrate_scattering_v3ff(S: vec3f, sigma_t: f32, ds: f32) -> vec3f {
    return S * cm_integrate_scattering(1.0, sigma_t, ds);
}

// The C++ march_accumulator<vec3, vec3>; grey extinction uses the float overload below.
struct CmMarchAccumulator {
    luminance: vec3f,
    transmittance: vec3f,
}

fn cm_march_accumulator() -> CmMarchAccumulator { return CmMarchAccumulator(vec3f(0.0), vec3f(1.0)); }

fn cm_march_add_segment(acc: ptr<function, CmMarchAccumulator>, S: vec3f, sigma_t: vec3f, ds: f32) {
    (*acc).luminance += (*acc).transmittance * cm_integrate_scattering_v3v3f(S, sigma_t, ds);
    (*acc).transmittance *= cm_beer_lambert_v3(sigma_t * ds);
}
fn cm_march_add_segment_MarchAccumulatorv3ff(acc: ptr<function, CmMarchAccumulator>, S: vec3f, sigma_t: f32, ds: f32) {
    (*acc).luminance += (*acc).transmittance * cm_integrate_scattering_v3ff(S, sigma_t, ds);
    (*acc).transmittance *= vec3f(cm_beer_lambert(sigma_t * ds));
}

// True once every channel's transmittance is below min_transmittance.
fn cm_march_is_opaque(acc: CmMarchAccumulator, min_transmittance: f32) -> bool {
    return all((acc.transmittance < vec3f(min_transmittance)));
}

fn cm_march_opacity(acc: CmMarchAccumulator) -> vec3f { return vec3f(1.0) - acc.transmittance; }

// Distance of fraction u of a march over [t_start, t_end] whose steps grow with distance:
// t_start + (t_end - t_start) (e^(u L) - 1) / (e^L - 1),
// L = ln((t_end + near_distance) / (t_start + near_distance));
// ends exact, results within them. (GLSL has no log1p: L = log(1 + x) loses relative precision for tiny x, which
// only bends the spacing of a nearly uniform schedule.)
fn cm_march_schedule_distance(u: f32, t_start: f32, t_end: f32, near_distance: f32) -> f32 {
    let v: f32 = cm_saturate(u);
    if (v <= 0.0) { return t_start; }
    if (v >= 1.0) { return t_end; }
    let base: f32 = t_start + near_distance;
    let ratio: f32 = (t_end - t_start) / base;
    // The ends' ratio near overflow (near_distance tiny): the difference of two logs (1e38, not
    // FLT_MAX: WGSL refuses the literal 3.4028235e38 as beyond f32).
    let L: f32 = select(log(t_end + near_distance) - log(base), log(1.0 + ratio), ratio < 1e38);
    let g: f32 = v * exp((v - 1.0) * L) * cm_one_minus_exp_neg_over_x(v * L) / cm_one_minus_exp_neg_over_x(L);
    // Within [t_start, t_end]: the sum rounds past t_end for u near 1.
    return clamp(t_start + (t_end - t_start) * g, t_start, t_end);
}

// Light steps placed quadratically: fraction u of a march of `length` (integration.hpp).
fn cm_light_march_distance(u: f32, length: f32) -> f32 {
    let v: f32 = cm_saturate(u);
    return length * (v * v);
}

// Sub-steps of optical depth <= 1 for a view step: ceil(tau) in [1, max_substeps]; NaN -> 1.
fn cm_refine_substeps(step_optical_depth: f32, max_substeps: i32) -> i32 {
    let most: i32 = max(max_substeps, 1);
    if (!(step_optical_depth > 1.0)) { return 1; }
    if (step_optical_depth >= f32(most)) { return most; }
    // Clamped after the conversion too: in [1, most] even where a compiler folds the NaN test.
    return clamp(i32(ceil(step_optical_depth)), 1, most);
}
// cloudmath/glsl/multiple_scattering.glsl: GLSL twin of cloudmath/multiple_scattering.hpp,
// Wrenninge's octaves: sum_{i<N} b^i phase(mu, c^i g) exp(-a^i tau).
// Letters: a scales extinction, b the contribution, c the eccentricity (b <= a conserves
// energy); Frostbite's notes swap a and b.
//
// Configuration (#define before the include):
//   CM_MS_OCTAVES   octave count of the overloads without an `octaves` argument (default 3),
//                   a compile-time constant, so drivers unroll the loop.
//   CM_MS_PHASE     name of a user function `float f(float mu, float scale)` returning the
//                   phase function with eccentricities scaled by `scale` = c^i. When defined,
//                   cm_multiple_scattering_with(...) is available (the C++ generic form).
override CM_MS_OCTAVES: i32 = 3;

fn cm_multiple_scattering(optical_depth: f32, mu: f32, g: f32, a: f32, b: f32, c: f32, octaves: i32) -> f32 {
    var sum: f32 = 0.0;
    var ai: f32 = 1.0;
    var bi: f32 = 1.0;
    var ci: f32 = 1.0;
    for (var i: i32 = 0; i < octaves; i++) {
        sum += bi * cm_phase_hg(mu, ci * g) * cm_beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}

// CM_MS_OCTAVES octaves (the C++ multiple_scattering<N>).
fn cm_multiple_scattering_ffffff(optical_depth: f32, mu: f32, g: f32, a: f32, b: f32, c: f32) -> f32 {
    return cm_multiple_scattering(optical_depth, mu, g, a, b, c, CM_MS_OCTAVES);
}

// Presets (the C++ multiple_scattering_preset without its name): a, b, c, octave count, the
// optical thickness range and the error measured there against the Monte Carlo reference
// (rms and max of (L_model - L_MC) / mean L_MC; see multiple_scattering.hpp).
struct CmMsPreset {
    a: f32,
    b: f32,
    c: f32,
    octaves: i32,
    tau_min: f32,
    tau_max: f32,
    rms_error: f32,
    max_error: f32,
}
const CM_MS_PRESET_PRODUCTION: CmMsPreset = CmMsPreset(0.5, 0.5, 0.5, 3, 1.0, 100.0, 1.034, 3.726);
const CM_MS_PRESET_FITTED: CmMsPreset = CmMsPreset(0.197, 0.409, 0.800, 5, 1.0, 100.0, 0.7096, 3.649);
const CM_MS_PRESET_CHEAP: CmMsPreset = CmMsPreset(0.0639, 0.582, 0.676, 2, 1.0, 100.0, 0.7394, 3.657);
const CM_MS_PRESET_THIN: CmMsPreset = CmMsPreset(0.173, 0.435, 0.805, 3, 1.0, 10.0, 0.5524, 1.311);
const CM_MS_PRESET_THICK: CmMsPreset = CmMsPreset(0.299, 0.625, 0.529, 6, 10.0, 100.0, 0.5431, 2.180);

// The octave sum with a preset's a, b, c and octave count.
fn cm_multiple_scattering_fffMsPreset(optical_depth: f32, mu: f32, g: f32, preset: CmMsPreset) -> f32 {
    return cm_multiple_scattering(optical_depth, mu, g, preset.a, preset.b, preset.c, preset.octaves);
}
// cloudmath/glsl/diffusion_lighting_models.glsl: the table layout, CmDiffusionModel (the C++
// diffusion_model without its name) and the fitted models of diffusion_lighting.glsl.
// Generated by cloudmath_lighting_error fit-diffusion (scripts/reference.sh)
// fitted on lighting_reference.csv, lighting_train_g0.8.csv, lighting_train_g0.93.csv
// held out: lighting_holdout_g0.75.csv, lighting_holdout_g0.85.csv, lighting_holdout_g0.9.csv, lighting_holdout_g0.85_albedo0.99.csv, lighting_holdout_renderer_phase.csv
// options: smoothing 0.01, ridge 0.0001
// clouds: diffusion_clouds.txt (cloudmath_volume_truth fit-clouds, scripts/truth.sh --fit);
// do not edit.

// diffusion_layout of the C++ header.
const CM_DIFFUSION_SIZE_X = 3;
const CM_DIFFUSION_SIZE_Y = 3;
const CM_DIFFUSION_SIZE_MU = 5;
const CM_DIFFUSION_SIZE_D = 3;
const CM_DIFFUSION_TABLE_SIZE = 135;
const CM_DIFFUSION_PEAK_SIZE = 6;
const CM_DIFFUSION_EXTRAPOLATION = 0.7104;

struct CmDiffusionModel {
    table: array<f32, CM_DIFFUSION_TABLE_SIZE>,
    peak: array<f32, CM_DIFFUSION_PEAK_SIZE>,
    tau_min: f32,
    tau_max: f32,
    g_min: f32,
    g_max: f32,
    rms_error: f32,
    max_error: f32,
    holdout_rms_error: f32,
}

const CM_DIFFUSION_MODEL_FITTED: CmDiffusionModel = CmDiffusionModel(array<f32, 135>(-3.63779521, -0.914912105, 1.70635867, -3.88458657, -1.01438761, 1.83863842, -4.07411861, -1.08499706, 1.86364174, -4.22852182, -1.13680637, 1.88357854, -4.41337013, -1.28653598, 1.8906889, -3.41249418, -0.438435525, 2.37067914, -3.679389, -0.481398314, 2.81360269, -3.93735456, -0.434743732, 3.32535911, -4.21281815, 0.13397783, 3.96604371, -4.75296021, -0.625977397, 3.94676495, -3.18768859, 0.303834915, 3.61556053, -3.40330791, 0.532708824, 4.28667927, -3.72234249, 0.670352578, 5.08247805, -4.18615723, 1.10500419, 5.82438374, -5.03370428, 0.268707722, 6.00597525, -1.12483203, -0.250908911, 0.737691581, -1.71727872, -0.154107124, 1.35278749, -2.31270099, -0.296629399, 1.84419191, -2.83147717, -0.176857606, 2.27854133, -3.39857984, -0.432381898, 2.52588558, -1.54329336, -0.0783012658, 1.66810703, -1.77514899, 0.140656725, 2.07082248, -2.06641412, 0.0201398432, 2.38603806, -2.30488491, 0.186118767, 2.62956119, -2.64830375, -0.0491206907, 2.65699935, -1.87015486, 0.323230892, 2.65220881, -1.68363297, 0.543600142, 2.75091314, -1.61523712, 0.567802548, 2.85334826, -1.68403065, 0.650013268, 2.90595961, -1.86149454, 0.381197721, 2.77433991, 1.47935808, 0.837722957, 0.11385522, 0.524554372, 1.02400398, 1.10683131, -0.494857401, 0.653903306, 1.88313341, -1.41779208, 0.683402479, 2.5830009, -2.40844631, 0.296885759, 3.10795283, 0.436332822, 0.629811347, 0.913960934, 0.191543251, 0.694232047, 1.13961029, -0.123454496, 0.431802183, 1.23250413, -0.331619084, 0.489707559, 1.28881478, -0.561985373, 0.352616936, 1.31824267, -0.536168933, 0.526002526, 1.6706773, -0.00326269679, 0.535771668, 1.13110614, 0.441741884, 0.463310778, 0.564299405, 0.824672639, 0.380927026, 0.0115512311, 1.28021872, 0.403354585, -0.482045919), array<f32, 6>(-0.335704416, 0.275073111, 1.61848819, -0.819109738, -1.57667077, 1.85697007), 1.0, 100.0, 0.800000012, 0.930000007, 0.332646996, 1.82897592, 0.514358997);
const CM_DIFFUSION_MODEL_PHYSICAL: CmDiffusionModel = CmDiffusionModel(array<f32, 135>(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0), array<f32, 6>(0.0, 0.0, 0.0, 1.0, 0.0, 0.0), 1.0, 100.0, 0.800000012, 0.930000007, 3.1927526, 11.7154102, 2.26203418);
const CM_DIFFUSION_MODEL_CLOUDS: CmDiffusionModel = CmDiffusionModel(array<f32, 135>(-3.63779521, -0.789787352, 1.74889231, -3.88458657, -0.821122408, 1.94393671, -4.07411814, -0.938555956, 1.90946949, -4.22852182, -1.06696045, 2.00247431, -4.41336918, -1.31071925, 1.9323281, -3.41840124, -0.609709144, 2.34047604, -3.68195796, -0.528841794, 2.52649236, -3.93794203, -0.6934793, 3.2269907, -4.2268219, -0.464829803, 3.76521063, -4.74970913, -0.771790504, 3.97403049, -3.1280973, -0.0133377621, 2.71018147, -3.41171288, -0.154176876, 3.55996394, -3.72441339, -0.089365609, 4.77672958, -4.21752357, 0.0380955823, 5.5605073, -5.021595, 0.109058894, 5.970644, -1.1272831, -0.361622453, 0.733960271, -1.72071564, -0.317219615, 1.38575745, -2.31215763, -0.462366819, 1.76480341, -2.83735013, -0.763368249, 1.85300267, -3.41216683, -0.463490546, 2.07052088, -1.75376594, -0.324012578, 1.93451929, -1.96283913, 0.27832222, 2.16721392, -1.97665405, 0.48579812, 2.61439419, -2.46168804, 0.50191021, 3.07850981, -2.77500391, -0.855869353, 3.34597087, -1.72183442, 0.774193406, 2.47909975, -1.50737607, 1.05215633, 2.63056898, -1.50364876, 1.33616376, 2.88188791, -1.84103155, 0.64275229, 3.04894757, -1.47143531, 0.570708394, 2.75915122, 1.47077811, 0.403333515, 0.0580750592, 0.512662649, 0.454395473, 1.01802278, -0.49449721, -0.159512013, 1.56150198, -1.42786622, -0.39336139, 1.92819083, -2.43063307, -0.295826644, 2.57339144, 0.164264113, -0.307559222, 0.90873754, -0.158881471, 0.216227651, 1.17361033, -0.0726163238, 1.05369902, 1.26502836, -0.559933841, 1.18652976, 1.32733107, -0.991645098, 0.412745744, 1.37741613, 0.156814083, 0.533913016, 1.67548609, 0.370449811, 0.634364069, 1.1493845, 0.51660651, 0.738265574, 0.5730896, 0.658008277, 0.152310789, 0.0271946769, 1.14128137, 0.0549481772, -0.471997976), array<f32, 6>(-0.652285874, 0.498014629, 1.82127774, -0.362266213, -1.538504, 1.94624293), 1.0, 100.0, 0.800000012, 0.930000007, 0.647738814, 2.84394932, 0.657612681);
// cloudmath/glsl/diffusion_lighting.glsl: GLSL twin of cloudmath/diffusion_lighting.hpp,
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
//           in diffusion_lighting_models.glsl; errors in the C++ header.
// GLSL 3.30 / ES 3.00: const arrays inside a struct, indexed at run time.

fn cmi_diffusion_depth(tau: f32) -> f32 { return clamp(tau, 0.0, 1e6); }

// (1 - albedo g, kappa): the similarity relations with absorption (C++ diffusion_similarity).
fn cm_diffusion_similarity(g: f32, albedo: f32) -> vec2f {
    let gc: f32 = clamp(g, -0.999, 0.999);
    let w: f32 = clamp(albedo, 0.0, 1.0);
    let s: f32 = max(1.0 - w * gc, 0.001);
    return vec2f(s, min(sqrt(3.0 * (1.0 - w) / s), 0.9));
}

// Fluence U (returned) and net flux F of the chord's diffusion solution with absorption
// kappa (the C++ diffusion_chord_fluence, same stable forms).
fn cm_diffusion_chord_fluence(x: f32, y: f32, exp_neg_x: f32, kappa: f32, flux: ptr<function, f32>) -> f32 {
    let z: f32 = CM_DIFFUSION_EXTRAPOLATION;
    let ez: f32 = exp(z);
    let L: f32 = x + y;
    let W: f32 = L + 2.0 * z;
    let a1: f32 = x + z;
    let a2: f32 = y + z;
    let e_far: f32 = exp(-(L + z));
    let k: f32 = clamp(kappa, 0.0, 0.9);
    var R1: f32;
    var R2: f32;
    var kQ1: f32;
    var kQ2: f32;
    if (k * W < 1e-4) {
        let k2: f32 = k * k;
        let W2: f32 = W * W;
        R1 = a1 / W * (1.0 + k2 * (a1 * a1 - W2) / 6.0);
        R2 = a2 / W * (1.0 + k2 * (a2 * a2 - W2) / 6.0);
        kQ1 = (1.0 + k2 * (a1 * a1 / 2.0 - W2 / 6.0)) / W;
        kQ2 = (1.0 + k2 * (a2 * a2 / 2.0 - W2 / 6.0)) / W;
    } else {
        let e1: f32 = exp(-k * a1);
        let e2: f32 = exp(-k * a2);
        let inv_denominator: f32 = 1.0 / cm_one_minus_exp_neg(2.0 * k * W);
        R1 = e2 * cm_one_minus_exp_neg(2.0 * k * a1) * inv_denominator;
        R2 = e1 * cm_one_minus_exp_neg(2.0 * k * a2) * inv_denominator;
        kQ1 = k * e2 * (1.0 + e1 * e1) * inv_denominator;
        kQ2 = k * e1 * (1.0 + e2 * e2) * inv_denominator;
    }
    let scale: f32 = 1.0 / (1.0 - k * k);
    (*flux) = scale * (ez * kQ2 - e_far * kQ1 - exp_neg_x);
    return max(3.0 * scale * (e_far * R1 + ez * R2 - exp_neg_x), 0.0);
}

// (u_sun, u_behind, u_mu, u_surface), each in [0, 1].
fn cm_diffusion_table_coordinates(tau_sun: f32, tau_behind: f32, tau_view: f32, mu: f32, g: f32, albedo: f32) -> vec4f {
    let s: f32 = cm_diffusion_similarity(g, albedo).x;
    let x: f32 = s * cmi_diffusion_depth(tau_sun);
    let y: f32 = s * cmi_diffusion_depth(tau_behind);
    let z: f32 = CM_DIFFUSION_EXTRAPOLATION;
    let t: f32 = (x + z) * (y + z) / (x + y + 2.0 * z);
    let d: f32 = s * cmi_diffusion_depth(tau_view) + z;
    return vec4f(x / (1.0 + x), y / (1.0 + y), 0.5 * clamp(mu, -1.0, 1.0) + 0.5, d / (d + t));
}

// Lower node and upper weight of u over n equally spaced nodes.
fn cmi_diffusion_hat(u: f32, n: i32, i0: ptr<function, i32>, w1: ptr<function, f32>) {
    let p: f32 = clamp(u, 0.0, 1.0) * f32(n - 1);
    // An integer clamp: int(NaN) is undefined (INT_MIN on common GPUs), and the node indexes
    // the table; [0, n - 2] whatever u is.
    let i: i32 = clamp(i32(p), 0, n - 2);
    (*i0) = i;
    (*w1) = p - f32(i);
}

fn cm_diffusion_table_lookup(m_in: CmDiffusionModel, u: vec4f) -> f32 {
    var m: CmDiffusionModel = m_in;
    var ix: i32;
    var iy: i32;
    var im: i32;
    var id: i32;
    var wx: f32;
    var wy: f32;
    var wm: f32;
    var wd: f32;
    cmi_diffusion_hat(u.x, CM_DIFFUSION_SIZE_X, &ix, &wx);
    cmi_diffusion_hat(u.y, CM_DIFFUSION_SIZE_Y, &iy, &wy);
    cmi_diffusion_hat(u.z, CM_DIFFUSION_SIZE_MU, &im, &wm);
    cmi_diffusion_hat(u.w, CM_DIFFUSION_SIZE_D, &id, &wd);
    var sum: f32 = 0.0;
    for (var a: i32 = 0; a < 2; a++) {
        for (var b: i32 = 0; b < 2; b++) {
            for (var c: i32 = 0; c < 2; c++) {
                for (var e: i32 = 0; e < 2; e++) {
                    let w: f32 = (select(1.0 - wx, wx, a == 1)) * (select(1.0 - wy, wy, b == 1)) * (select(1.0 - wm, wm, c == 1)) * (select(1.0 - wd, wd, e == 1));
                    let index: i32 = (((ix + a) * CM_DIFFUSION_SIZE_Y + iy + b) * CM_DIFFUSION_SIZE_MU + im + c) * CM_DIFFUSION_SIZE_D + id + e;
                    sum += w * m.table[index];
                }
            }
        }
    }
    return sum;
}

// The model with the three phase values it needs (scales 1, 0.5 and 0.8) given.
fn cmi_diffusion_scattering_phases(tau_sun: f32, tau_behind: f32, tau_view: f32, mu: f32, g: f32, albedo: f32, m: CmDiffusionModel, p1: f32, p_half: f32, p_four_fifths: f32) -> f32 {
    let mc: f32 = clamp(mu, -1.0, 1.0);
    let gc: f32 = clamp(g, -0.999, 0.999);
    let w: f32 = clamp(albedo, 0.0, 1.0);
    let medium: vec2f = cm_diffusion_similarity(gc, w);
    let ts: f32 = cmi_diffusion_depth(tau_sun);
    let x: f32 = medium.x * ts;
    let y: f32 = medium.x * cmi_diffusion_depth(tau_behind);
    let direct: f32 = exp(-ts);
    let e_half: f32 = exp(-0.5 * x);
    let e_one: f32 = e_half * e_half;
    let beams: vec3f = max(vec3f(e_half, e_one, e_one * e_one) - direct, vec3f(0.0));
    let w_half: f32 = m.peak[0] * beams.x + m.peak[2] * beams.y + m.peak[4] * beams.z;
    let w_four_fifths: f32 = m.peak[1] * beams.x + m.peak[3] * beams.y + m.peak[5] * beams.z;
    let peak: f32 = w_half * p_half + w_four_fifths * p_four_fifths;
    let source: f32 = w * (1.0 - gc) / medium.x;
    var flux: f32;
    let U: f32 = cm_diffusion_chord_fluence(x, y, e_one, medium.y, &flux);
    let D: f32 = source * max(U + 3.0 * gc * flux * mc, 0.0) * CM_INV_FOUR_PI;
    let C: f32 = cm_diffusion_table_lookup(m, cm_diffusion_table_coordinates(ts, tau_behind, tau_view, mc, gc, w));
    return max(p1 * direct + peak + D * max(C, 0.0), 0.0);
}

// With the Henyey-Greenstein phase function of asymmetry g.
fn cm_diffusion_scattering(tau_sun: f32, tau_behind: f32, tau_view: f32, mu: f32, g: f32, albedo: f32, m: CmDiffusionModel) -> f32 {
    let mc: f32 = clamp(mu, -1.0, 1.0);
    return cmi_diffusion_scattering_phases(tau_sun, tau_behind, tau_view, mu, g, albedo, m, cm_phase_hg(mc, g), cm_phase_hg(mc, 0.5 * g), cm_phase_hg(mc, 0.8 * g));
}
// cloudmath/glsl/cone_sampling.glsl: GLSL twin of cloudmath/cone_sampling.hpp, Schneider's
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

struct CmConeLightConfig {
    sample_count: i32, // all samples, the far one included
    step_length: f32, // length of each near segment
    cone_spread: f32, // cone radius per unit distance (tan of the half-angle)
    far_distance: f32, // distance of the far sample; <= 0: no far sample
    far_segment_length: f32, // optical-depth weight of the far sample
}

fn cmi_cone_has_far(cfg: CmConeLightConfig) -> bool { return cfg.far_distance > 0.0 && cfg.sample_count > 0; }
fn cmi_cone_near_count(cfg: CmConeLightConfig) -> i32 {
    return max(select(cfg.sample_count, cfg.sample_count - 1, cmi_cone_has_far(cfg)), 0);
}

// Point i of n of the Vogel spiral in the unit disc; i modulo n, n < 1 treated as 1; every
// int i and n (GLSL leaves % of negative operands undefined, hence the explicit wrap, which
// never overflows: -(i + 1) >= 0 for every negative i).
fn cm_cone_kernel_offset(i: i32, n: i32) -> vec2f {
    let count: i32 = max(n, 1);
    let k: i32 = select(count - 1 - (-(i + 1)) % count, i % count, i >= 0);
    let radius: f32 = sqrt((f32(k) + 0.5) / f32(count));
    let sc: vec2f = cmi_sin_cos(f32(k) * 2.39996322972865); // the golden angle, k times
    return radius * vec2f(sc.y, sc.x);
}

fn cm_cone_sample_distance(cfg: CmConeLightConfig, i: i32) -> f32 {
    let n_near: i32 = cmi_cone_near_count(cfg);
    if (cmi_cone_has_far(cfg) && i >= n_near) { return cfg.far_distance; }
    let k: i32 = clamp(i, 0, max(n_near - 1, 0));
    return (f32(k) + 0.5) * cfg.step_length;
}

fn cm_cone_sample_length(cfg: CmConeLightConfig, i: i32) -> f32 {
    return select(cfg.step_length, cfg.far_segment_length, cmi_cone_has_far(cfg) && i >= cmi_cone_near_count(cfg));
}

// Orthonormal u, v across the unit vector n (Duff et al., JCGT 2017).
fn cmi_orthonormal_basis(n: vec3f, u: ptr<function, vec3f>, v: ptr<function, vec3f>) {
    let s: f32 = select(-1.0, 1.0, n.z >= 0.0);
    let a: f32 = -1.0 / (s + n.z);
    let b: f32 = n.x * n.y * a;
    (*u) = vec3f(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    (*v) = vec3f(b, s + n.y * n.y * a, -n.y);
}

fn cm_cone_sample_position(origin: vec3f, light_dir: vec3f, cfg: CmConeLightConfig, i: i32) -> vec3f {
    let d: f32 = cm_cone_sample_distance(cfg, i);
    let n_near: i32 = cmi_cone_near_count(cfg);
    if (cmi_cone_has_far(cfg) && i >= n_near) { return origin + light_dir * d; }
    var u: vec3f;
    var v: vec3f;
    cmi_orthonormal_basis(light_dir, &u, &v);
    let k: vec2f = cm_cone_kernel_offset(i, n_near);
    return origin + light_dir * d + (u * k.x + v * k.y) * (cfg.cone_spread * d);
}
// cloudmath/glsl/geometry.glsl: GLSL twin of cloudmath/geometry.hpp: ray/sphere roots and
// planet-scale cloud-layer segments in the altitude form, accurate in float at Earth radius
// (c = (h - H)(2R + h + H) and a cancellation-free discriminant; see geometry.hpp).
// Results are vec2(t_near, t_far); vec2(-1) when the line misses.

// Roots of t^2 + 2 b t + c = 0 with disc = b^2 - c >= 0, sorted; stable q form.
fn cmi_stable_quadratic_roots(b: f32, c: f32, disc: f32) -> vec2f {
    let sq: f32 = sqrt(disc);
    let q: f32 = select((sq - b), -(b + sq), b >= 0.0);
    let t1: f32 = select(0.0, c / q, q != 0.0);
    return select(vec2f(t1, q), vec2f(q, t1), q < t1);
}

// A secant crossing the sphere ahead of the origin (a tangent contact does not count).
fn cmi_enters_ahead(roots: vec2f) -> bool { return roots.x >= 0.0 && roots.y > roots.x; }

// Error-free a * b = p + e (returned as vec2(p, e)) and a + b = s + e (Dekker's split,
// no FMA needed; geometry.hpp's two_product and two_sum). The split needs a * 4097 rounded
// before the subtraction: a compiler that fuses as - (as - a) into fma(a, 4097, -...) loses
// the exactness (measured: the HLSL twin through spirv-opt, 1.4e-5 off). CM_PRECISE (core.glsl)
// forbids that where the language can: `precise` in HLSL, and in GLSL 4.00+ if you define it so.
fn cmi_two_product(a: f32, b: f32) -> vec2f {
    let p: f32 = a * b;
    let as_: f32 = a * 4097.0;
    let bs: f32 = b * 4097.0;
    let ah: f32 = as_ - (as_ - a);
    let al: f32 = a - ah;
    let bh: f32 = bs - (bs - b);
    let bl: f32 = b - bh;
    let e: f32 = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return vec2f(p, e);
}
fn cmi_two_sum(a: f32, b: f32) -> vec2f {
    let s: f32 = a + b;
    let bb: f32 = s - a;
    let e: f32 = (a - (s - bb)) + (b - bb);
    return vec2f(s, e);
}

// |f|^2 - r^2 with the rounding errors of its products and sums added back; the plain form
// when a split overflows.
fn cmi_norm2_minus_square(f: vec3f, r: f32) -> f32 {
    let x: vec2f = cmi_two_product(f.x, f.x);
    let y: vec2f = cmi_two_product(f.y, f.y);
    let z: vec2f = cmi_two_product(f.z, f.z);
    let rr: vec2f = cmi_two_product(r, r);
    var s: vec2f = cmi_two_sum(x.x, y.x);
    var err: f32 = x.y + y.y + s.y;
    s = cmi_two_sum(s.x, z.x);
    err += z.y + s.y;
    s = cmi_two_sum(s.x, -rr.x);
    err += s.y - rr.y;
    let c: f32 = s.x + err;
    return select(dot(f, f) - r * r, c, abs(c) <= 3.402823466e38);
}

// Unit dir; c compensated, the discriminant b^2 - c near the sphere and Haines et al.'s
// r^2 - |f - (f.d) d|^2 far from it (geometry.hpp).
fn cm_ray_sphere_intersect(origin: vec3f, dir: vec3f, center: vec3f, radius: f32) -> vec2f {
    let f: vec3f = origin - center;
    let b: f32 = dot(f, dir);
    let c: f32 = cmi_norm2_minus_square(f, radius);
    var disc: f32;
    if (abs(c) < radius * radius) {
        let bb: vec2f = cmi_two_product(b, b);
        disc = (bb.x - c) + bb.y;
    } else {
        let perp: vec3f = f - b * dir;
        disc = radius * radius - dot(perp, perp);
    }
    if (disc < 0.0) { return vec2f(-1.0); }
    return cmi_stable_quadratic_roots(b, c, disc);
}

fn cm_ray_sphere_intersect_altitude(altitude: f32, cos_zenith: f32, planet_radius: f32, sphere_altitude: f32) -> vec2f {
    let mu: f32 = clamp(cos_zenith, -1.0, 1.0);
    let h: f32 = altitude;
    let H: f32 = sphere_altitude;
    let R: f32 = planet_radius;
    let r: f32 = R + h;
    let s: f32 = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    let disc: f32 = ((H - h) + r * mu * mu / (1.0 + s)) * ((R + H) + r * s);
    if (disc < 0.0) { return vec2f(-1.0); }
    let b: f32 = r * mu;
    let c: f32 = (h - H) * (2.0 * R + h + H);
    return cmi_stable_quadratic_roots(b, c, disc);
}

fn cm_cloud_layer_segment(altitude: f32, cos_zenith: f32, planet_radius: f32, layer_bottom: f32, layer_top: f32) -> vec2f {
    let none: vec2f = vec2f(-1.0);
    let h: f32 = max(altitude, 0.0);
    let bottom: f32 = min(layer_bottom, layer_top);
    let top: f32 = max(layer_bottom, layer_top);
    let to_top: vec2f = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, top);
    let to_bottom: vec2f = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, bottom);
    let to_ground: vec2f = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, 0.0);
    var t_start: f32;
    var t_end: f32;
    if (h < bottom) {
        t_start = to_bottom.y;
        t_end = to_top.y;
    } else if (h <= top) {
        t_start = 0.0;
        t_end = select(to_top.y, to_bottom.x, cmi_enters_ahead(to_bottom));
    } else {
        if (!cmi_enters_ahead(to_top)) { return none; }
        t_start = to_top.x;
        t_end = select(to_top.y, to_bottom.x, cmi_enters_ahead(to_bottom));
    }
    if (cmi_enters_ahead(to_ground)) {
        if (to_ground.x <= t_start) { return none; }
        t_end = min(t_end, to_ground.x);
    }
    return vec2f(t_start, t_end);
}

fn cm_altitude_along_ray(altitude: f32, cos_zenith: f32, planet_radius: f32, t: f32) -> f32 {
    let mu: f32 = clamp(cos_zenith, -1.0, 1.0);
    let R: f32 = planet_radius;
    let r: f32 = R + altitude;
    let excess: f32 = altitude * (2.0 * R + altitude) + t * (2.0 * r * mu + t);
    let radius: f32 = sqrt(max(R * R + excess, 0.0));
    return excess / (radius + R);
}

// Altitude of p given relative to the camera (+y up at the camera); the camera at p = 0.
fn cm_point_altitude(p: vec3f, camera_altitude: f32, planet_radius: f32) -> f32 {
    let t: f32 = length(p);
    if (t > 0.0) {
        return cm_altitude_along_ray(camera_altitude, p.y / t, planet_radius, t);
    }
    return camera_altitude;
}

fn cm_height_fraction(altitude: f32, layer_bottom: f32, layer_top: f32) -> f32 {
    return cmi_remap_unit(altitude, layer_bottom, layer_top); // cm_remap_clamped(..., 0.0, 1.0)
}
// cloudmath/glsl/density.glsl: GLSL twin of cloudmath/density.hpp: height gradients and
// presets, coverage, erosion, exponential height fog and its analytic optical depth.

fn cm_height_gradient(h: f32, profile: vec4f) -> f32 {
    return cm_smoothstep_safe(profile.x, profile.y, h) - cm_smoothstep_safe(profile.z, profile.w, h);
}

fn cm_height_profile_stratus() -> vec4f { return vec4f(0.02, 0.05, 0.09, 0.11); }
fn cm_height_profile_stratocumulus() -> vec4f { return vec4f(0.02, 0.2, 0.48, 0.625); }
fn cm_height_profile_cumulus() -> vec4f { return vec4f(0.01, 0.0625, 0.78, 1.0); }

// Type 0 stratus, 0.5 stratocumulus, 1 cumulus; profiles blended with weights summing to 1.
fn cm_height_profile_for_type(cloud_type: f32) -> vec4f {
    let t: f32 = cm_saturate(cloud_type);
    let w_stratus: f32 = 1.0 - cm_saturate(2.0 * t);
    let w_stratocumulus: f32 = 1.0 - abs(t - 0.5) * 2.0;
    let w_cumulus: f32 = cm_saturate(t - 0.5) * 2.0;
    return cm_height_profile_stratus() * w_stratus + cm_height_profile_stratocumulus() * w_stratocumulus + cm_height_profile_cumulus() * w_cumulus;
}

fn cm_height_gradient_for_type(h: f32, cloud_type: f32) -> f32 {
    return cm_height_gradient(h, cm_height_profile_for_type(cloud_type));
}

// The height fractions outside which cm_height_gradient_for_type is exactly 0: clamp a
// march to them.
fn cm_height_range_for_type(cloud_type: f32) -> vec2f {
    let p: vec4f = cm_height_profile_for_type(cloud_type);
    return vec2f(p.x, p.w);
}

// (1 - exp(-a h)) exp(-b h) (Olajos 2016: a = 50, b = 4), in [0, 1] for every finite input:
// h <= 0 gives 0, a < 0 and b < 0 act as 0 (h clamped before either exponential: no 0 * Inf).
fn cm_height_gradient_exponential(h: f32, a: f32, b: f32) -> f32 {
    let height: f32 = max(h, 0.0);
    return cm_one_minus_exp_neg(max(a, 0.0) * height) * exp(-max(b, 0.0) * height);
}

// max(0, base + coverage - 1): monotonic in coverage; coverage clamped to [0, 1].
fn cm_apply_coverage(base: f32, coverage: f32) -> f32 {
    let c: f32 = cm_saturate(coverage);
    return cmi_remap_unit(base, 1.0 - c, 1.0) * c; // cm_remap_clamped(..., 0.0, 1.0)
}

fn cm_erode(base: f32, erosion: f32) -> f32 { return cmi_remap_unit(base, erosion, 1.0); } // cm_remap_clamped(..., 0, 1)

// The exponent is floored at -104 (exp gives 0 there in float, as in C++) before exp: a driver
// that folds exp's log2(e) into the product would otherwise compute (-falloff log2 e) *
// altitude, which is Inf * 0 = NaN for a huge falloff at altitude 0 (glsl.fuzz found it).
fn cm_height_fog_density(altitude: f32, density_at_zero: f32, falloff: f32) -> f32 {
    return density_at_zero * exp(max(-falloff * altitude, -104.0));
}

// rho0 L exp(-k h_low) (1 - exp(-x)) / x, x = k |mu| L, from the lower end of the ray.
fn cm_height_fog_optical_depth(altitude: f32, cos_zenith: f32, distance: f32, density_at_zero: f32, falloff: f32) -> f32 {
    let mu: f32 = clamp(cos_zenith, -1.0, 1.0);
    let rise: f32 = mu * distance;
    let h_low: f32 = select(altitude, altitude + rise, rise < 0.0);
    return density_at_zero * distance * exp(max(-falloff * h_low, -104.0)) * cm_one_minus_exp_neg_over_x(falloff * abs(rise));
}

// Clear air's optical depth (r, g, b): Rayleigh (5.802, 13.558, 33.1) 1e-6 /m, scale height
// 8 km, plus aerosols 4.40e-6 /m, scale height 1.2 km (Bruneton 2017, Hillaire 2020).
fn cm_air_optical_depth(altitude: f32, cos_zenith: f32, distance: f32) -> vec3f {
    let rayleigh: f32 = cm_height_fog_optical_depth(altitude, cos_zenith, distance, 1.0, 1.0 / 8000.0);
    let aerosol: f32 = cm_height_fog_optical_depth(altitude, cos_zenith, distance, 4.40e-6, 1.0 / 1200.0);
    return vec3f(5.802e-6, 13.558e-6, 33.1e-6) * rayleigh + vec3f(aerosol);
}

// L e^-tau + L_air (1 - e^-tau): radiance seen through air that scatters L_air.
// The two weighted terms (no L_air - L: it lost L_air when L >> L_air), clamped to the
// interval between L and L_air; tau < 0 taken as 0.
fn cm_aerial_perspective(L: f32, L_air: f32, tau: f32) -> f32 {
    let t: f32 = max(tau, 0.0);
    return clamp(L * exp(-t) + L_air * cm_one_minus_exp_neg(t), min(L, L_air), max(L, L_air));
}
fn cm_aerial_perspective_v3v3v3(L: vec3f, L_air: vec3f, tau: vec3f) -> vec3f {
    let t: vec3f = max(tau, vec3f(0.0));
    return clamp(L * exp(-t) + L_air * cm_one_minus_exp_neg_v3(t), min(L, L_air), max(L, L_air));
}

// Nubis density model (density.hpp): steps on already-sampled texture values.
fn cm_nubis_low_frequency_fbm(base: vec4f) -> f32 { return base.y * 0.625 + base.z * 0.25 + base.w * 0.125; }
fn cm_nubis_base_cloud(base: vec4f) -> f32 {
    return cm_remap(base.x, cm_nubis_low_frequency_fbm(base) - 1.0, 1.0, 0.0, 1.0);
}
fn cm_nubis_high_frequency_fbm(detail: vec3f) -> f32 {
    return detail.x * 0.625 + detail.y * 0.25 + detail.z * 0.125;
}
fn cm_nubis_detail_erosion(detail: vec3f, h: f32) -> f32 {
    let hf: f32 = cm_nubis_high_frequency_fbm(detail);
    let t: f32 = cm_saturate(h * 10.0);
    return (hf + t * ((1.0 - hf) - hf)) * 0.2;
}
// 0.6 + 0.4 saturate(weather_b): a cloud's top as a share of its type's profile.
fn cm_cloud_top_fraction(weather_b: f32) -> f32 { return 0.6 + 0.4 * cm_saturate(weather_b); }

// Base shape with per-cloud type (G), top (B) and coverage narrowing with height (rounded tops).
fn cm_cloud_shape_density(base: vec4f, weather: vec3f, h: f32, coverage: f32, cloud_type: f32, type_spread: f32, top_rounding: f32) -> f32 {
    let hc: f32 = h / cm_cloud_top_fraction(weather.z);
    if (!(hc < 1.0)) { return 0.0; }
    let t: f32 = cm_saturate(cloud_type + (weather.y - 0.5) * type_spread);
    let hr: f32 = max(hc, 0.0); // under the layer nothing to round (hc^2 overflowed: NaN)
    let c: f32 = cm_saturate(weather.x - 0.5 + coverage) * (1.0 - top_rounding * hr * hr);
    return cm_apply_coverage(cm_nubis_base_cloud(base) * cm_height_gradient_for_type(hc, t), c);
}

fn cm_nubis_density(base: vec4f, detail: vec3f, coverage: f32, cloud_type: f32, h: f32) -> f32 {
    let shaped: f32 = cm_nubis_base_cloud(base) * cm_height_gradient_for_type(h, cloud_type);
    return cm_erode(cm_apply_coverage(shaped, coverage), cm_nubis_detail_erosion(detail, h));
}
// cloudmath/glsl/noise.glsl: GLSL twin of cloudmath/noise.hpp: tileable improved Perlin
// (2D, 3D, analytic derivatives), Worley, fBm, Nubis Worley fBm, Perlin-Worley, curl noise.
// p in lattice cells; period = cells per tile (int >= 1); seed a uint (overloads without it
// use 0). The hashes are uint arithmetic and match the C++ bit for bit; in GLSL ES fragment
// shaders declare `precision highp int;` so that uint has 32 bits.

// 32-bit mixer ("lowbias32" constants), identical to cloudmath::noise_hash.
fn cm_noise_hash(x_in: u32) -> u32 {
    var x: u32 = x_in;
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}
fn cm_noise_hash_uuuu(x: u32, y: u32, z: u32, seed: u32) -> u32 {
    return cm_noise_hash(x + cm_noise_hash(y + cm_noise_hash(z + cm_noise_hash(seed))));
}

// Low-discrepancy sequences in 32-bit fixed point (Roberts 2018), bit-identical to the C++:
// R1 (golden ratio), R2 (plastic number), and a pixel's march offset for a frame.
fn cm_low_discrepancy_r1(n: u32) -> f32 { return f32((0x80000000u + n * 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0); }
fn cm_low_discrepancy_r2(n: u32) -> vec2f {
    return vec2f(f32((0x80000000u + n * 0xc13fa9a9u) >> 8u), f32((0x80000000u + n * 0x91e10da6u) >> 8u)) * (1.0 / 16777216.0);
}
fn cm_frame_jitter(pixel_hash: u32, frame: u32) -> f32 {
    return f32((pixel_hash + frame * 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0);
}
// The index-th sample's offset of a pixel's frame (R1 over frames, R-sequence over indices).
fn cm_sample_jitter(pixel_hash: u32, frame: u32, index: u32) -> f32 {
    return cm_frame_jitter(pixel_hash + index * 0xc13fa9a9u, frame);
}
// Triangular noise in (-1, 1) from one hash (add / 255 before an 8-bit store).
fn cm_triangular_dither(h: u32) -> f32 { return (f32(h & 0xffffu) - f32(h >> 16u)) * (1.0 / 65536.0); }

// i modulo n in [0, n) with % on non-negative operands only.
fn cmi_wrap_cell(i: i32, n: i32) -> i32 { return select(n - 1 - ((-(i + 1)) % n), i % n, i >= 0); }
// floor(p) as ints clamped to +-2^30, and periods saturated at 2^30, as in noise.hpp: no
// overflow for coordinates or octave counts outside the documented domain.
fn cmi_floor_to_cell(p: vec3f) -> vec3i {
    return vec3i(clamp(floor(p), vec3f(-1073741824.0), vec3f(1073741824.0)));
}
fn cmi_grow_period(period: i32, factor: i32) -> i32 {
    return select(period * factor, 1073741824, period > 1073741824 / factor);
}
// The top 24 bits of a hash in [0, 1), exact (noise.hpp's hash_to_unit).
fn cm_hash_to_unit(h: u32) -> f32 { return f32(h >> 8u) * (1.0 / 16777216.0); }
fn cmi_fade(t: f32) -> f32 { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
fn cmi_fade_derivative(t: f32) -> f32 { return 30.0 * t * t * (t - 1.0) * (t - 1.0); }

var<private> CMI_GRADIENTS3: array<vec3f, 16> = array<vec3f, 16>(vec3f(1.0, 1.0, 0.0), vec3f(-1.0, 1.0, 0.0), vec3f(1.0, -1.0, 0.0), vec3f(-1.0, -1.0, 0.0), vec3f(1.0, 0.0, 1.0), vec3f(-1.0, 0.0, 1.0), vec3f(1.0, 0.0, -1.0), vec3f(-1.0, 0.0, -1.0), vec3f(0.0, 1.0, 1.0), vec3f(0.0, -1.0, 1.0), vec3f(0.0, 1.0, -1.0), vec3f(0.0, -1.0, -1.0), vec3f(1.0, 1.0, 0.0), vec3f(-1.0, 1.0, 0.0), vec3f(0.0, -1.0, 1.0), vec3f(0.0, -1.0, -1.0));
var<private> CMI_GRADIENTS2: array<vec2f, 8> = array<vec2f, 8>(vec2f(1.0, 0.0), vec2f(-1.0, 0.0), vec2f(0.0, 1.0), vec2f(0.0, -1.0), vec2f(0.70710678, 0.70710678), vec2f(-0.70710678, 0.70710678), vec2f(0.70710678, -0.70710678), vec2f(-0.70710678, -0.70710678));
fn cmi_gradient3(h: u32) -> vec3f { return CMI_GRADIENTS3[i32(h & 15u)]; }
fn cmi_gradient2(h: u32) -> vec2f { return CMI_GRADIENTS2[i32(h & 7u)]; }

const CMI_PERLIN3_SCALE = 0.96592582628906829; // cos 15 deg: raw extremes +-1.0352764
const CMI_PERLIN2_SCALE = 1.41421356237309505; // sqrt 2: raw extremes +-0.70710678

// (value, d/dx, d/dy, d/dz) of improved Perlin noise, before the clamp of cm_perlin_noise.
fn cm_perlin_noise_derivatives(p: vec3f, period: i32, seed: u32) -> vec4f {
    let n: i32 = max(period, 1);
    let i: vec3i = cmi_floor_to_cell(p);
    let q: vec3f = p - floor(p);
    let x: f32 = q.x;
    let y: f32 = q.y;
    let z: f32 = q.z;
    let x0: u32 = u32(cmi_wrap_cell(i.x, n));
    let y0: u32 = u32(cmi_wrap_cell(i.y, n));
    let z0: u32 = u32(cmi_wrap_cell(i.z, n));
    let x1: u32 = u32(cmi_wrap_cell(i.x + 1, n));
    let y1: u32 = u32(cmi_wrap_cell(i.y + 1, n));
    let z1: u32 = u32(cmi_wrap_cell(i.z + 1, n));
    let g000: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y0, z0, seed));
    let g100: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y0, z0, seed));
    let g010: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y1, z0, seed));
    let g110: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y1, z0, seed));
    let g001: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y0, z1, seed));
    let g101: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y0, z1, seed));
    let g011: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y1, z1, seed));
    let g111: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y1, z1, seed));
    let v000: f32 = g000.x * x + g000.y * y + g000.z * z;
    let v100: f32 = g100.x * (x - 1.0) + g100.y * y + g100.z * z;
    let v010: f32 = g010.x * x + g010.y * (y - 1.0) + g010.z * z;
    let v110: f32 = g110.x * (x - 1.0) + g110.y * (y - 1.0) + g110.z * z;
    let v001: f32 = g001.x * x + g001.y * y + g001.z * (z - 1.0);
    let v101: f32 = g101.x * (x - 1.0) + g101.y * y + g101.z * (z - 1.0);
    let v011: f32 = g011.x * x + g011.y * (y - 1.0) + g011.z * (z - 1.0);
    let v111: f32 = g111.x * (x - 1.0) + g111.y * (y - 1.0) + g111.z * (z - 1.0);
    let u: f32 = cmi_fade(x);
    let v: f32 = cmi_fade(y);
    let w: f32 = cmi_fade(z);
    let du: f32 = cmi_fade_derivative(x);
    let dv: f32 = cmi_fade_derivative(y);
    let dw: f32 = cmi_fade_derivative(z);
    let k0: f32 = v000;
    let k1: f32 = v100 - v000;
    let k2: f32 = v010 - v000;
    let k3: f32 = v001 - v000;
    let k4: f32 = v000 - v100 - v010 + v110;
    let k5: f32 = v000 - v010 - v001 + v011;
    let k6: f32 = v000 - v100 - v001 + v101;
    let k7: f32 = -v000 + v100 + v010 - v110 + v001 - v101 - v011 + v111;
    let value: f32 = k0 + k1 * u + k2 * v + k3 * w + k4 * u * v + k5 * v * w + k6 * w * u + k7 * u * v * w;
    let gk1: vec3f = g100 - g000;
    let gk2: vec3f = g010 - g000;
    let gk3: vec3f = g001 - g000;
    let gk4: vec3f = g000 - g100 - g010 + g110;
    let gk5: vec3f = g000 - g010 - g001 + g011;
    let gk6: vec3f = g000 - g100 - g001 + g101;
    let gk7: vec3f = -g000 + g100 + g010 - g110 + g001 - g101 - g011 + g111;
    var grad: vec3f = g000 + gk1 * u + gk2 * v + gk3 * w + gk4 * (u * v) + gk5 * (v * w) + gk6 * (w * u) + gk7 * (u * v * w);
    grad.x += du * (k1 + k4 * v + k6 * w + k7 * v * w);
    grad.y += dv * (k2 + k4 * u + k5 * w + k7 * u * w);
    grad.z += dw * (k3 + k5 * v + k6 * u + k7 * u * v);
    return vec4f(value, grad) * CMI_PERLIN3_SCALE;
}
fn cm_perlin_noise_derivatives_v3i(p: vec3f, period: i32) -> vec4f {
    return cm_perlin_noise_derivatives(p, period, 0u);
}

fn cm_perlin_noise(p: vec3f, period: i32, seed: u32) -> f32 {
    return clamp(cm_perlin_noise_derivatives(p, period, seed).x, -1.0, 1.0);
}
fn cm_perlin_noise_v3i(p: vec3f, period: i32) -> f32 { return cm_perlin_noise(p, period, 0u); }

fn cm_perlin_noise_v2iu(p: vec2f, period: i32, seed: u32) -> f32 {
    let n: i32 = max(period, 1);
    let i: vec2i = cmi_floor_to_cell(vec3f(p, 0.0)).xy;
    let q: vec2f = p - floor(p);
    let x0: u32 = u32(cmi_wrap_cell(i.x, n));
    let y0: u32 = u32(cmi_wrap_cell(i.y, n));
    let x1: u32 = u32(cmi_wrap_cell(i.x + 1, n));
    let y1: u32 = u32(cmi_wrap_cell(i.y + 1, n));
    let g00: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x0, y0, 0u, seed));
    let g10: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x1, y0, 0u, seed));
    let g01: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x0, y1, 0u, seed));
    let g11: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x1, y1, 0u, seed));
    let v00: f32 = g00.x * q.x + g00.y * q.y;
    let v10: f32 = g10.x * (q.x - 1.0) + g10.y * q.y;
    let v01: f32 = g01.x * q.x + g01.y * (q.y - 1.0);
    let v11: f32 = g11.x * (q.x - 1.0) + g11.y * (q.y - 1.0);
    let u: f32 = cmi_fade(q.x);
    let v: f32 = cmi_fade(q.y);
    let a: f32 = v00 + u * (v10 - v00);
    let b: f32 = v01 + u * (v11 - v01);
    return clamp((a + v * (b - a)) * CMI_PERLIN2_SCALE, -1.0, 1.0);
}
fn cm_perlin_noise_v2i(p: vec2f, period: i32) -> f32 { return cm_perlin_noise_v2iu(p, period, 0u); }

// Distance to the nearest feature point (one per cell, 27-cell search, which is not exact in
// rare configurations: see noise.hpp), in [0, sqrt 3].
fn cm_worley_f1(p: vec3f, period: i32, seed: u32) -> f32 {
    let n: i32 = max(period, 1);
    let i: vec3i = cmi_floor_to_cell(p);
    let q: vec3f = p - floor(p);
    var best: f32 = 3.0;
    for (var dz: i32 = -1; dz <= 1; dz++) {
        for (var dy: i32 = -1; dy <= 1; dy++) {
            for (var dx: i32 = -1; dx <= 1; dx++) {
                let h: u32 = cm_noise_hash_uuuu(u32(cmi_wrap_cell(i.x + dx, n)), u32(cmi_wrap_cell(i.y + dy, n)), u32(cmi_wrap_cell(i.z + dz, n)), seed);
                let h2: u32 = cm_noise_hash(h);
                let h3: u32 = cm_noise_hash(h2);
                let ox: f32 = f32(dx) + cm_hash_to_unit(h) - q.x;
                let oy: f32 = f32(dy) + cm_hash_to_unit(h2) - q.y;
                let oz: f32 = f32(dz) + cm_hash_to_unit(h3) - q.z;
                let d2: f32 = ox * ox + oy * oy + oz * oz;
                best = select(best, d2, d2 < best);
            }
        }
    }
    return sqrt(best);
}
fn cm_worley_f1_v3i(p: vec3f, period: i32) -> f32 { return cm_worley_f1(p, period, 0u); }

// 1 - F1 / sqrt(3) in [0, 1].
fn cm_worley_noise(p: vec3f, period: i32, seed: u32) -> f32 {
    return cm_saturate(1.0 - cm_worley_f1(p, period, seed) * 0.57735026918962576);
}
fn cm_worley_noise_v3i(p: vec3f, period: i32) -> f32 { return cm_worley_noise(p, period, 0u); }

// fBm: octave i has amplitude gain^i, frequency and period times lacunarity^i, seed + i;
// divided by the sum of amplitudes. octaves and lacunarity below 1 are treated as 1; gain is
// clamped to [0, 1], so the sum of amplitudes is at least 1 (no division by 0 for negative
// gains, no overflow for large ones) and the result stays in the base noise's range.
// One loop for the three fBm twins (GLSL has no callables): kind 0 is 3D Perlin, 1 is 2D
// Perlin on p.xy, 2 is Worley; the callers pass constants, which drivers fold.
fn cmi_fbm(p: vec3f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32, kind: i32) -> f32 {
    let count: i32 = max(octaves, 1);
    let lac: i32 = max(lacunarity, 1);
    var per: i32 = max(period, 1);
    let g: f32 = clamp(gain, 0.0, 1.0);
    var sum: f32 = 0.0;
    var norm: f32 = 0.0;
    var amplitude: f32 = 1.0;
    var frequency: f32 = 1.0;
    for (var i: i32 = 0; i < count; i++) {
        let q: vec3f = p * frequency;
        let s: u32 = seed + u32(i);
        var octave: f32;
        if (kind == 0) {
            octave = cm_perlin_noise(q, per, s);
        } else if (kind == 1) {
            octave = cm_perlin_noise_v2iu(q.xy, per, s);
        } else {
            octave = cm_worley_noise(q, per, s);
        }
        sum += amplitude * octave;
        norm += amplitude;
        amplitude *= g;
        frequency *= f32(lac);
        per = cmi_grow_period(per, lac);
    }
    return sum / norm;
}

fn cm_perlin_fbm(p: vec3f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32) -> f32 {
    return cmi_fbm(p, period, octaves, lacunarity, gain, seed, 0);
}
fn cm_perlin_fbm_v3ii(p: vec3f, period: i32, octaves: i32) -> f32 {
    return cm_perlin_fbm(p, period, octaves, 2, 0.5, 0u);
}

fn cm_perlin_fbm_v2iiifu(p: vec2f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32) -> f32 {
    return cmi_fbm(vec3f(p, 0.0), period, octaves, lacunarity, gain, seed, 1);
}
fn cm_perlin_fbm_v2ii(p: vec2f, period: i32, octaves: i32) -> f32 {
    return cm_perlin_fbm_v2iiifu(p, period, octaves, 2, 0.5, 0u);
}

fn cm_worley_fbm(p: vec3f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32) -> f32 {
    return cmi_fbm(p, period, octaves, lacunarity, gain, seed, 2);
}
fn cm_worley_fbm_v3ii(p: vec3f, period: i32, octaves: i32) -> f32 {
    return cm_worley_fbm(p, period, octaves, 2, 0.5, 0u);
}

// 0.625 W(p) + 0.25 W(2p) + 0.125 W(4p), periods doubling (Schneider 2015).
fn cm_worley_fbm_nubis(p: vec3f, period: i32, seed: u32) -> f32 {
    let n: i32 = max(period, 1);
    return 0.625 * cm_worley_noise(p, n, seed) + 0.25 * cm_worley_noise(p * 2.0, cmi_grow_period(n, 2), seed + 1u) + 0.125 * cm_worley_noise(p * 4.0, cmi_grow_period(n, 4), seed + 2u);
}
fn cm_worley_fbm_nubis_v3i(p: vec3f, period: i32) -> f32 { return cm_worley_fbm_nubis(p, period, 0u); }

// Perlin fBm (3 octaves, in [0, 1]) dilated by the Nubis Worley fBm (Schneider 2015).
fn cm_perlin_worley(p: vec3f, period: i32, seed: u32) -> f32 {
    let perlin: f32 = cm_perlin_fbm(p, period, 3, 2, 0.5, seed) * 0.5 + 0.5;
    let worley: f32 = cm_worley_fbm_nubis(p, period, seed + 101u);
    return cmi_remap_unit(perlin, worley - 1.0, 1.0); // cm_remap_clamped(..., 0.0, 1.0)
}
fn cm_perlin_worley_v3i(p: vec3f, period: i32) -> f32 { return cm_perlin_worley(p, period, 0u); }

// Curl of the potential (Perlin seed, seed + 1, seed + 2), divergence-free (Bridson 2007).
fn cm_curl_noise(p: vec3f, period: i32, seed: u32) -> vec3f {
    let a: vec4f = cm_perlin_noise_derivatives(p, period, seed);
    let b: vec4f = cm_perlin_noise_derivatives(p, period, seed + 1u);
    let c: vec4f = cm_perlin_noise_derivatives(p, period, seed + 2u);
    return vec3f(c.z - b.w, a.w - c.y, b.y - a.z);
}
fn cm_curl_noise_v3i(p: vec3f, period: i32) -> vec3f { return cm_curl_noise(p, period, 0u); }

fn cm_curl_noise_v2iu(p: vec2f, period: i32, seed: u32) -> vec2f {
    let d: vec4f = cm_perlin_noise_derivatives(vec3f(p, 0.0), period, seed);
    return vec2f(d.z, -d.y);
}
fn cm_curl_noise_v2i(p: vec2f, period: i32) -> vec2f { return cm_curl_noise_v2iu(p, period, 0u); }
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
// cloudmath/glsl/reprojection.glsl: GLSL twin of cloudmath/reprojection.hpp: the pixel of
// each 4 x 4 block a frame renders (Bayer order), the projection of a point into a previous
// camera, the bilinear footprint of a history lookup and the running-mean blend weight.
// Use: uvec2 o = cm_temporal_update_offset(frame);
//      vec3 uvz = cm_camera_project(p_prev, fwd, right, up, tan_half_fov, aspect);
//      vec4 fp = cm_texel_bilinear(uvz.xy, vec2(textureSize(history, 0)));  // texelFetch taps

// Rank of (x mod 4, y mod 4) in the 4 x 4 Bayer matrix: 4 [0 2; 3 1](low bits) + (high bits).
fn cm_bayer_index_4x4(x: u32, y: u32) -> u32 {
    let lo: u32 = (((x ^ y) & 1u) << 1u) | (y & 1u);
    let hi: u32 = ((((x >> 1u) ^ (y >> 1u)) & 1u) << 1u) | ((y >> 1u) & 1u);
    return 4u * lo + hi;
}

// The pixel of each 4 x 4 block with Bayer rank frame mod 16.
fn cm_temporal_update_offset(frame: u32) -> vec2u {
    let i: u32 = frame & 15u;
    let lo: u32 = i >> 2u;
    let hi: u32 = i & 3u;
    return vec2u(((lo >> 1u) ^ lo) & 1u, lo & 1u) + 2u * vec2u(((hi >> 1u) ^ hi) & 1u, hi & 1u);
}

// (u, v, depth) of camera-relative p in the pinhole camera; (-1, -1, z) when z <= 0 or NaN.
fn cm_camera_project(p: vec3f, forward: vec3f, right: vec3f, up: vec3f, tan_half_fov: f32, aspect: f32) -> vec3f {
    let z: f32 = dot(p, forward);
    if (!(z > 0.0)) { return vec3f(-1.0, -1.0, z); }
    let s: f32 = 0.5 / (z * tan_half_fov);
    return vec3f(0.5 + dot(p, right) * s / aspect, 0.5 + dot(p, up) * s, z);
}

// (x0, y0, fx, fy): texels x0..x0+1, y0..y0+1 weighted like GL_LINEAR, for texelFetch.
fn cm_texel_bilinear(uv: vec2f, size: vec2f) -> vec4f {
    let scaled: vec2f = uv * size;
    var st: vec2f = scaled - 0.5;
    // Within 4 ulp of uv * size of an integer: that integer (a texel centre, uv rounded).
    let nearest: vec2f = floor(st + 0.5);
    let tolerance: vec2f = 4.0 * 1.1920929e-7 * max(abs(scaled), vec2f(1.0));
    if (abs(st.x - nearest.x) <= tolerance.x) { st.x = nearest.x; }
    if (abs(st.y - nearest.y) <= tolerance.y) { st.y = nearest.y; }
    let base: vec2f = floor(st);
    return vec4f(base, st - base);
}

// 1 / (min(history_samples, max_samples - 1) + 1); 1 for an empty (or NaN) history.
fn cm_temporal_blend_weight(history_samples: f32, max_samples: f32) -> f32 {
    let cap: f32 = select(0.0, max_samples - 1.0, max_samples > 1.0);
    let n: f32 = select(0.0, (select(cap, history_samples, history_samples < cap)), history_samples > 0.0);
    return 1.0 / (n + 1.0);
}
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
// cloudmath/glsl/atmosphere.glsl: GLSL twin of cloudmath/atmosphere.hpp: a planet's air
// (CmAtmosphere, Earth's from cm_earth_atmosphere()), its extinction at an altitude, the
// optical depth and transmittance along a ray by quadrature, the transmittance LUT's
// parametrisation (Bruneton 2017) both ways, the scattering coefficients, the sun's illuminance,
// Hillaire 2020's multiple scattering and its LUT's parametrisation, the sky's radiance and the
// aerial perspective (with CM_ATMOSPHERE_TABLE, below), and EV100 exposure.
// Use: CmAtmosphere air = cm_earth_atmosphere();
//      vec3 T_sun = cm_atmosphere_transmittance(air, altitude, sun_dir.y, 64);
//      vec3 T_lut = texture(u_transmittance_lut, cm_atmosphere_transmittance_lut_uv(air, altitude, mu, vec2(256.0, 64.0))).rgb;
//      // with #define CM_ATMOSPHERE_TABLE my_table before the include (the section below):
//      vec3 sky = sun_lux * cm_atmosphere_sky_radiance(air, CmAtmosphereTable(32, 32, 3, 64), altitude, view_dir, sun_dir, 32, 32);
// Units: metres, 1/m; channels 680, 550, 440 nm.

// atmosphere_parameters (atmosphere.hpp), field for field.
struct CmAtmosphere {
    bottom_radius: f32,
    top_radius: f32,
    rayleigh_scattering: vec3f,
    rayleigh_scale_height: f32,
    mie_scattering: f32,
    mie_extinction: f32,
    mie_scale_height: f32,
    mie_g: f32,
    ozone_absorption: vec3f,
    ozone_center: f32,
    ozone_half_width: f32,
    ground_albedo: f32,
}

// Earth's air (Bruneton 2017): see earth_atmosphere() in atmosphere.hpp.
fn cm_earth_atmosphere() -> CmAtmosphere {
    return CmAtmosphere(6360e3, 6420e3, vec3f(5.802e-6, 13.558e-6, 33.1e-6), 8000.0, 3.996e-6, 4.40e-6, 1200.0, 0.8, vec3f(0.650e-6, 1.881e-6, 0.085e-6), 25e3, 15e3, 0.1);
}

// Rayleigh + Mie extinction + ozone absorption at an altitude (below 0 taken as 0).
fn cm_atmosphere_extinction(air: CmAtmosphere, altitude: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    let tent: f32 = max(1.0 - abs(h - air.ozone_center) / air.ozone_half_width, 0.0);
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) + vec3f(air.mie_extinction * exp(-h / air.mie_scale_height)) + air.ozone_absorption * tent;
}

// The distance along the ray to the top of the air (0 once outside, pointing outward).
fn cm_atmosphere_distance_to_top(air: CmAtmosphere, altitude: f32, cos_zenith: f32) -> f32 {
    let t: vec2f = cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, air.top_radius - air.bottom_radius);
    return max(t.y, 0.0);
}

// True when the ray meets the ground sphere in front of the point.
fn cm_atmosphere_ray_hits_ground(air: CmAtmosphere, altitude: f32, cos_zenith: f32) -> bool {
    if (!(cos_zenith < 0.0)) { return false; }
    let t: vec2f = cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, 0.0);
    return t.x >= 0.0 && t.y >= t.x;
}

// Optical depth along `distance` metres of the ray: the midpoint rule over `steps` steps.
fn cm_atmosphere_optical_depth(air: CmAtmosphere, altitude: f32, cos_zenith: f32, distance: f32, steps: i32) -> vec3f {
    let n: i32 = max(steps, 1);
    let ds: f32 = max(distance, 0.0) / f32(n);
    var tau: vec3f = vec3f(0.0);
    for (var i: i32 = 0; i < n; i++) {
        let t: f32 = (f32(i) + 0.5) * ds;
        tau += cm_atmosphere_extinction(air, cm_altitude_along_ray(altitude, cos_zenith, air.bottom_radius, t));
    }
    return tau * ds;
}

// Transmittance from the point to the top of the air along the direction; 0 into the ground.
fn cm_atmosphere_transmittance(air: CmAtmosphere, altitude: f32, cos_zenith: f32, steps: i32) -> vec3f {
    if (cm_atmosphere_ray_hits_ground(air, altitude, cos_zenith)) { return vec3f(0.0); }
    return exp(-cm_atmosphere_optical_depth(air, altitude, cos_zenith, cm_atmosphere_distance_to_top(air, altitude, cos_zenith), steps));
}

// The texture coordinates of (altitude, cos_zenith) in a transmittance LUT of `size` texels.
fn cm_atmosphere_transmittance_lut_uv(air: CmAtmosphere, altitude: f32, cos_zenith: f32, size: vec2f) -> vec2f {
    let R: f32 = air.bottom_radius;
    let top: f32 = air.top_radius;
    let r: f32 = R + clamp(altitude, 0.0, top - R);
    let H: f32 = sqrt((top - R) * (top + R));
    let rho: f32 = sqrt(max((r - R) * (r + R), 0.0));
    let d: f32 = cm_atmosphere_distance_to_top(air, r - R, cos_zenith);
    let d_min: f32 = top - r;
    let d_max: f32 = rho + H;
    let x_mu: f32 = select(0.0, clamp((d - d_min) / (d_max - d_min), 0.0, 1.0), d_max > d_min);
    let x_r: f32 = rho / H;
    return vec2f(0.5 / size.x + x_mu * (1.0 - 1.0 / size.x), 0.5 / size.y + x_r * (1.0 - 1.0 / size.y));
}

// The inverse: (altitude, cos_zenith) of texture coordinate uv (a LUT generator's texel).
fn cm_atmosphere_transmittance_lut_altitude_mu(air: CmAtmosphere, uv: vec2f, size: vec2f) -> vec2f {
    let R: f32 = air.bottom_radius;
    let top: f32 = air.top_radius;
    let x_mu: f32 = cm_saturate((uv.x - 0.5 / size.x) / (1.0 - 1.0 / size.x));
    let x_r: f32 = cm_saturate((uv.y - 0.5 / size.y) / (1.0 - 1.0 / size.y));
    let H: f32 = sqrt((top - R) * (top + R));
    let rho: f32 = H * x_r;
    let r: f32 = sqrt(rho * rho + R * R);
    let d_min: f32 = top - r;
    let d_max: f32 = rho + H;
    let d: f32 = d_min + x_mu * (d_max - d_min);
    let mu: f32 = select(1.0, clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0), d > 0.0);
    return vec2f(r - R, mu);
}

// sigma_s (1/m per channel): Rayleigh plus Mie scattering at an altitude (ozone only absorbs).
fn cm_atmosphere_scattering_coefficient(air: CmAtmosphere, altitude: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) + vec3f(air.mie_scattering * exp(-h / air.mie_scale_height));
}

// Scattering times phase (1/(m sr)): Rayleigh's phase for the molecules, Cornette-Shanks for
// the aerosols; cos_theta between the sun's and the view ray's directions (both outward).
fn cm_atmosphere_scattering(air: CmAtmosphere, altitude: f32, cos_theta: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    return air.rayleigh_scattering * (exp(-h / air.rayleigh_scale_height) * cm_phase_rayleigh(cos_theta)) + vec3f(air.mie_scattering * exp(-h / air.mie_scale_height) * cm_phase_cornette_shanks(cos_theta, air.mie_g));
}

// The sun's illuminance on a plane facing it: sun_illuminance (above the air) x transmittance.
fn cm_atmosphere_sun_illuminance(air: CmAtmosphere, altitude: f32, cos_sun_zenith: f32, sun_illuminance: vec3f) -> vec3f {
    return sun_illuminance * cm_atmosphere_transmittance(air, altitude, cos_sun_zenith, 64);
}

// Hillaire 2020's Psi_ms (see atmosphere_multiple_scattering in atmosphere.hpp): every order of
// scattering from the second on, per unit sun illuminance and scattering coefficient, from
// `directions` rays (spherical Fibonacci) of `steps` steps, sun transmittance in sun_steps steps;
// the second order turned towards the point by Rayleigh's phase (molecules), isotropically
// (aerosols).
fn cm_atmosphere_multiple_scattering(air: CmAtmosphere, altitude: f32, cos_sun_zenith: f32, directions: i32, steps: i32, sun_steps: i32) -> vec3f {
    let n_dir: i32 = max(directions, 1);
    let n: i32 = max(steps, 1);
    let h: f32 = clamp(altitude, 0.0, air.top_radius - air.bottom_radius);
    let r: f32 = air.bottom_radius + h;
    let mu_s: f32 = clamp(cos_sun_zenith, -1.0, 1.0);
    let sun: vec3f = vec3f(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    let golden_angle: f32 = CM_PI * (3.0 - sqrt(5.0));
    var L2: vec3f = vec3f(0.0);
    var f: vec3f = vec3f(0.0);
    for (var k: i32 = 0; k < n_dir; k++) {
        let mu: f32 = 1.0 - (2.0 * f32(k) + 1.0) / f32(n_dir);
        let phi: f32 = golden_angle * f32(k);
        let sin_zenith: f32 = sqrt(max(1.0 - mu * mu, 0.0));
        let dir: vec3f = vec3f(sin_zenith * cos(phi), mu, sin_zenith * sin(phi));
        let ground: bool = cm_atmosphere_ray_hits_ground(air, h, mu);
        var len: f32;
        if (ground) {
            len = cm_ray_sphere_intersect_altitude(h, mu, air.bottom_radius, 0.0).x;
        } else {
            len = cm_atmosphere_distance_to_top(air, h, mu);
        }
        let ds: f32 = len / f32(n);
        let nu: f32 = dot(dir, sun);
        var throughput: vec3f = vec3f(1.0);
        var L: vec3f = vec3f(0.0);
        var F: vec3f = vec3f(0.0);
        for (var i: i32 = 0; i < n; i++) {
            let t: f32 = (f32(i) + 0.5) * ds;
            let hy: f32 = cm_altitude_along_ray(h, mu, air.bottom_radius, t);
            let mu_sy: f32 = clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), -1.0, 1.0);
            let sigma_t: vec3f = cm_atmosphere_extinction(air, hy);
            let sigma_s: vec3f = cm_atmosphere_scattering_coefficient(air, hy);
            let step_t: vec3f = cm_beer_lambert_v3(sigma_t * ds);
            let integral: vec3f = cm_one_minus_exp_neg_over_x_v3(sigma_t * ds) * ds;
            let sun_t: vec3f = cm_atmosphere_transmittance(air, hy, mu_sy, sun_steps);
            // The second order's last turn: Rayleigh's phase for the molecules, isotropic aerosols.
            let h0: f32 = max(hy, 0.0);
            let turn: vec3f = air.rayleigh_scattering * (exp(-h0 / air.rayleigh_scale_height) * cm_phase_rayleigh(nu)) + vec3f(air.mie_scattering * exp(-h0 / air.mie_scale_height) * CM_INV_FOUR_PI);
            L += throughput * turn * sun_t * integral;
            F += throughput * sigma_s * integral;
            throughput *= step_t;
        }
        if (ground) {
            let mu_sg: f32 = clamp((r * mu_s + len * nu) / air.bottom_radius, -1.0, 1.0);
            L += throughput * cm_atmosphere_transmittance(air, 0.0, mu_sg, sun_steps) * (max(mu_sg, 0.0) * air.ground_albedo * CM_INV_PI);
        }
        L2 += L;
        f += F;
    }
    L2 /= vec3f(f32(n_dir));
    f /= vec3f(f32(n_dir));
    return L2 / (vec3f(1.0) - min(f, vec3f(0.999)));
}

// What the multiple-scattering field scatters into a ray per unit length (see
// atmosphere_multiple_scattering_source): psi and its vertical second moment from the LUTs
// (vertical_moment = psi / 3 for an isotropic field); Rayleigh's phase over the field for the
// molecules, isotropic for the aerosols.
fn cm_atmosphere_multiple_scattering_source(air: CmAtmosphere, altitude: f32, psi: vec3f, vertical_moment: vec3f, cos_view_zenith: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    let mu2: f32 = clamp(cos_view_zenith * cos_view_zenith, 0.0, 1.0);
    let horizontal: vec3f = (psi - vertical_moment) * 0.5;
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) * (0.75 * (psi + horizontal * (1.0 - mu2) + vertical_moment * mu2)) + psi * (air.mie_scattering * exp(-h / air.mie_scale_height));
}

// The multiple-scattering LUT's (u, v) of (altitude, cos_sun_zenith), and the inverse: u by
// sign(mu_s) sqrt(|mu_s|), which crowds the columns around Earth's shadow (atmosphere.hpp).
fn cm_atmosphere_multiple_scattering_lut_uv(air: CmAtmosphere, altitude: f32, cos_sun_zenith: f32, size: vec2f) -> vec2f {
    let c: f32 = clamp(cos_sun_zenith, -1.0, 1.0);
    let root: f32 = sqrt(abs(c));
    let x_mu: f32 = cm_saturate(0.5 + 0.5 * (select(root, -root, c < 0.0)));
    let x_h: f32 = cm_saturate(altitude / (air.top_radius - air.bottom_radius));
    return vec2f(0.5 / size.x + x_mu * (1.0 - 1.0 / size.x), 0.5 / size.y + x_h * (1.0 - 1.0 / size.y));
}
fn cm_atmosphere_multiple_scattering_lut_altitude_mu(air: CmAtmosphere, uv: vec2f, size: vec2f) -> vec2f {
    let x_mu: f32 = cm_saturate((uv.x - 0.5 / size.x) / (1.0 - 1.0 / size.x));
    let x_h: f32 = cm_saturate((uv.y - 0.5 / size.y) / (1.0 - 1.0 / size.y));
    let m: f32 = 2.0 * x_mu - 1.0;
    return vec2f(x_h * (air.top_radius - air.bottom_radius), m * abs(m));
}

// ---------------------------------------------------------------------------------------
// The sky and the aerial perspective (atmosphere_inscatter, atmosphere_sky_radiance): the
// march of atmosphere.hpp step for step, reading the multiple-scattering table through a
// function you define, so that the texels come from your own textures:
//   vec3 my_table(int part, int x, int y);   // declared before the include, defined anywhere
//   #define CM_ATMOSPHERE_TABLE my_table
//   #include "cloudmath/glsl/atmosphere.glsl"
//   vec3 my_table(int part, int x, int y) {  // e.g. the parts stacked in one RGB32F texture
//       return part == CM_ATMOSPHERE_TABLE_GROUND ? texelFetch(u_ground, ivec2(x, 0), 0).rgb
//                                                 : texelFetch(u_table, ivec2(x, y + part * 32), 0).rgb;
//   }
// It returns texel (x, y) of `part` (row y = 0 first, as atmosphere_sky_luts stores them):
// CM_ATMOSPHERE_TABLE_PSI the LUT's Psi_ms, _VERTICAL its vertical moments, _ALONG its
// sun-azimuth moments, _AEROSOL + j (j = 0 .. CM_ATMOSPHERE_AEROSOL_NODES - 1) the aerosol
// field's node j, and _GROUND the ground irradiance (x its column, y = 0). The library
// interpolates them itself, exactly as the C++ (detail::lut_bilinear, clamp to edge), so a
// shader and the CPU give the same sky to float rounding, whatever the texture filtering.
const CM_ATMOSPHERE_TABLE_PSI = 0;
const CM_ATMOSPHERE_TABLE_VERTICAL = 1;
const CM_ATMOSPHERE_TABLE_ALONG = 2;
const CM_ATMOSPHERE_TABLE_GROUND = 3;
const CM_ATMOSPHERE_TABLE_AEROSOL = 4;
const CM_ATMOSPHERE_AEROSOL_NODES = 17;

// atmosphere_multiple_scattering_table (atmosphere.hpp): which parts of the table a shader has
// and their sizes. parts 0: no multiple scattering (the single-scattering sky); 1: Psi_ms alone
// (Hillaire's LUT, an isotropic field); 2: with the vertical moments; 3: with the sun-azimuth
// moments and the aerosol field as well (atmosphere_make_sky_luts). width and height (>= 2)
// are the LUT's; ground_width the ground irradiance's texels (0: the ground below the horizon
// reflects the sun alone).
struct CmAtmosphereTable {
    width: i32,
    height: i32,
    parts: i32,
    ground_width: i32,
}

// What a view ray gathers (atmosphere_segment): the transmittance to the segment's end and the
// light scattered into it per unit sun illuminance (1/sr).
struct CmAtmosphereSegment {
    transmittance: vec3f,
    radiance: vec3f,
}

// floor(x) as an int clamped to [lo, hi]; NaN gives lo (core.hpp's floor_to_int).
fn cmi_floor_to_int(x: f32, lo: i32, hi: i32) -> i32 {
    if (!(x > f32(lo))) { return lo; }
    if (x >= f32(hi)) { return hi; }
    return i32(floor(x));
}

// The length of a ray in the air: to the ground where it meets it, else to the top.
fn cmi_atmosphere_ray_length(air: CmAtmosphere, altitude: f32, cos_zenith: f32) -> f32 {
    if (cm_atmosphere_ray_hits_ground(air, altitude, cos_zenith)) { return cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, 0.0).x; }
    return cm_atmosphere_distance_to_top(air, altitude, cos_zenith);
}

// The Lambertian ground's radiance per unit sun illuminance under a sun of zenith cosine mu_s.
fn cmi_atmosphere_lit_ground(air: CmAtmosphere, mu_s: f32, sun_steps: i32) -> vec3f {
    return cm_atmosphere_transmittance(air, 0.0, mu_s, sun_steps) * (max(mu_s, 0.0) * air.ground_albedo * CM_INV_PI);
}

// The square of the cosine of the azimuth between directions of zenith cosines mu and mu_s
// whose dot product is nu; 1/2 (no azimuth) when either is vertical.
fn cmi_atmosphere_cos2_azimuth(mu: f32, mu_s: f32, nu: f32) -> f32 {
    let den: f32 = (1.0 - mu * mu) * (1.0 - mu_s * mu_s);
    if (!(den > 1e-8)) { return 0.5; }
    let c: f32 = nu - mu * mu_s;
    return clamp(c * c / den, 0.0, 1.0);
}

// EV100 of a camera (f-number, shutter seconds, ISO), of an average luminance, and the exposure.
fn cm_ev100_from_camera(aperture: f32, shutter_time: f32, iso: f32) -> f32 {
    return log2(aperture * aperture / shutter_time * 100.0 / iso);
}
fn cm_ev100_from_luminance(average_luminance: f32) -> f32 { return log2(average_luminance * 100.0 / 12.5); }
fn cm_exposure_from_ev100(ev100: f32) -> f32 { return 1.0 / (1.2 * exp2(ev100)); }
// cloudmath/glsl/cloudmath.glsl: every GLSL twin. Define configuration macros
// (CM_MS_OCTAVES, CM_MS_PHASE, CM_DIFFUSION_PHASE, CM_CONE_EXTINCTION, CM_CONE_SAMPLES) before including it.
