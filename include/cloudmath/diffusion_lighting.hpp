// cloudmath/diffusion_lighting.hpp: multiple scattering from diffusion along the sun's chord,
// corrected by a small table fitted to a path tracer: the lighting model to use where the
// octaves' error (70% rms and more against the path tracer) is too much.
//
// Use:      #include <cloudmath/diffusion_lighting.hpp>
//           // per view-ray sample: the optical depth toward the sun (as for the octaves),
//           // the optical depth behind the sample on the same line (away from the sun, to
//           // where the cloud ends: a second short march, or a sun-aligned shadow map that
//           // stores front depth and total optical depth) and the optical depth from the
//           // camera (the view march already has it: -log of its transmittance)
//           float M = cloudmath::diffusion_scattering(tau_sun, tau_behind, tau_view, mu, g,
//                                                     albedo, cloudmath::diffusion_models::fitted);
//           S = sigma_s * sun_irradiance * M;   // source term of integration.hpp
// Why:      the octaves see one number per sample, tau_sun, and no choice of their a, b, c
//           brings them below 50% rms (docs/lighting_error.md): the light that diffuses
//           through a cloud depends on where the sample sits in it. This model sees the chord
//           through the sample along the sun (tau_sun in front, tau_behind after it) and the
//           depth below the surface the camera looks through (tau_view).
// Model:    similarity scaling (van de Hulst 1980; Bouthors et al., "Interactive multiple
//           anisotropic scattering in clouds", I3D 2008): diffuse light in a medium of
//           asymmetry g behaves like isotropic scattering at transport optical depth
//           (1 - g) tau, (1 - albedo g) tau with absorption. With s = 1 - albedo g,
//           x = s tau_sun, y = s tau_behind, L = x + y and the extrapolation length
//           z = 0.7104 (Milne's problem; Ishimaru, "Wave propagation and scattering in
//           random media", 1978, ch. 9), the conservative diffusion equation on the chord,
//           -U''/3 = e^(-x) with U(-z) = U(L + z) = 0, has the exact solution
//             U = 3 [ e^z - e^(-x) - (e^z - e^(-(L + z))) (x + z) / (L + 2 z) ]
//             F = (e^z - e^(-(L + z))) / (L + 2 z) - e^(-x)     (net flux along the sun)
//           (with absorption, diffusion_chord_fluence's sinh/cosh form). The diffusion
//           radiance (U + 3 F.w) / (4 pi), scattered toward the camera by a phase function
//           of mean cosine g, gives D = a' (U + 3 g F mu)^+ / (4 pi), a' = albedo (1 - g) / s
//           the scaled medium's albedo. Then
//             M = max(0,  p(mu, 1) e^(-tau_sun)                            single, exact
//                       + sum_{a, c} w_ac p(mu, c) (e^(-a x) - e^(-tau_sun))^+  forward peak
//                       + D max(C(u), 0) )                                     diffusion
//           where p(mu, c) is the phase function with its eccentricity scaled by c
//           (a in {1/2, 1, 2}, c in {1/2, 4/5}): light scattered into the forward peak that
//           still travels with the sun, as in the octaves; and C is a multilinear table over
//           u = (x / (1 + x), y / (1 + y), (1 + mu) / 2, d / (d + t)) with
//           d = s tau_view + z and t = (x + z)(y + z) / (L + 2 z): the correction of the
//           one-dimensional diffusion for the cloud's other surfaces, largest near the
//           surface the camera looks through (d small against the chord's diffusion
//           length t), where light escapes through a boundary the chord cannot see.
//           The weights w and the table C are fitted by least squares to our Monte Carlo
//           path tracer (tools/reference, cloudmath_lighting_error fit-diffusion); each
//           model states its measured error (diffusion_model below). The fitted weights may
//           be negative (the fit is unconstrained); the two max(0, ...) keep every result a
//           radiance, and the errors are measured with them.
// Models:   diffusion_models::fitted (fitted to homogeneous spheres and slabs: 33% rms on
//           the reference, 34-51% on the held-out rays; the model for homogeneous media),
//           diffusion_models::clouds (the same model fitted to whole-cloud images: the example
//           renderer against its path tracer on 10 selection images, cloudmath_volume_truth
//           fit-clouds; on the images it never saw 15-21% excess rms at a high sun on the
//           classic field, 22-25% on the detailed one, against 18-29% and 32-33% with
//           `fitted`; worse on homogeneous media, 59% on the reference: use it for cloud
//           fields, docs/lighting_research.md), diffusion_models::physical (no fit: plain
//           diffusion). diffusion_models::all lists the homogeneous-media models.
// Inputs:   optical depths >= 0 (negative values count as 0, values above 1e6 as 1e6: past
//           that nothing changes in float); mu in [-1, 1] (clamped); g clamped to
//           [-0.999, 0.999] like phase_hg; albedo clamped to [0, 1]. tau_behind = 0 and tau_view = 0 are valid (the
//           back and the front surface of a cloud). Every result is finite and >= 0.
// Returns:  the sun term M (1/sr), like multiple_scattering(): radiance = integral of
//           T_view sigma_s F0 M ds.
// Cost:     3 exponentials and 1 division per sample in a conservative medium (3 octaves:
//           3 exponentials), 5 more with absorption (albedo < 1), 3 phase evaluations that
//           depend on mu only (once per ray in a ray marcher), a 135-entry table; plus what the
//           renderer spends on tau_behind.
// GLSL twin: cloudmath/glsl/diffusion_lighting.glsl (same names with cm_; models as
//           CM_DIFFUSION_MODEL_<NAME>).
#ifndef CLOUDMATH_DIFFUSION_LIGHTING_HPP
#define CLOUDMATH_DIFFUSION_LIGHTING_HPP

#include <cmath>

#include "core.hpp"
#include "phase.hpp"

namespace cloudmath {

// Table and peak-term layout, shared with the GLSL twin and the fitting tool.
namespace diffusion_layout {
inline constexpr int size_x = 3, size_y = 3, size_mu = 5, size_d = 3;
inline constexpr int table_size = size_x * size_y * size_mu * size_d;  // 135
// Forward-peak terms: attenuation factors a (of the transport depth x) and eccentricity
// factors c; weight w_ac is peak[ia * peak_c_count + ic].
inline constexpr int peak_a_count = 3, peak_c_count = 2;
inline constexpr int peak_size = peak_a_count * peak_c_count;  // 6
inline constexpr double peak_a[peak_a_count] = {0.5, 1.0, 2.0};
inline constexpr double peak_c[peak_c_count] = {0.5, 0.8};
// The extrapolation length z (transport mean free paths): Milne's 0.7104.
inline constexpr double extrapolation = 0.7104;
// Index of table entry (ix, iy, imu, id); d varies fastest.
constexpr int table_index(int ix, int iy, int imu, int id) noexcept {
    return ((ix * size_y + iy) * size_mu + imu) * size_d + id;
}
}  // namespace diffusion_layout

// A fitted model: its table and peak weights, and what it was fitted to and measured with.
// Errors are those of multiple_scattering_preset: rms and max over reference rays of
// (L_model - L_MC) / (mean L_MC of the ray's image), the sun term integrated exactly along
// each ray (docs/lighting_error.md, docs/lighting_research.md).
struct diffusion_model {
    const char* name;
    float table[diffusion_layout::table_size];
    float peak[diffusion_layout::peak_size];
    float tau_min, tau_max;      // optical thickness range of the fit and of the errors
    float g_min, g_max;          // HG asymmetries of the fit's reference sets
    float rms_error, max_error;  // on docs/data/lighting_reference.csv (g = 0.85)
    float holdout_rms_error;     // worst rms over the held-out split (g = 0.75, 0.85, 0.9)
};

namespace detail {

template <class T>
inline T diffusion_depth(T tau) noexcept {
    return detail::clamp(tau, T(0), T(1e6));
}

// Piecewise-linear weights of coordinate u in [0, 1] over n >= 2 equally spaced nodes: the
// lower node and the weight of the upper one. The node is in [0, n - 2] for every u: a NaN u
// gives node 0 and a NaN weight (the lookup's result is NaN, as the contract says), never an
// index outside the table (a NaN converted to int read it 2^31 entries away).
template <class T>
inline void diffusion_hat(T u, int n, int& i0, T& w1) noexcept {
    const T p = detail::clamp(u, T(0), T(1)) * T(n - 1);
    i0 = detail::floor_to_int(p, 0, n - 2);
    w1 = p - T(i0);
}

}  // namespace detail

// The similarity relations for an absorbing medium (van de Hulst 1980): transport optical
// depth (1 - albedo g) tau, and the diffusion's absorption length 1 / kappa with
// kappa^2 = 3 (1 - albedo) / (1 - albedo g) per transport depth. kappa is clamped to 0.9
// (albedo below about 1 - 0.27 (1 - g)), where the particular solution's 1 / (1 - kappa^2)
// would resonate: clouds (albedo 0.99 and above) are far from it.
template <class T>
struct diffusion_medium {
    T s;      // 1 - albedo g, in [0.001, 2]
    T kappa;  // in [0, 0.9]
};
template <class T>
[[nodiscard]] inline diffusion_medium<T> diffusion_similarity(T g, T albedo) noexcept {
    const T gc = detail::clamp(g, T(-0.999), T(0.999));
    const T w = detail::clamp(albedo, T(0), T(1));
    const T s = detail::max(T(1) - w * gc, T(0.001));
    return {s, detail::min(std::sqrt(T(3) * (T(1) - w) / s), T(0.9))};
}

// The diffusion solution on a chord (header comment), with absorption: fluence U (>= 0;
// returned) and net flux F (in `flux`) at transport depth x of a chord of transport
// thickness L = x + y, for -U''/3 + (kappa^2 / 3) U = e^(-x), U(-z) = U(L + z) = 0:
//   U = 3 / (1 - kappa^2) [ e^(-(L + z)) R(x + z) + e^z R(L + z - x) - e^(-x) ]
//   F = 1 / (1 - kappa^2) [ kappa (e^z Q(L + z - x) - e^(-(L + z)) Q(x + z)) - e^(-x) ]
// with R(a) = sinh(kappa a) / sinh(kappa W), Q(a) = cosh(kappa a) / sinh(kappa W),
// W = L + 2 z, written with decaying exponentials only (no overflow for any L); for
// kappa W < 1e-4 their series to second order in kappa (at kappa = 0 the conservative
// solution, 3 [e^z - e^(-x) - (e^z - e^(-(L + z))) (x + z) / W]).
// e^(-x) is given (the caller has it).
template <class T>
[[nodiscard]] inline T diffusion_chord_fluence(T x, T y, T exp_neg_x, T kappa,
                                               T& flux) noexcept {
    const T z = T(diffusion_layout::extrapolation);
    const T ez = std::exp(z);
    const T L = x + y;
    const T W = L + T(2) * z;
    const T a1 = x + z, a2 = y + z;  // distances to the two extrapolated ends
    const T e_far = std::exp(-(L + z));
    const T k = detail::clamp(kappa, T(0), T(0.9));
    T R1, R2, kQ1, kQ2;
    if (k * W < T(1e-4)) {
        // Second-order series of sinh and cosh: the next term is (k W)^4 / 120 < 1e-18.
        const T k2 = k * k, W2 = W * W;
        R1 = a1 / W * (T(1) + k2 * (a1 * a1 - W2) / T(6));
        R2 = a2 / W * (T(1) + k2 * (a2 * a2 - W2) / T(6));
        kQ1 = (T(1) + k2 * (a1 * a1 / T(2) - W2 / T(6))) / W;
        kQ2 = (T(1) + k2 * (a2 * a2 / T(2) - W2 / T(6))) / W;
    } else {
        // sinh(k a) / sinh(k W) = e^(-k (W - a)) (1 - e^(-2 k a)) / (1 - e^(-2 k W)), W - a1 = a2;
        // 1 - e^(-u) by one_minus_exp_neg, exact where k a is tiny and W is not.
        const T e1 = std::exp(-k * a1), e2 = std::exp(-k * a2);
        const T inv_denominator = T(1) / one_minus_exp_neg(T(2) * k * W);
        R1 = e2 * one_minus_exp_neg(T(2) * k * a1) * inv_denominator;
        R2 = e1 * one_minus_exp_neg(T(2) * k * a2) * inv_denominator;
        kQ1 = k * e2 * (T(1) + e1 * e1) * inv_denominator;
        kQ2 = k * e1 * (T(1) + e2 * e2) * inv_denominator;
    }
    const T scale = T(1) / (T(1) - k * k);
    flux = scale * (ez * kQ2 - e_far * kQ1 - exp_neg_x);
    return detail::max(T(3) * scale * (e_far * R1 + ez * R2 - exp_neg_x), T(0));
}

// The four table coordinates of a sample, each in [0, 1] (header comment).
template <class T>
struct diffusion_coordinates {
    T u_sun, u_behind, u_mu, u_surface;
};
template <class T>
[[nodiscard]] inline diffusion_coordinates<T> diffusion_table_coordinates(
    T tau_sun, T tau_behind, T tau_view, T mu, T g, T albedo) noexcept {
    const T s = diffusion_similarity(g, albedo).s;
    const T x = s * detail::diffusion_depth(tau_sun);
    const T y = s * detail::diffusion_depth(tau_behind);
    const T z = T(diffusion_layout::extrapolation);
    const T t = (x + z) * (y + z) / (x + y + T(2) * z);
    const T d = s * detail::diffusion_depth(tau_view) + z;
    return {x / (T(1) + x), y / (T(1) + y), T(0.5) * detail::clamp(mu, T(-1), T(1)) + T(0.5),
            d / (d + t)};
}

namespace detail {

// Calls f(index, weight) for the 16 table entries around coordinates u with their
// multilinear weights (the table C at u is the sum of weight * table[index]).
template <class T, class F>
inline void diffusion_table_corners(const diffusion_coordinates<T>& u, F&& f) noexcept {
    namespace L = diffusion_layout;
    int ix, iy, im, id;
    T wx, wy, wm, wd;
    diffusion_hat(u.u_sun, L::size_x, ix, wx);
    diffusion_hat(u.u_behind, L::size_y, iy, wy);
    diffusion_hat(u.u_mu, L::size_mu, im, wm);
    diffusion_hat(u.u_surface, L::size_d, id, wd);
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c)
                for (int e = 0; e < 2; ++e)
                    f(L::table_index(ix + a, iy + b, im + c, id + e),
                      (a ? wx : T(1) - wx) * (b ? wy : T(1) - wy) * (c ? wm : T(1) - wm) *
                          (e ? wd : T(1) - wd));
}

// What the model combines with its fitted numbers at one sample (header comment): the
// clamped mu, e^(-tau_sun), the forward-peak beams (e^(-a x) - e^(-tau_sun))^+ for the
// a of diffusion_layout, the diffusion term D and the table coordinates. The fitting tool
// (tools/reference/lighting_diffusion) builds its features from the same terms.
template <class T>
struct diffusion_sample {
    T mu;
    T direct;
    T beams[diffusion_layout::peak_a_count];
    T diffuse;
    diffusion_coordinates<T> u;
};
template <class T>
inline diffusion_sample<T> diffusion_sample_terms(T tau_sun, T tau_behind, T tau_view, T mu, T g,
                                                  T albedo) noexcept {
    diffusion_sample<T> r;
    r.mu = clamp(mu, T(-1), T(1));
    const T gc = clamp(g, T(-0.999), T(0.999));
    const T w = clamp(albedo, T(0), T(1));
    const diffusion_medium<T> medium = diffusion_similarity(gc, w);
    const T ts = diffusion_depth(tau_sun);
    const T x = medium.s * ts;
    const T y = medium.s * diffusion_depth(tau_behind);

    r.direct = std::exp(-ts);
    // e^(-a x) for a = 1/2, 1, 2 from one exponential.
    const T e_half = std::exp(T(-0.5) * x);
    const T e_one = e_half * e_half;
    const T beams[diffusion_layout::peak_a_count] = {e_half, e_one, e_one * e_one};
    for (int ia = 0; ia < diffusion_layout::peak_a_count; ++ia)
        r.beams[ia] = max(beams[ia] - r.direct, T(0));

    // The scaled medium's albedo w (1 - g) / (1 - w g) scales the first-collision source.
    const T source = w * (T(1) - gc) / medium.s;
    T flux = T(0);
    const T U = diffusion_chord_fluence(x, y, e_one, medium.kappa, flux);
    r.diffuse = source * max(U + T(3) * gc * flux * r.mu, T(0)) * inv_four_pi_v<T>;
    r.u = diffusion_table_coordinates(ts, tau_behind, tau_view, r.mu, gc, w);
    return r;
}

}  // namespace detail

// The table C at coordinates u (multilinear interpolation).
template <class T>
[[nodiscard]] inline T diffusion_table_lookup(const diffusion_model& m,
                                              const diffusion_coordinates<T>& u) noexcept {
    T sum = T(0);
    detail::diffusion_table_corners(u, [&](int index, T weight) { sum += weight * T(m.table[index]); });
    return sum;
}

// Generic form: phase(mu, scale) returns the phase function with its eccentricities scaled
// by `scale` (1, 1/2 and 4/5 are asked for), as in multiple_scattering_with; g is that
// phase function's mean cosine (for a dual lobe, (1 - w) g0 + w g1); albedo the medium's
// single-scattering albedo sigma_s / sigma_t (clamped to [0, 1]).
template <class T, class PhaseFn>
[[nodiscard]] inline T diffusion_scattering_with(T tau_sun, T tau_behind, T tau_view, T mu,
                                                 T g, T albedo, const diffusion_model& m,
                                                 PhaseFn&& phase) noexcept {
    namespace L = diffusion_layout;
    const detail::diffusion_sample<T> t =
        detail::diffusion_sample_terms(tau_sun, tau_behind, tau_view, mu, g, albedo);
    T peak = T(0);
    for (int ic = 0; ic < L::peak_c_count; ++ic) {
        T weight = T(0);
        for (int ia = 0; ia < L::peak_a_count; ++ia)
            weight += T(m.peak[ia * L::peak_c_count + ic]) * t.beams[ia];
        peak += weight * phase(t.mu, T(L::peak_c[ic]));
    }
    const T C = diffusion_table_lookup(m, t.u);
    return detail::max(phase(t.mu, T(1)) * t.direct + peak + t.diffuse * detail::max(C, T(0)), T(0));
}

// With the Henyey-Greenstein phase function of asymmetry g.
template <class T>
[[nodiscard]] inline T diffusion_scattering(T tau_sun, T tau_behind, T tau_view, T mu, T g,
                                            T albedo, const diffusion_model& m) noexcept {
    return diffusion_scattering_with(tau_sun, tau_behind, tau_view, mu, g, albedo, m,
                                     [g](T mm, T scale) { return phase_hg(mm, scale * g); });
}

}  // namespace cloudmath

// The fitted models (generated by cloudmath_lighting_error fit-diffusion).
#include "diffusion_lighting_models.hpp"

#endif  // CLOUDMATH_DIFFUSION_LIGHTING_HPP
