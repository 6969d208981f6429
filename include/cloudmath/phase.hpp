// cloudmath/phase.hpp: normalised phase functions and Henyey-Greenstein sampling.
//
// Use:      #include <cloudmath/phase.hpp>
//           float p = cloudmath::phase_hg(dot(view_dir, light_dir), 0.8f);
// Convention: mu is the cosine of the scattering angle, mu = dot(view_dir, light_dir),
//           view_dir pointing from the camera into the scene and light_dir from the sample
//           toward the light: mu = +1 is looking straight into the sun (forward scattering).
//           pbrt and Mitsuba pass dot(wo, wi) with wo pointing back to the camera, which is
//           -mu: their HG has "+ 2 g cos" where ours has "- 2 g mu".
// Units:    every phase function integrates to 1 over the sphere (units 1/sr).
// Domain:   mu is clamped to [-1, 1] (dot products of unit vectors overshoot by an ulp);
//           g is clamped to [-phase_g_max, phase_g_max] = [-0.9999, 0.9999] so that |g| >= 1
//           (a delta function) gives a finite, normalised, very sharp lobe instead of
//           Inf or NaN. Peak value at the clamp: HG(1, 0.9999) = 1.59e7 /sr.
// Accuracy: HG-type denominators 1 + g^2 - 2 g mu are written as (1-g)^2 + 2g(1-mu) for
//           g >= 0 and (1+g)^2 - 2g(1+mu) for g < 0: sums of non-negative terms, so the
//           forward (resp. backward) peak keeps full float precision. The textbook form
//           loses 0.03% at g = 0.99, 0.2% at 0.995 and 10% at 0.999 in float.
// GLSL twin: cloudmath/glsl/phase.glsl.
#ifndef CLOUDMATH_PHASE_HPP
#define CLOUDMATH_PHASE_HPP

#include <cmath>

#include "core.hpp"

namespace cloudmath {

// Largest |g| the phase functions accept; larger values are clamped to it.
template <class T> inline constexpr T phase_g_max = T(0.9999);

namespace detail {

template <class T>
constexpr T clamp_g(T g) noexcept {
    return clamp(g, -phase_g_max<T>, phase_g_max<T>);
}

template <class T>
constexpr T clamp_mu(T mu) noexcept {
    return clamp(mu, T(-1), T(1));
}

// 1 + g^2 - 2 g mu without cancellation at the peak on the side of g (see header comment).
// Expects clamped g and mu; the result is >= (1 - |g|)^2 > 0.
template <class T>
constexpr T hg_denominator_base(T mu, T g) noexcept {
    return g >= T(0) ? (T(1) - g) * (T(1) - g) + T(2) * g * (T(1) - mu)
                     : (T(1) + g) * (T(1) + g) - T(2) * g * (T(1) + mu);
}

// (1 + g^2 - 2 g mu)^(-3/2) as 1 / (d sqrt d): cheaper and more accurate than pow(d, 1.5).
template <class T>
inline T hg_denominator_pow(T mu, T g) noexcept {
    const T d = hg_denominator_base(mu, g);
    return T(1) / (d * std::sqrt(d));
}

}  // namespace detail

// ---------------------------------------------------------------------------------------
// Isotropic: 1 / (4 pi).
template <class T>
[[nodiscard]] constexpr T phase_isotropic() noexcept {
    return inv_four_pi_v<T>;
}

// Rayleigh: 3 (1 + mu^2) / (16 pi). Mean cosine 0.
template <class T>
[[nodiscard]] constexpr T phase_rayleigh(T mu) noexcept {
    mu = detail::clamp_mu(mu);
    return T(3) / (T(16) * pi_v<T>) * (T(1) + mu * mu);
}

// Henyey-Greenstein (Henyey & Greenstein, ApJ 93:70, 1941):
//   p = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)), mean cosine g.
// Numerator as (1 - g)(1 + g): exact near |g| = 1 where 1 - g*g rounds.
// Relative error in float: a few ulp for all mu and |g| <= 0.9999 (tested).
template <class T>
[[nodiscard]] inline T phase_hg(T mu, T g) noexcept {
    mu = detail::clamp_mu(mu);
    g = detail::clamp_g(g);
    return inv_four_pi_v<T> * ((T(1) - g) * (T(1) + g)) * detail::hg_denominator_pow(mu, g);
}

// Dual-lobe HG (Hillaire 2016, "Physically based sky, atmosphere and cloud rendering in
// Frostbite"): (1 - w) HG(mu, g0) + w HG(mu, g1). w is clamped to [0, 1] so the mix stays
// a normalised, non-negative phase function. Frostbite example: g0 = 0.8, g1 = -0.5, w = 0.5.
template <class T>
[[nodiscard]] inline T phase_hg_dual(T mu, T g0, T g1, T w) noexcept {
    w = saturate(w);
    return (T(1) - w) * phase_hg(mu, g0) + w * phase_hg(mu, g1);
}

// Cornette-Shanks (Cornette & Shanks, Appl. Opt. 31:3152, 1992), normalised form:
//   p = 3/(8 pi) (1 - g^2)/(2 + g^2) (1 + mu^2) / (1 + g^2 - 2 g mu)^(3/2).
// Mean cosine 3 g (4 + g^2) / (5 (2 + g^2)). The variant with mu^2 inside the denominator,
// seen in the literature, is not normalised (integral 1.246 at g = 0.5).
template <class T>
[[nodiscard]] inline T phase_cornette_shanks(T mu, T g) noexcept {
    mu = detail::clamp_mu(mu);
    g = detail::clamp_g(g);
    const T k = T(3) / (T(8) * pi_v<T>) * ((T(1) - g) * (T(1) + g)) / (T(2) + g * g);
    return k * (T(1) + mu * mu) * detail::hg_denominator_pow(mu, g);
}

// Draine (Draine, ApJ 598:1017, 2003):
//   p = 1/(4 pi) (1 - g^2)(1 + alpha mu^2) / [(1 + alpha (1 + 2 g^2)/3) (1 + g^2 - 2 g mu)^(3/2)].
// alpha = 0 is HG, alpha = 1 is Cornette-Shanks. Mean cosine
//   g (1 + alpha (3 + 2 g^2)/5) / (1 + alpha (1 + 2 g^2)/3).
// Domain alpha >= 0 (the Mie fit uses up to 250); negative alpha is clamped to 0.
template <class T>
[[nodiscard]] inline T phase_draine(T mu, T g, T alpha) noexcept {
    mu = detail::clamp_mu(mu);
    g = detail::clamp_g(g);
    alpha = detail::max(alpha, T(0));
    const T norm = T(1) + alpha * (T(1) + T(2) * g * g) / T(3);
    return inv_four_pi_v<T> * ((T(1) - g) * (T(1) + g)) * (T(1) + alpha * mu * mu) / norm *
           detail::hg_denominator_pow(mu, g);
}

// ---------------------------------------------------------------------------------------
// Jendersie & d'Eon 2023, "An Approximate Mie Scattering Function for Fog and Cloud
// Rendering" (SIGGRAPH 2023 Talks, doi 10.1145/3587421.3595409): a fit of the Mie phase
// function of water droplets of diameter d (micrometres) as
//   p = (1 - w_D) HG(mu, g_HG) + w_D Draine(mu, g_D, alpha).
// The fit covers 0 < d <= 50 um in four ranges; d is clamped to [0, 50]. The parameters
// depend on d only: compute them once per medium with mie_approx_params and evaluate with
// the phase_mie_approx(mu, params) overload.
template <class T>
struct mie_approx_parameters {
    T g_hg;     // HG lobe eccentricity
    T g_draine; // Draine lobe eccentricity
    T alpha;    // Draine alpha
    T w_draine; // weight of the Draine lobe
};

// Parameters of the Jendersie & d'Eon fit for droplet diameter d in micrometres.
// Reference values (REFERENCES.md): d = 10 -> g_HG 0.98818, g_D 0.55567, alpha 21.996,
// w_D 0.48196. For d <= 0.1 the term is 312.983 * d^4.3 (some ports write
// pow(312.983 d, 4.3), which is wrong).
template <class T>
[[nodiscard]] inline mie_approx_parameters<T> mie_approx_params(T d) noexcept {
    using std::cos;
    using std::exp;
    using std::log;
    using std::pow;
    using std::sin;
    using std::tan;
    d = detail::clamp(d, T(0), T(50));
    mie_approx_parameters<T> p{};
    if (d <= T(0.1)) {
        p.g_hg = T(13.8) * d * d;
        p.g_draine = T(1.1456) * d * sin(T(9.29044) * d);
        p.alpha = T(250);
        p.w_draine = T(0.252977) - T(312.983) * pow(d, T(4.3));
    } else if (d < T(1.5)) {
        const T L = log(d);
        p.g_hg = T(0.862) - T(0.143) * L * L;
        const T inner = (L - T(0.238604)) * (L + T(1.00667)) / (T(0.507522) - T(0.15677) * L);
        p.g_draine =
            T(0.379685) * cos(T(1.19692) * cos(inner) + T(1.37932) * L + T(0.0625835)) +
            T(0.344213);
        p.alpha = T(250);
        p.w_draine = T(0.146209) * cos(T(3.38707) * L + T(2.11193)) + T(0.316072) +
                     T(0.0778917) * L;
    } else if (d < T(5)) {
        const T L = log(d);
        // tan(L) has a pole at d = e^(pi/2) = 4.81; the fraction tends to 0 from both
        // sides there and its denominator stays >= 0.70 in magnitude, so g_D is continuous.
        p.g_hg = T(0.0604931) * log(L) + T(0.940256);
        p.g_draine = T(0.500411) - T(0.081287) / (T(-2) * L + tan(L) + T(1.27551));
        p.alpha = T(7.30354) * L + T(6.31675);
        p.w_draine = T(0.026914) * (L - cos(T(5.68947) * (log(L) - T(0.0292149)))) + T(0.3764);
    } else {
        p.g_hg = exp(T(-0.0990567) / (d - T(1.67154)));
        p.g_draine = exp(T(-2.20679) / (d + T(3.91029)) - T(0.428934));
        p.alpha = exp(T(3.62489) - T(8.29288) / (d + T(5.52825)));
        p.w_draine = exp(T(-0.599085) / (d - T(0.641583)) - T(0.665888));
    }
    return p;
}

template <class T>
[[nodiscard]] inline T phase_mie_approx(T mu, const mie_approx_parameters<T>& p) noexcept {
    return (T(1) - p.w_draine) * phase_hg(mu, p.g_hg) +
           p.w_draine * phase_draine(mu, p.g_draine, p.alpha);
}

// Convenience form: evaluates the parameters for every call (about 4 transcendental
// functions more than the overload above).
template <class T>
[[nodiscard]] inline T phase_mie_approx(T mu, T droplet_diameter_um) noexcept {
    return phase_mie_approx(mu, mie_approx_params(droplet_diameter_um));
}

// ---------------------------------------------------------------------------------------
// Schlick's phase function (Blasi, Le Saec & Schlick, "A rendering algorithm for discrete
// volume density objects", Eurographics 1993): p = (1 - k^2) / (4 pi (1 - k mu)^2).
// Exactly normalised for every |k| < 1; no square root, so it is the cheap stand-in for HG.
// k is clamped like g. The denominator is written (1 - k) + k (1 - mu) (k >= 0) or
// (1 + k) - k (1 + mu) (k < 0) for the same reason as HG's: within 3 ulp of exact in IEEE
// builds. -ffast-math may re-associate it into 1 - k mu, which leaves about 1e-4 relative
// error at the peak for |k| near 0.9999 (measured: 839 ulp in float).
template <class T>
[[nodiscard]] inline T phase_schlick(T mu, T k) noexcept {
    mu = detail::clamp_mu(mu);
    k = detail::clamp_g(k);
    const T d = k >= T(0) ? (T(1) - k) + k * (T(1) - mu) : (T(1) + k) - k * (T(1) + mu);
    return inv_four_pi_v<T> * ((T(1) - k) * (T(1) + k)) / (d * d);
}

// The k that makes Schlick's function approximate HG(g): k = 1.55 g - 0.55 g^3
// (Blasi et al. 1993). Mean cosine of Schlick(k(g)) is not exactly g.
template <class T>
[[nodiscard]] constexpr T schlick_k_from_hg_g(T g) noexcept {
    return T(1.55) * g - T(0.55) * g * g * g;
}

// Fast approximation of HG: phase_schlick(mu, schlick_k_from_hg_g(g)).
// Normalised exactly. Maximum relative error against phase_hg(mu, g) over mu in [-1, 1]
// (measured by tests/test_phase.cpp, which asserts these bounds):
//   |g| <= 0.3: 9%,  |g| <= 0.5: 23%,  |g| <= 0.8: 66%,  |g| <= 0.9: 90%;
//   towards the clamp |g| = 0.9999 it grows to a factor 73 (the opposite lobe), measured by
//   bash scripts/speed-vs-error.sh.
// The error is largest in the forward peak and the back lobe; it is a shape
// approximation, not a drop-in replacement where the forward peak matters.
template <class T>
[[nodiscard]] inline T phase_hg_schlick(T mu, T g) noexcept {
    return phase_schlick(mu, schlick_k_from_hg_g(detail::clamp_g(g)));
}

// ---------------------------------------------------------------------------------------
// sample_phase_hg(g, u): mu distributed as HG(mu, g) for u uniform in [0, 1).
// Inverse CDF of HG in mu (derived here, valid for every clamped g including g = 0, where
// it reduces to mu = 2u - 1 (to rounding), so no isotropic special case is needed as in pbrt's
// |g| < 1e-3 branch). For g >= 0, with t = (1 - g) + 2 g u:
//   1 - mu = (1 - g)^2 (1 - u) (1 + g + t) / t^2,
// a product of non-negative terms, accurate in the forward peak. For g < 0 the mirror
// identity HG(mu, g) = HG(-mu, -g) is used with u -> 1 - u.
// Domain: every finite g and u. g is clamped to [-phase_g_max, phase_g_max], u to [0, 1];
// u = 0 gives mu = -1 and u = 1 gives mu = 1 exactly. NaN u gives NaN (IEEE builds).
// Monotonic: mu is non-decreasing in u for every g, bit for bit with IEEE arithmetic (with
// or without FMA contraction), so stratified and low-discrepancy u stay stratified. The
// formula is written so that every rounded step moves the same way as u grows: with
// w = (1 - g) / t (non-increasing in u),
//   1 - mu = (1 - u) * (w * (w (1 + g) + (1 - g))),
// a product of non-negative factors that all shrink as u grows. The form above,
// (1 - u) (1 + g + t) / t^2, multiplied a growing factor into a shrinking one, and its
// roundings went backwards by an ulp (3884 times over 2^24 + 1 evenly spaced u at g = 0.3 in
// float). Measured by tests/test_phase.cpp on dense sweeps of u.
// The pdf of the sampled mu, per steradian, is phase_hg(mu, g).
template <class T>
[[nodiscard]] inline T sample_phase_hg(T g, T u) noexcept {
    g = detail::clamp_g(g);
    u = saturate(u);
    const T a = detail::abs(g);
    // Sample the mirrored lobe for g < 0 with v = 1 - u; 1 - v is then u itself, exact.
    const T v = g >= T(0) ? u : T(1) - u;
    const T one_minus_v = g >= T(0) ? T(1) - u : u;
    const T t = (T(1) - a) + T(2) * a * v;  // >= 1 - a > 0, non-decreasing in v
    const T w = (T(1) - a) / t;              // in (0, 1], non-increasing in v; 1 at v = 0
    const T one_minus_m = one_minus_v * (w * (w * (T(1) + a) + (T(1) - a)));
    // v = 0 is the far end exactly (the rounded 1 - mu there is 2 only to an ulp).
    const T m = v <= T(0) ? T(-1) : detail::clamp(T(1) - one_minus_m, T(-1), T(1));
    return g >= T(0) ? m : -m;
}

}  // namespace cloudmath

#endif  // CLOUDMATH_PHASE_HPP
