// cloudmath/atmosphere.hpp: a physical atmosphere for the clouds' sun and sky: the parameters
// of a planet's air with Earth's as the documented default, the extinction at an altitude,
// the optical depth and transmittance along a ray by quadrature, the transmittance LUT's
// parametrisation (Bruneton 2017) with a CPU baker and lookup, the scattering coefficients,
// Hillaire 2020's multiple scattering with its LUT and a refined LUT (the orders gathered from
// the air around, a sky-lit ground, the field's vertical moment), the sky's irradiance on the
// ground (and its table, for a sky-lit ground below the horizon), the aerial perspective
// (in-scattering and transmittance to a point), the sky's radiance, the sun's illuminance,
// and the exposure of physically based engines (EV100).
//
// Use:      #include <cloudmath/atmosphere.hpp>
//           const auto air = cloudmath::earth_atmosphere<float>();
//           glm::vec3 T_sun = cloudmath::atmosphere_transmittance(air, camera_altitude, sun_dir.y);
//           // once per atmosphere, then per pixel (directions in the camera's frame, +y up):
//           cloudmath::atmosphere_sky_luts<float> luts = cloudmath::atmosphere_make_sky_luts(air);  // 32 x 32
//           // the ground below the horizon lit by the sky too (else by the sun alone):
//           luts.ground_irradiance = cloudmath::atmosphere_ground_irradiance_lut(air, luts.table());
//           const cloudmath::atmosphere_multiple_scattering_table<float> ms = luts.table();
//           glm::vec3 sky = sun_lux * cloudmath::atmosphere_sky_radiance(air, ms, camera_altitude, view_dir, sun_dir);
//           auto haze = cloudmath::atmosphere_inscatter(air, ms, camera_altitude, view_dir, sun_dir, distance);
//           glm::vec3 seen = surface * haze.transmittance + sun_lux * haze.radiance;
//           float exposure = cloudmath::exposure_from_ev100(cloudmath::ev100_from_camera(16.f, 1 / 100.f, 100.f));
// Units:    lengths in metres, altitudes above the ground sphere (bottom_radius), scattering and
//           absorption coefficients in 1/m; the three channels are the wavelengths 680, 550 and
//           440 nm (red, green, blue).
// Model:    Rayleigh and Mie (aerosol) densities fall exponentially with altitude; ozone, which
//           only absorbs, lies in a tent 2 ozone_half_width wide around ozone_center; extinction
//           sigma_t(h) = rayleigh e^(-h/H_R) + mie_extinction e^(-h/H_M) + ozone tent(h).
// Source:   Bruneton 2017, "precomputed_atmospheric_scattering" (its Earth constants and its
//           transmittance LUT parametrisation); Hillaire 2020 (EGSR) uses the same; Lagarde and
//           de Rousiers 2014, "Moving Frostbite to Physically Based Rendering", for EV100.
// Accuracy: atmosphere_transmittance with its default 64 steps is within 1e-3 absolute of a
//           20,000-step long double quadrature at every altitude from 0 to the top and every
//           zenith angle, in float (measured 5.3e-4; tests/test_atmosphere.cpp). The 256 x 64
//           LUT's bilinear lookup is within 2.5e-3 more than 0.06 in cosine from the horizon
//           (worst at 40 km, the ozone tent's kink between two rows; 256 x 128: 1.0e-3) and
//           within 0.02 nearer to it.
//           The sky (atmosphere_sky_radiance, float, 32 steps, atmosphere_make_sky_luts' 32 x 32
//           LUTs) is within 0.5-0.9% rms of a path tracer with every order of scattering for
//           the sun at 90-10 degrees and 1.4-3.5% at 2 and -2 (docs/atmosphere_truth.md; a
//           held-out set at 60, 20, 5, 0 and -1 degrees: 0.7-3.5%, docs/atmosphere_holdout.md),
//           and 0.80% rms, worst 1.54%, 2-10 degrees above the horizon for the sun at 2-60
//           degrees (docs/atmosphere.md); with Hillaire's LUT alone 1.7-5.5% and 10-11%.
// Light:    per unit of the sun's illuminance above the air: radiance in 1/sr, to be multiplied
//           by the sun's illuminance (lux per channel gives cd/m^2; docs/atmosphere.md).
// GLSL twin: cloudmath/glsl/atmosphere.glsl (the LUT bakers and lookups; atmosphere_inscatter
//           and atmosphere_sky_radiance read the multiple-scattering table through a function
//           the shader defines, CM_ATMOSPHERE_TABLE, within 1e-4 relative of these in
//           docs/glsl_parity.md; the refined LUT and the ground irradiance LUT are C++ only).
#ifndef CLOUDMATH_ATMOSPHERE_HPP
#define CLOUDMATH_ATMOSPHERE_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core.hpp"
#include "geometry.hpp"
#include "phase.hpp"
#include "transmittance.hpp"

namespace cloudmath {

// A planet's air. Every field is configurable; earth_atmosphere() gives Earth's.
template <class T>
struct atmosphere_parameters {
    T bottom_radius;                  // m: the ground sphere
    T top_radius;                     // m: where the air ends (no extinction above)
    glm::vec<3, T> rayleigh_scattering;  // 1/m at the ground (Rayleigh scatters, absorbs nothing)
    T rayleigh_scale_height;          // m
    T mie_scattering;                 // 1/m at the ground (grey)
    T mie_extinction;                 // 1/m at the ground: scattering + absorption
    T mie_scale_height;               // m
    T mie_g;                          // the Cornette-Shanks phase function's asymmetry
    glm::vec<3, T> ozone_absorption;  // 1/m at the ozone layer's peak
    T ozone_center;                   // m: the altitude of the peak
    T ozone_half_width;               // m: the tent falls to 0 this far above and below it
    T ground_albedo;                  // Lambertian
};

// Earth's air as Bruneton 2017 gives it (REFERENCES.md, "Atmosphere"): ground 6360 km, top
// 6420 km; Rayleigh (5.802, 13.558, 33.1) e-6 /m, scale height 8 km; Mie scattering 3.996e-6
// and extinction 4.40e-6 /m, scale height 1.2 km, g 0.8; ozone (0.650, 1.881, 0.085) e-6 /m in
// a tent 25 km +- 15 km; ground albedo 0.1.
template <class T>
[[nodiscard]] constexpr atmosphere_parameters<T> earth_atmosphere() noexcept {
    return {T(6360e3),
            T(6420e3),
            glm::vec<3, T>(T(5.802e-6), T(13.558e-6), T(33.1e-6)),
            T(8000),
            T(3.996e-6),
            T(4.40e-6),
            T(1200),
            T(0.8),
            glm::vec<3, T>(T(0.650e-6), T(1.881e-6), T(0.085e-6)),
            T(25e3),
            T(15e3),
            T(0.1)};
}

// The number of view zenith cosines at which atmosphere_multiple_scattering_refined_lut
// tabulates the aerosol field (the multiple-scattering field turned by Cornette-Shanks).
inline constexpr int atmosphere_aerosol_field_nodes = 17;

// atmosphere_extinction(air, altitude): sigma_t (1/m per channel) at `altitude` metres above
// the ground: Rayleigh + Mie extinction + ozone absorption. Altitudes below 0 are taken as 0;
// above the top the air still has its exponential tails (the caller's rays end at the top).
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_extinction(const atmosphere_parameters<T>& air, T altitude) noexcept {
    const T h = detail::max(altitude, T(0));
    const T tent = detail::max(T(1) - detail::abs(h - air.ozone_center) / air.ozone_half_width, T(0));
    return air.rayleigh_scattering * std::exp(-h / air.rayleigh_scale_height) +
           glm::vec<3, T>(air.mie_extinction * std::exp(-h / air.mie_scale_height)) + air.ozone_absorption * tent;
}

// atmosphere_distance_to_top(air, altitude, cos_zenith): how far a ray from `altitude` with
// zenith cosine mu travels before it leaves the air (the top sphere), by the cancellation-free
// ray_sphere_intersect_altitude; 0 at or above the top when the ray points outward.
template <class T>
[[nodiscard]] inline T atmosphere_distance_to_top(const atmosphere_parameters<T>& air, T altitude, T cos_zenith) noexcept {
    const glm::vec<2, T> t = ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius,
                                                           air.top_radius - air.bottom_radius);
    return detail::max(t.y, T(0));
}

// atmosphere_ray_hits_ground(air, altitude, cos_zenith): true when the ray meets the ground
// sphere (in front of the point): below the horizon of a point above the ground.
template <class T>
[[nodiscard]] inline bool atmosphere_ray_hits_ground(const atmosphere_parameters<T>& air, T altitude, T cos_zenith) noexcept {
    if (!(cos_zenith < T(0))) return false;
    const glm::vec<2, T> t = ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, T(0));
    return t.x >= T(0) && t.y >= t.x;
}

// atmosphere_optical_depth(air, altitude, cos_zenith, distance, steps): the optical depth
// (per channel) along `distance` metres of the ray, by the midpoint rule over `steps` equal
// steps (at least 1), each sample's altitude from altitude_along_ray (no cancellation at
// planet scale). The integrand is smooth, so 64 steps reach the transmittance's 1e-3 over a
// whole path to the top (header comment); a segment of a few kilometres needs far fewer.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_optical_depth(const atmosphere_parameters<T>& air, T altitude, T cos_zenith,
                                                             T distance, int steps = 64) noexcept {
    const int n = steps > 1 ? steps : 1;
    const T d = detail::max(distance, T(0));
    const T ds = d / T(n);
    glm::vec<3, T> tau(T(0));
    for (int i = 0; i < n; ++i) {
        const T t = (T(i) + T(0.5)) * ds;
        tau += atmosphere_extinction(air, altitude_along_ray(altitude, cos_zenith, air.bottom_radius, t));
    }
    return tau * ds;
}

// atmosphere_transmittance(air, altitude, cos_zenith, steps): the transmittance from the
// point to the top of the air along the direction (what the sun's light keeps on its way
// down to the point, for the sun in that direction); 0 when the ray meets the ground first.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_transmittance(const atmosphere_parameters<T>& air, T altitude, T cos_zenith,
                                                             int steps = 64) noexcept {
    if (atmosphere_ray_hits_ground(air, altitude, cos_zenith)) return glm::vec<3, T>(T(0));
    const glm::vec<3, T> tau =
        atmosphere_optical_depth(air, altitude, cos_zenith, atmosphere_distance_to_top(air, altitude, cos_zenith), steps);
    return glm::vec<3, T>(std::exp(-tau.x), std::exp(-tau.y), std::exp(-tau.z));
}

namespace detail {
// The length of a ray in the air from `altitude` with zenith cosine mu: to the ground where it
// meets it, else to the top.
template <class T>
inline T atmosphere_ray_length(const atmosphere_parameters<T>& air, T altitude, T cos_zenith) noexcept {
    return atmosphere_ray_hits_ground(air, altitude, cos_zenith)
               ? ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, T(0)).x
               : atmosphere_distance_to_top(air, altitude, cos_zenith);
}

// The Lambertian ground's radiance per unit sun illuminance where the sun's zenith cosine is
// mu_s: albedo / pi times the sun's cosine and transmittance (0 with the sun below it).
template <class T>
inline glm::vec<3, T> atmosphere_lit_ground(const atmosphere_parameters<T>& air, T mu_s, int sun_steps) noexcept {
    return atmosphere_transmittance(air, T(0), mu_s, sun_steps) * (max(mu_s, T(0)) * air.ground_albedo * inv_pi_v<T>);
}
}  // namespace detail

// The transmittance LUT's parametrisation (Bruneton 2017, 4.1.3): a texture of width x
// height texels over (mu, r) for rays that reach the top without meeting the ground. With
// H = sqrt(top^2 - bottom^2), rho = sqrt(r^2 - bottom^2) (the distance to the horizon) and d
// the distance to the top, x_r = rho / H and x_mu = (d - d_min) / (d_max - d_min),
// d_min = top - r, d_max = rho + H: the horizon and the zenith land on the texture's edges
// and the texels crowd near the horizon, where the transmittance changes fastest. Texture
// coordinates put x = 0 and 1 at the centres of the first and last texels.
// atmosphere_transmittance_lut_uv(air, altitude, cos_zenith, size): the (u, v) to sample.
template <class T>
[[nodiscard]] inline glm::vec<2, T> atmosphere_transmittance_lut_uv(const atmosphere_parameters<T>& air, T altitude, T cos_zenith,
                                                                    const glm::vec<2, T>& size) noexcept {
    const T R = air.bottom_radius, top = air.top_radius;
    const T r = R + detail::clamp(altitude, T(0), top - R);
    const T H = std::sqrt((top - R) * (top + R));
    const T rho = std::sqrt(detail::max((r - R) * (r + R), T(0)));
    const T d = atmosphere_distance_to_top(air, r - R, cos_zenith);
    const T d_min = top - r, d_max = rho + H;
    const T x_mu = d_max > d_min ? detail::clamp((d - d_min) / (d_max - d_min), T(0), T(1)) : T(0);
    const T x_r = rho / H;
    return glm::vec<2, T>(T(0.5) / size.x + x_mu * (T(1) - T(1) / size.x), T(0.5) / size.y + x_r * (T(1) - T(1) / size.y));
}

// atmosphere_transmittance_lut_altitude_mu(air, uv, size): the inverse, the (altitude,
// cos_zenith) of texture coordinate uv: what a LUT generator evaluates at each texel centre.
template <class T>
[[nodiscard]] inline glm::vec<2, T> atmosphere_transmittance_lut_altitude_mu(const atmosphere_parameters<T>& air,
                                                                             const glm::vec<2, T>& uv,
                                                                             const glm::vec<2, T>& size) noexcept {
    const T R = air.bottom_radius, top = air.top_radius;
    const T x_mu = saturate((uv.x - T(0.5) / size.x) / (T(1) - T(1) / size.x));
    const T x_r = saturate((uv.y - T(0.5) / size.y) / (T(1) - T(1) / size.y));
    const T H = std::sqrt((top - R) * (top + R));
    const T rho = H * x_r;
    const T r = std::sqrt(rho * rho + R * R);
    const T d_min = top - r, d_max = rho + H;
    const T d = d_min + x_mu * (d_max - d_min);
    // mu from the law of cosines, top^2 = r^2 + d^2 + 2 r d mu; straight up where d = 0.
    const T mu = d > T(0) ? detail::clamp((H * H - rho * rho - d * d) / (T(2) * r * d), T(-1), T(1)) : T(1);
    return glm::vec<2, T>(r - R, mu);
}

// atmosphere_transmittance_lut(air, width, height, steps): the LUT on the CPU, row-major
// (v = 0 first), each texel atmosphere_transmittance at its centre. width, height >= 2
// (smaller values are taken as 2). The reference for a GPU-generated one.
template <class T>
[[nodiscard]] inline std::vector<glm::vec<3, T>> atmosphere_transmittance_lut(const atmosphere_parameters<T>& air, int width,
                                                                             int height, int steps = 64) {
    const int w = width > 2 ? width : 2, h = height > 2 ? height : 2;
    const glm::vec<2, T> size{T(w), T(h)};
    std::vector<glm::vec<3, T>> lut(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const glm::vec<2, T> am =
                atmosphere_transmittance_lut_altitude_mu(air, glm::vec<2, T>((T(i) + T(0.5)) / size.x, (T(j) + T(0.5)) / size.y), size);
            lut[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)] =
                atmosphere_transmittance(air, am.x, am.y, steps);
        }
    return lut;
}

namespace detail {
// A LUT of width x height texels sampled as GL_LINEAR with clamp-to-edge would at uv.
template <class T>
inline glm::vec<3, T> lut_bilinear(const glm::vec<3, T>* lut, int w, int h, const glm::vec<2, T>& uv) noexcept {
    const T x = uv.x * T(w) - T(0.5), y = uv.y * T(h) - T(0.5);
    const int x0 = floor_to_int(x, 0, w - 2), y0 = floor_to_int(y, 0, h - 2);
    const T fx = saturate(x - T(x0)), fy = saturate(y - T(y0));
    const auto at = [&](int i, int j) {
        return lut[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)];
    };
    const glm::vec<3, T> bottom = at(x0, y0) * (T(1) - fx) + at(x0 + 1, y0) * fx;
    const glm::vec<3, T> upper = at(x0, y0 + 1) * (T(1) - fx) + at(x0 + 1, y0 + 1) * fx;
    return bottom * (T(1) - fy) + upper * fy;
}

template <class T>
inline glm::vec<3, T> lut_bilinear(const std::vector<glm::vec<3, T>>& lut, int w, int h, const glm::vec<2, T>& uv) noexcept {
    if (w < 2 || h < 2 || lut.size() < static_cast<std::size_t>(w) * static_cast<std::size_t>(h)) return glm::vec<3, T>(T(0));
    return lut_bilinear(lut.data(), w, h, uv);
}
}  // namespace detail

// atmosphere_transmittance_from_lut(air, lut, width, height, altitude, cos_zenith): the LUT
// sampled as GL_LINEAR with clamp-to-edge would at atmosphere_transmittance_lut_uv; 0 when
// the ray meets the ground (the LUT holds only rays to the top). lut must hold width x height
// texels (width, height >= 2), as atmosphere_transmittance_lut made them.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_transmittance_from_lut(const atmosphere_parameters<T>& air,
                                                                      const std::vector<glm::vec<3, T>>& lut, int width,
                                                                      int height, T altitude, T cos_zenith) noexcept {
    if (atmosphere_ray_hits_ground(air, altitude, cos_zenith)) return glm::vec<3, T>(T(0));
    return detail::lut_bilinear(lut, width, height,
                                atmosphere_transmittance_lut_uv(air, altitude, cos_zenith, glm::vec<2, T>(T(width), T(height))));
}

// ---------------------------------------------------------------------------------------
// Scattering, multiple scattering (Hillaire 2020), sky radiance, sun illuminance and aerial
// perspective. Light is given per unit of the sun's illuminance above the air: pass the sun's
// extraterrestrial illuminance (lux, or W/m^2 per channel) and radiance comes out in the same
// unit per steradian (cd/m^2 for lux; luminance is then dot(rec709, rgb), see docs/atmosphere.md).

// atmosphere_scattering_coefficient(air, altitude): sigma_s (1/m per channel): Rayleigh plus
// Mie scattering (ozone only absorbs). What the isotropic multiple-scattering term multiplies.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_scattering_coefficient(const atmosphere_parameters<T>& air, T altitude) noexcept {
    const T h = detail::max(altitude, T(0));
    return air.rayleigh_scattering * std::exp(-h / air.rayleigh_scale_height) +
           glm::vec<3, T>(air.mie_scattering * std::exp(-h / air.mie_scale_height));
}

// atmosphere_scattering(air, altitude, cos_theta): the scattering coefficient times the phase
// function (1/(m sr) per channel) for light turned by the angle whose cosine is cos_theta
// (between the sun's direction and the view ray's, both pointing away from the point):
// Rayleigh's phase for the molecules, Cornette-Shanks with mie_g for the aerosols.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_scattering(const atmosphere_parameters<T>& air, T altitude, T cos_theta) noexcept {
    const T h = detail::max(altitude, T(0));
    return air.rayleigh_scattering * (std::exp(-h / air.rayleigh_scale_height) * phase_rayleigh(cos_theta)) +
           glm::vec<3, T>(air.mie_scattering * std::exp(-h / air.mie_scale_height) * phase_cornette_shanks(cos_theta, air.mie_g));
}

// atmosphere_sun_illuminance(air, altitude, cos_sun_zenith, sun_illuminance): the sun's
// illuminance on a plane facing it at `altitude` (per channel, in the unit of
// sun_illuminance, the value above the air): sun_illuminance times atmosphere_transmittance
// (64 steps); 0 once the sun is behind the ground. Earth's shadow is sharp here: the sun's
// disc is a point.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_sun_illuminance(const atmosphere_parameters<T>& air, T altitude, T cos_sun_zenith,
                                                               const glm::vec<3, T>& sun_illuminance) noexcept {
    return sun_illuminance * atmosphere_transmittance(air, altitude, cos_sun_zenith, 64);
}

namespace detail {
// The sun with zenith cosine mu_s at azimuth 0 in a point's frame (+y up).
template <class T>
inline glm::vec<3, T> atmosphere_sun_direction(T mu_s) noexcept {
    return {std::sqrt(max(T(1) - mu_s * mu_s, T(0))), mu_s, T(0)};
}

// Ray k of a golden-angle set: zenith cosine mu, azimuth k times the golden angle. With the
// cosines evenly spaced, the rays spread evenly over the sphere (spherical Fibonacci) or the
// hemisphere.
template <class T>
inline glm::vec<3, T> atmosphere_golden_ray(T mu, int k) noexcept {
    const T phi = pi_v<T> * (T(3) - std::sqrt(T(5))) * T(k);
    const T sin_zenith = std::sqrt(max(T(1) - mu * mu, T(0)));
    return {sin_zenith * std::cos(phi), mu, sin_zenith * std::sin(phi)};
}

// The second order's turn towards the point (1/(m sr)): the sun's light scattered once at
// altitude h by the angle whose cosine is nu. Molecules with Rayleigh's phase: from a high sun
// the light that reaches a point along the horizon is turned by 90 degrees, 0.75 of the
// isotropic value Hillaire 2020 uses. Aerosols isotropic for Hillaire's LUT (and its GLSL,
// HLSL and WGSL twins): alone, Cornette-Shanks's forward peak (g = 0.8), narrower than 64
// rays resolve, put the sky at a high sun 3% rms off, not 1.5%. With Cornette-Shanks where
// the refined LUT also carries the aerosol field (cornette_shanks): the aureole's light is
// then in the field, and the aerosol field turns it on forward (with an isotropic turn the
// sky 2-10 degrees up was 1-2% too dark; docs/atmosphere.md).
template <class T>
inline glm::vec<3, T> atmosphere_second_order_turn(const atmosphere_parameters<T>& air, T altitude, T nu,
                                                   bool cornette_shanks = false) noexcept {
    const T h = max(altitude, T(0));
    const T aerosol_phase = cornette_shanks ? phase_cornette_shanks(nu, air.mie_g) : inv_four_pi_v<T>;
    return air.rayleigh_scattering * (std::exp(-h / air.rayleigh_scale_height) * phase_rayleigh(nu)) +
           glm::vec<3, T>(air.mie_scattering * std::exp(-h / air.mie_scale_height) * aerosol_phase);
}

// The aerosol field's nodes: view zenith cosines mu_j = x_j |x_j|, x_j = -1 + 2 j / (J - 1),
// crowded around the horizon.
template <class T>
inline T atmosphere_aerosol_node(int j) noexcept {
    const T x = T(-1) + T(2) * T(j) / T(atmosphere_aerosol_field_nodes - 1);
    return x * abs(x);
}

// w[k J + j]: Cornette-Shanks between ray k of the golden set of n_dir rays (zenith cosine
// 1 - (2k + 1)/n_dir) and a view of zenith cosine mu_j, averaged over the azimuth between
// them (the field is taken as symmetric about the vertical), normalised so that the mean over
// the rays is 1 for each node: an isotropic field is carried as it is.
template <class T>
inline std::vector<T> atmosphere_aerosol_weights(int n_dir, T g) {
    const int J = atmosphere_aerosol_field_nodes, M = 256;
    std::vector<T> w(static_cast<std::size_t>(n_dir) * static_cast<std::size_t>(J));
    for (int j = 0; j < J; ++j) {
        const double mj = double(atmosphere_aerosol_node<T>(j)), sj = std::sqrt(max(1.0 - mj * mj, 0.0));
        double sum = 0.0;
        std::vector<double> pb(static_cast<std::size_t>(n_dir));
        for (int k = 0; k < n_dir; ++k) {
            const double mk = 1.0 - (2.0 * k + 1.0) / n_dir, sk = std::sqrt(max(1.0 - mk * mk, 0.0));
            double acc = 0.0;
            for (int m = 0; m < M; ++m)
                acc += double(phase_cornette_shanks(T(mk * mj + sk * sj * std::cos(pi_v<double> * (m + 0.5) / M)), g));
            pb[static_cast<std::size_t>(k)] = acc / M;
            sum += acc / M;
        }
        for (int k = 0; k < n_dir; ++k)
            w[static_cast<std::size_t>(k) * static_cast<std::size_t>(J) + static_cast<std::size_t>(j)] =
                T(pb[static_cast<std::size_t>(k)] * n_dir / sum);
    }
    return w;
}
}  // namespace detail

namespace detail {
// Psi_ms's parts at a point: L2 (the second order's light arriving, per unit sun illuminance),
// f (the fraction of isotropic light that the air scatters back to the point) and b2 (L2's
// vertical second moment: the mean over rays of the light arriving times the square of the
// ray's zenith cosine; L2 / 3 for light arriving alike from everywhere).
template <class T>
struct atmosphere_second_order_parts {
    glm::vec<3, T> L2, f, b2;
    glm::vec<3, T> c2{T(0)};  // the mean of the light times the square of the ray's horizontal cosine towards the sun's azimuth
    glm::vec<3, T> S[atmosphere_aerosol_field_nodes] = {};  // the light turned by Cornette-Shanks into each node's view (with weights)
};

template <class T>
inline atmosphere_second_order_parts<T> atmosphere_second_order(const atmosphere_parameters<T>& air, T altitude, T cos_sun_zenith,
                                                                int directions, int steps, int sun_steps,
                                                                const T* aerosol_weights = nullptr) noexcept {
    const int n_dir = directions > 1 ? directions : 1, n = steps > 1 ? steps : 1;
    const T h = clamp(altitude, T(0), air.top_radius - air.bottom_radius);
    const T r = air.bottom_radius + h;
    const T mu_s = clamp(cos_sun_zenith, T(-1), T(1));
    const glm::vec<3, T> sun = atmosphere_sun_direction(mu_s);
    glm::vec<3, T> L2(T(0)), f(T(0)), b2(T(0));
    atmosphere_second_order_parts<T> out{};
    for (int k = 0; k < n_dir; ++k) {
        // Spherical Fibonacci: cosines evenly spaced in (-1, 1), azimuths by the golden angle.
        const T mu = T(1) - (T(2) * T(k) + T(1)) / T(n_dir);
        const glm::vec<3, T> dir = atmosphere_golden_ray(mu, k);
        const bool ground = atmosphere_ray_hits_ground(air, h, mu);
        const T length = atmosphere_ray_length(air, h, mu);
        const T ds = length / T(n);
        const T nu = glm::dot(dir, sun);
        glm::vec<3, T> throughput(T(1)), L(T(0)), F(T(0));
        for (int i = 0; i < n; ++i) {
            const T t = (T(i) + T(0.5)) * ds;
            const T hy = altitude_along_ray(h, mu, air.bottom_radius, t);
            const T mu_sy = clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), T(-1), T(1));
            const glm::vec<3, T> sigma_t = atmosphere_extinction(air, hy);
            const glm::vec<3, T> sigma_s = atmosphere_scattering_coefficient(air, hy);
            const glm::vec<3, T> step_t = beer_lambert(sigma_t * ds);
            // (1 - e^-sigma ds)/sigma without the textbook form's loss in thin air (core.hpp).
            const glm::vec<3, T> integral = one_minus_exp_neg_over_x(sigma_t * ds) * ds;
            const glm::vec<3, T> sun_t = atmosphere_transmittance(air, hy, mu_sy, sun_steps);
            L += throughput * atmosphere_second_order_turn(air, hy, nu, aerosol_weights != nullptr) * sun_t * integral;
            F += throughput * sigma_s * integral;
            throughput *= step_t;
        }
        if (ground) {
            const T mu_sg = clamp((r * mu_s + length * nu) / air.bottom_radius, T(-1), T(1));
            L += throughput * atmosphere_lit_ground(air, mu_sg, sun_steps);
        }
        L2 += L;
        f += F;
        b2 += L * (mu * mu);
        out.c2 += L * (dir.x * dir.x);  // the sun is at azimuth 0 (+x)
        if (aerosol_weights != nullptr)
            for (int j = 0; j < atmosphere_aerosol_field_nodes; ++j)
                out.S[j] += L * aerosol_weights[k * atmosphere_aerosol_field_nodes + j];
    }
    out.L2 = L2 / T(n_dir);
    out.f = f / T(n_dir);
    out.b2 = b2 / T(n_dir);
    out.c2 /= T(n_dir);
    for (int j = 0; j < atmosphere_aerosol_field_nodes; ++j) out.S[j] /= T(n_dir);
    return out;
}

// Hillaire's geometric series over the orders from the second on. f < 1 for any air that
// absorbs or lets light escape; the clamp keeps 1/(1 - f) finite.
template <class T>
inline glm::vec<3, T> atmosphere_geometric_orders(const atmosphere_second_order_parts<T>& p) noexcept {
    return p.L2 / (glm::vec<3, T>(T(1)) - glm::min(p.f, glm::vec<3, T>(T(0.999))));
}
}  // namespace detail

// atmosphere_multiple_scattering(air, altitude, cos_sun_zenith, directions, steps,
// sun_steps): Hillaire 2020's Psi_ms (5.5), the radiance that every order of scattering from
// the second on sends into a point, per unit sun illuminance and per unit scattering
// coefficient; the point's multiple scattering is sigma_s Psi_ms, isotropic. From the point it
// marches `directions` rays spread evenly over the sphere (a spherical Fibonacci set), each
// over `steps` equal steps to the top or the ground, and gathers
//   L2  = mean over rays of the singly scattered light arriving along the ray (Rayleigh's
//         phase for the molecules where Hillaire takes isotropic, isotropic for the aerosols;
//         sun transmittance by atmosphere_transmittance with sun_steps steps) plus the
//         Lambertian ground's reflection where the ray meets it,
//   f   = mean over rays of the fraction of isotropic light scattered back towards the point,
// and sums the orders as a geometric series: Psi_ms = L2 / (1 - f). Each step is integrated
// exactly for its constant medium, (1 - e^-sigma_t ds)/sigma_t (Hillaire 2015), so thin and
// thick steps both conserve energy. Hillaire's LUT uses 64 directions and 20 steps.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_multiple_scattering(const atmosphere_parameters<T>& air, T altitude,
                                                                   T cos_sun_zenith, int directions, int steps,
                                                                   int sun_steps) noexcept {
    return detail::atmosphere_geometric_orders(
        detail::atmosphere_second_order(air, altitude, cos_sun_zenith, directions, steps, sun_steps));
}

// The multiple-scattering LUT's parametrisation: u = 0.5 + 0.5 sign(mu_s) sqrt(|mu_s|) for the
// sun's zenith cosine mu_s, v = altitude / (top - bottom), with x = 0 and 1 at the centres of
// the first and last texels. Hillaire 2020 spaces u linearly in mu_s; the square root crowds
// the columns around the horizon, where Earth's shadow (mu_s from 0 at the ground to -0.14 at
// the top) makes Psi_ms change fastest: 32 columns put 12 within 0.15 of mu_s = 0 instead of 4.
// With the sun 2 degrees below the horizon the linear 32 x 32 LUT left the sky 8.6% rms off
// its path-traced truth, this one 4.7% (docs/atmosphere.md).
// atmosphere_multiple_scattering_lut_uv(air, altitude, cos_sun_zenith, size): the (u, v).
template <class T>
[[nodiscard]] inline glm::vec<2, T> atmosphere_multiple_scattering_lut_uv(const atmosphere_parameters<T>& air, T altitude,
                                                                          T cos_sun_zenith, const glm::vec<2, T>& size) noexcept {
    const T c = detail::clamp(cos_sun_zenith, T(-1), T(1));
    const T root = std::sqrt(detail::abs(c));
    const T x_mu = saturate(T(0.5) + T(0.5) * (c < T(0) ? -root : root));
    const T x_h = saturate(altitude / (air.top_radius - air.bottom_radius));
    return glm::vec<2, T>(T(0.5) / size.x + x_mu * (T(1) - T(1) / size.x), T(0.5) / size.y + x_h * (T(1) - T(1) / size.y));
}

// atmosphere_multiple_scattering_lut_altitude_mu(air, uv, size): the inverse, (altitude,
// cos_sun_zenith) at texture coordinate uv.
template <class T>
[[nodiscard]] inline glm::vec<2, T> atmosphere_multiple_scattering_lut_altitude_mu(const atmosphere_parameters<T>& air,
                                                                                   const glm::vec<2, T>& uv,
                                                                                   const glm::vec<2, T>& size) noexcept {
    const T x_mu = saturate((uv.x - T(0.5) / size.x) / (T(1) - T(1) / size.x));
    const T x_h = saturate((uv.y - T(0.5) / size.y) / (T(1) - T(1) / size.y));
    const T m = T(2) * x_mu - T(1);
    return glm::vec<2, T>(x_h * (air.top_radius - air.bottom_radius), m * detail::abs(m));
}


// atmosphere_multiple_scattering_lut(air, width, height, directions, steps, sun_steps): the
// LUT on the CPU, row-major (v = 0 first), each texel atmosphere_multiple_scattering at its
// centre; width, height >= 2. Hillaire's size is 32 x 32 with 64 directions and 20 steps.
template <class T>
[[nodiscard]] inline std::vector<glm::vec<3, T>> atmosphere_multiple_scattering_lut(const atmosphere_parameters<T>& air, int width,
                                                                                   int height, int directions = 64,
                                                                                   int steps = 20, int sun_steps = 32) {
    const int w = width > 2 ? width : 2, h = height > 2 ? height : 2;
    const glm::vec<2, T> size{T(w), T(h)};
    std::vector<glm::vec<3, T>> lut(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const glm::vec<2, T> am = atmosphere_multiple_scattering_lut_altitude_mu(
                air, glm::vec<2, T>((T(i) + T(0.5)) / size.x, (T(j) + T(0.5)) / size.y), size);
            lut[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)] =
                atmosphere_multiple_scattering(air, am.x, am.y, directions, steps, sun_steps);
        }
    return lut;
}

// atmosphere_multiple_scattering_from_lut(air, lut, width, height, altitude, cos_sun_zenith):
// the LUT's bilinear lookup at atmosphere_multiple_scattering_lut_uv.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_multiple_scattering_from_lut(const atmosphere_parameters<T>& air,
                                                                            const std::vector<glm::vec<3, T>>& lut, int width,
                                                                            int height, T altitude, T cos_sun_zenith) noexcept {
    return detail::lut_bilinear(lut, width, height,
                                atmosphere_multiple_scattering_lut_uv(air, altitude, cos_sun_zenith,
                                                                      glm::vec<2, T>(T(width), T(height))));
}

// What a view ray gathers: the transmittance along it and the light scattered into it.
template <class T>
struct atmosphere_segment {
    glm::vec<3, T> transmittance;  // from the camera to the segment's end
    glm::vec<3, T> radiance;       // in-scattered, per unit sun illuminance, 1/sr
};

// The multiple-scattering LUT as atmosphere_inscatter reads it: Psi_ms per texel and, where
// given, the field's vertical second moment per texel (atmosphere_multiple_scattering_refined_lut's
// `vertical_moments`); without it the field is taken as isotropic.
template <class T>
struct atmosphere_multiple_scattering_table {
    const std::vector<glm::vec<3, T>>* texels = nullptr;  // atmosphere_multiple_scattering_lut's
    int width = 0, height = 0;                            // nothing (no multiple scattering) if empty
    const std::vector<glm::vec<3, T>>* vertical_moments = nullptr;  // same size as texels, or none
    // The sky's irradiance on the ground by the sun's angle (atmosphere_ground_irradiance_lut),
    // for atmosphere_sky_radiance's ground; none: the ground reflects only the sun.
    const std::vector<glm::vec<3, T>>* ground_irradiance = nullptr;
    // Where given (atmosphere_multiple_scattering_refined_lut's last two outputs): the field's
    // horizontal second moment towards the sun's azimuth (same size as texels), for Rayleigh's
    // turn by the view's azimuth as well; and the aerosol field, atmosphere_aerosol_field_nodes
    // blocks of width x height texels (node-major), the field turned by Cornette-Shanks into a
    // view of each node's zenith cosine.
    const std::vector<glm::vec<3, T>>* sun_azimuth_moments = nullptr;
    const std::vector<glm::vec<3, T>>* aerosol_field = nullptr;
};

namespace detail {
// The sky's irradiance on the ground for the sun's zenith cosine mu_s there from
// atmosphere_ground_irradiance_lut's values: linear in the LUT's column coordinate u.
template <class T>
inline glm::vec<3, T> atmosphere_ground_irradiance_at(const atmosphere_parameters<T>& air,
                                                      const std::vector<glm::vec<3, T>>& per_column, T mu_s) noexcept {
    const int w = static_cast<int>(per_column.size());
    if (w < 2) return w == 1 ? per_column[0] : glm::vec<3, T>(T(0));
    const T x = atmosphere_multiple_scattering_lut_uv(air, T(0), mu_s, glm::vec<2, T>(T(w), T(1))).x * T(w) - T(0.5);
    const int x0 = floor_to_int(x, 0, w - 2);  // a NaN mu_s reads column 0, never an undefined conversion
    const T fx = saturate(x - T(x0));
    return per_column[static_cast<std::size_t>(x0)] * (T(1) - fx) + per_column[static_cast<std::size_t>(x0) + 1] * fx;
}
}  // namespace detail

// atmosphere_multiple_scattering_source(air, altitude, psi, vertical_moment, cos_view_zenith):
// the light per unit length (1/m, per unit sun illuminance and steradian) that the
// multiple-scattering field scatters into a ray whose zenith cosine there is cos_view_zenith:
// psi (Psi_ms, the field's mean) and vertical_moment (the mean of the field times the square
// of its direction's zenith cosine, psi / 3 for an isotropic field) from the LUTs. The
// aerosols scatter it isotropically: sigma_M psi. The molecules by Rayleigh's phase over the
// field taken as symmetric about the vertical: sigma_R 3/4 (psi + a (1 - mu^2) + b mu^2), with
// b the vertical moment and a = (psi - b) / 2 each horizontal one; for an isotropic field that
// is sigma_R psi. Near the ground the field comes mostly from near the horizon, which Rayleigh
// turns into a horizontal view up to 1.125 times as strongly as isotropic light and into a
// vertical one 0.75 times as strongly.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_multiple_scattering_source(const atmosphere_parameters<T>& air, T altitude,
                                                                          const glm::vec<3, T>& psi,
                                                                          const glm::vec<3, T>& vertical_moment,
                                                                          T cos_view_zenith) noexcept {
    const T h = detail::max(altitude, T(0));
    const T mu2 = detail::clamp(cos_view_zenith * cos_view_zenith, T(0), T(1));
    const glm::vec<3, T> horizontal = (psi - vertical_moment) * T(0.5);
    return air.rayleigh_scattering * std::exp(-h / air.rayleigh_scale_height) *
               (T(0.75) * (psi + horizontal * (T(1) - mu2) + vertical_moment * mu2)) +
           psi * (air.mie_scattering * std::exp(-h / air.mie_scale_height));
}

namespace detail {
// What the table's field scatters into a ray with zenith cosine mu_view at (altitude, mu_s).
// cos2_azimuth: the square of the cosine of the azimuth between the view and the sun.
template <class T>
inline glm::vec<3, T> atmosphere_table_source(const atmosphere_parameters<T>& air, const atmosphere_multiple_scattering_table<T>& ms,
                                              T altitude, T cos_sun_zenith, T cos_view_zenith, T cos2_azimuth) noexcept {
    const glm::vec<2, T> uv =
        atmosphere_multiple_scattering_lut_uv(air, altitude, cos_sun_zenith, glm::vec<2, T>(T(ms.width), T(ms.height)));
    const glm::vec<3, T> psi = lut_bilinear(*ms.texels, ms.width, ms.height, uv);
    if (ms.vertical_moments == nullptr) return atmosphere_scattering_coefficient(air, altitude) * psi;
    const glm::vec<3, T> b = lut_bilinear(*ms.vertical_moments, ms.width, ms.height, uv);
    const std::size_t texels = static_cast<std::size_t>(ms.width) * static_cast<std::size_t>(ms.height);
    if (ms.sun_azimuth_moments == nullptr || ms.aerosol_field == nullptr || ms.sun_azimuth_moments->size() < texels ||
        ms.aerosol_field->size() < texels * std::size_t(atmosphere_aerosol_field_nodes))
        return atmosphere_multiple_scattering_source(air, altitude, psi, b, cos_view_zenith);
    const T h = max(altitude, T(0));
    const T mu2 = clamp(cos_view_zenith * cos_view_zenith, T(0), T(1));
    const T c2 = clamp(cos2_azimuth, T(0), T(1));
    const glm::vec<3, T> along = lut_bilinear(*ms.sun_azimuth_moments, ms.width, ms.height, uv);  // towards the sun's azimuth
    const glm::vec<3, T> horizontal = along * c2 + (psi - b - along) * (T(1) - c2);
    const glm::vec<3, T> rayleigh = air.rayleigh_scattering * std::exp(-h / air.rayleigh_scale_height) *
                                    (T(0.75) * (psi + horizontal * (T(1) - mu2) + b * mu2));
    glm::vec<3, T> aerosol = psi;
    // Where the sun is below this point's horizon the field is lit from one side of the sky
    // only, and its azimuthal average misplaces Cornette-Shanks's forward peak: isotropic there.
    if (cos_sun_zenith > T(0)) {
        const T m = clamp(cos_view_zenith, T(-1), T(1));
        const T x = m < T(0) ? -std::sqrt(-m) : std::sqrt(m);
        const T fj = (x + T(1)) * T(0.5) * T(atmosphere_aerosol_field_nodes - 1);
        const int j0 = floor_to_int(fj, 0, atmosphere_aerosol_field_nodes - 2);
        const T fr = saturate(fj - T(j0));
        const glm::vec<3, T>* field = ms.aerosol_field->data();
        aerosol = lut_bilinear(field + texels * std::size_t(j0), ms.width, ms.height, uv) * (T(1) - fr) +
                  lut_bilinear(field + texels * std::size_t(j0 + 1), ms.width, ms.height, uv) * fr;
    }
    return rayleigh + aerosol * (air.mie_scattering * std::exp(-h / air.mie_scale_height));
}

// The square of the cosine of the azimuth between directions of zenith cosines mu and mu_s
// whose dot product is nu; 1/2 (no azimuth) when either is vertical.
template <class T>
inline T atmosphere_cos2_azimuth(T mu, T mu_s, T nu) noexcept {
    const T den = (T(1) - mu * mu) * (T(1) - mu_s * mu_s);
    if (!(den > T(1e-8))) return T(0.5);
    const T c = nu - mu * mu_s;
    return clamp(c * c / den, T(0), T(1));
}
}  // namespace detail

// atmosphere_inscatter(air, ms, altitude, view_dir, sun_dir, distance, steps, sun_steps): the
// light that the air scatters into the view ray between the camera and `distance` metres
// along it (or where the ray leaves the air or meets the ground, if nearer), and the
// transmittance over the same stretch: aerial perspective for a point at that distance, the
// sky for an infinite one. Directions are unit vectors in the camera's frame with +y up (the
// radial direction through the camera at `altitude` inside the air). Per step: the sun's
// single scattering (atmosphere_scattering times the sun's transmittance, 0 in the planet's
// shadow) plus what the multiple-scattering field scatters into the ray
// (atmosphere_multiple_scattering_source; none if ms is empty), integrated
// exactly for the step's constant medium. Steps grow quadratically with distance (t_i = D
// (i/steps)^2) because the air thins as the ray climbs. Radiance is per unit sun
// illuminance; multiply by the sun's illuminance above the air.
template <class T>
[[nodiscard]] inline atmosphere_segment<T> atmosphere_inscatter(const atmosphere_parameters<T>& air,
                                                                 const atmosphere_multiple_scattering_table<T>& ms, T altitude,
                                                                 const glm::vec<3, T>& view_dir, const glm::vec<3, T>& sun_dir,
                                                                 T distance, int steps = 32, int sun_steps = 32) noexcept {
    const int n = steps > 1 ? steps : 1;
    const T h = detail::clamp(altitude, T(0), air.top_radius - air.bottom_radius);
    const T r = air.bottom_radius + h;
    const T mu = detail::clamp(view_dir.y, T(-1), T(1));
    const T mu_s = detail::clamp(sun_dir.y, T(-1), T(1));
    const T nu = detail::clamp(glm::dot(view_dir, sun_dir), T(-1), T(1));
    const T edge = detail::atmosphere_ray_length(air, h, mu);
    const T D = detail::clamp(distance, T(0), edge);  // a NaN distance stays NaN: NaN out
    const bool use_ms = ms.texels != nullptr && !ms.texels->empty();
    // The view's azimuth from the sun's, from the camera (it turns little along the ray).
    const T cos2_azimuth = detail::atmosphere_cos2_azimuth(mu, mu_s, nu);
    atmosphere_segment<T> out{glm::vec<3, T>(T(1)), glm::vec<3, T>(T(0))};
    for (int i = 0; i < n; ++i) {
        const T x0 = T(i) / T(n), x1 = T(i + 1) / T(n);
        const T t0 = D * x0 * x0, t1 = D * x1 * x1;
        const T ds = t1 - t0, t = T(0.5) * (t0 + t1);
        const T hy = altitude_along_ray(h, mu, air.bottom_radius, t);
        const T mu_sy = detail::clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), T(-1), T(1));
        const glm::vec<3, T> sigma_t = atmosphere_extinction(air, hy);
        glm::vec<3, T> source = atmosphere_scattering(air, hy, nu) * atmosphere_transmittance(air, hy, mu_sy, sun_steps);
        if (use_ms)
            source += detail::atmosphere_table_source(air, ms, hy, mu_sy,
                                                      detail::clamp((r * mu + t) / (air.bottom_radius + hy), T(-1), T(1)),
                                                      cos2_azimuth);
        const glm::vec<3, T> step_t = beer_lambert(sigma_t * ds);
        const glm::vec<3, T> integral = one_minus_exp_neg_over_x(sigma_t * ds) * ds;
        out.radiance += out.transmittance * source * integral;
        out.transmittance *= step_t;
    }
    return out;
}

// atmosphere_sky_radiance(air, ms, altitude, view_dir, sun_dir, steps, sun_steps): the sky's
// radiance along view_dir (per unit sun illuminance, 1/sr; the sun's disc itself excluded):
// atmosphere_inscatter to the end of the air, plus, for rays that meet the ground, the
// Lambertian ground seen through the air: lit by the sun (albedo/pi cos T_sun) and, when the
// table carries ms.ground_irradiance (atmosphere_ground_irradiance_lut), by the sky. Without
// it the ground below the horizon is too dark by the sky's share of its light: against the
// path tracer, looking straight down from sea level, in blue 27% with the sun at 30 degrees,
// 63% at 10, 99% at 2 (docs/atmosphere.md, "The ground below the horizon").
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_sky_radiance(const atmosphere_parameters<T>& air,
                                                            const atmosphere_multiple_scattering_table<T>& ms, T altitude,
                                                            const glm::vec<3, T>& view_dir, const glm::vec<3, T>& sun_dir,
                                                            int steps = 32, int sun_steps = 32) noexcept {
    const T inf = std::numeric_limits<T>::max();
    const atmosphere_segment<T> seg = atmosphere_inscatter(air, ms, altitude, view_dir, sun_dir, inf, steps, sun_steps);
    const T h = detail::clamp(altitude, T(0), air.top_radius - air.bottom_radius);
    const T mu = detail::clamp(view_dir.y, T(-1), T(1));
    if (!atmosphere_ray_hits_ground(air, h, mu)) return seg.radiance;
    const T t = detail::atmosphere_ray_length(air, h, mu);
    const T mu_sg = detail::clamp(((air.bottom_radius + h) * sun_dir.y + t * glm::dot(view_dir, sun_dir)) / air.bottom_radius,
                                  T(-1), T(1));
    glm::vec<3, T> ground = detail::atmosphere_lit_ground(air, mu_sg, sun_steps);
    if (ms.ground_irradiance != nullptr)
        ground += detail::atmosphere_ground_irradiance_at(air, *ms.ground_irradiance, mu_sg) *
                  (air.ground_albedo * inv_pi_v<T>);
    return seg.radiance + seg.transmittance * ground;
}

// atmosphere_ground_irradiance(air, ms, cos_sun_zenith, directions, steps, sun_steps): the
// sky's irradiance on the ground (a horizontal plane at altitude 0, the sun's own light left
// out) per unit sun illuminance: atmosphere_sky_radiance times the zenith cosine, integrated
// over the upper hemisphere by `directions` rays whose zenith cosines are evenly spaced in
// (0, 1) (so each stands for the same solid angle, 2 pi / directions) and whose azimuths step
// by the golden angle. The sky's share of what the ground reflects, which Hillaire 2020's
// Psi_ms leaves out.
template <class T>
[[nodiscard]] inline glm::vec<3, T> atmosphere_ground_irradiance(const atmosphere_parameters<T>& air,
                                                                 const atmosphere_multiple_scattering_table<T>& ms,
                                                                 T cos_sun_zenith, int directions = 128, int steps = 32,
                                                                 int sun_steps = 32) noexcept {
    const int n = directions > 1 ? directions : 1;
    const glm::vec<3, T> sun = detail::atmosphere_sun_direction(detail::clamp(cos_sun_zenith, T(-1), T(1)));
    glm::vec<3, T> E(T(0));
    for (int k = 0; k < n; ++k) {
        const T mu = (T(k) + T(0.5)) / T(n);
        E += atmosphere_sky_radiance(air, ms, T(0), detail::atmosphere_golden_ray(mu, k), sun, steps, sun_steps) * mu;
    }
    return E * (T(2) * pi_v<T> / T(n));
}

// atmosphere_ground_irradiance_lut(air, ms, size, directions, steps, sun_steps): the sky's
// irradiance on the ground (atmosphere_ground_irradiance) at `size` (>= 2) sun zenith cosines
// spaced as the multiple-scattering LUT's columns (u = 0.5 + 0.5 sign(mu_s) sqrt(|mu_s|), the
// first and last values at mu_s = -1 and 1), for atmosphere_multiple_scattering_table::
// ground_irradiance: atmosphere_sky_radiance then lets the ground below the horizon reflect
// the sky as well as the sun, reading the values linearly by u. Per unit sun illuminance. An
// empty `ms` gives the single-scattering sky's irradiance. Cost: size x `directions` sky rays
// (64 x 128: 0.13-0.23 s on one thread). Looking 30-90 degrees down, the sky-lit ground is
// within 1% of the path tracer with the sun at 90-10 degrees, 2.6% at 2 and 7.6% at -2
// (docs/atmosphere.md, "The ground below the horizon").
template <class T>
[[nodiscard]] inline std::vector<glm::vec<3, T>> atmosphere_ground_irradiance_lut(
    const atmosphere_parameters<T>& air, const atmosphere_multiple_scattering_table<T>& ms, int size = 64,
    int directions = 128, int steps = 32, int sun_steps = 32) {
    const int n = size > 2 ? size : 2;
    // Only the columns matter: mu_s depends on u alone (the altitude row is any).
    const glm::vec<2, T> columns{T(n), T(2)};
    std::vector<glm::vec<3, T>> E(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const T mu_s =
            atmosphere_multiple_scattering_lut_altitude_mu(air, glm::vec<2, T>((T(i) + T(0.5)) / columns.x, T(0.25)), columns).y;
        E[static_cast<std::size_t>(i)] = atmosphere_ground_irradiance(air, ms, mu_s, directions, steps, sun_steps);
    }
    return E;
}

namespace detail {
// One texel's pass of atmosphere_multiple_scattering_refined_lut: over the rays and steps of
// atmosphere_second_order, the light that the multiple-scattering field of the previous pass
// (`field`) sends to the point from the air, plus the ground's reflection of the sky's
// irradiance (`sky_on_ground`, one value per LUT column, by the sun's cosine at the ground);
// the gathered light's mean (E) and vertical second moment (b), as atmosphere_second_order's
// L2 and b2.
template <class T>
struct atmosphere_gathered {
    glm::vec<3, T> E, b;
    glm::vec<3, T> c2{T(0)};
    glm::vec<3, T> S[atmosphere_aerosol_field_nodes] = {};
};

template <class T>
inline atmosphere_gathered<T> atmosphere_orders_gathered(const atmosphere_parameters<T>& air,
                                                                   const atmosphere_multiple_scattering_table<T>& field,
                                                                   const std::vector<glm::vec<3, T>>& sky_on_ground, T altitude,
                                                                   T cos_sun_zenith, int directions, int steps,
                                                                   const T* aerosol_weights = nullptr) noexcept {
    const int n_dir = directions > 1 ? directions : 1, n = steps > 1 ? steps : 1;
    const T h = clamp(altitude, T(0), air.top_radius - air.bottom_radius);
    const T r = air.bottom_radius + h;
    const T mu_s = clamp(cos_sun_zenith, T(-1), T(1));
    const glm::vec<3, T> sun = atmosphere_sun_direction(mu_s);
    glm::vec<3, T> E(T(0)), b(T(0));
    atmosphere_gathered<T> out{};
    for (int k = 0; k < n_dir; ++k) {
        const T mu = T(1) - (T(2) * T(k) + T(1)) / T(n_dir);  // atmosphere_second_order's rays
        const glm::vec<3, T> dir = atmosphere_golden_ray(mu, k);
        const T length = atmosphere_ray_length(air, h, mu);
        const T ds = length / T(n);
        const T nu = glm::dot(dir, sun);
        const T cos2_azimuth = atmosphere_cos2_azimuth(mu, mu_s, nu);
        glm::vec<3, T> throughput(T(1)), G(T(0));
        for (int i = 0; i < n; ++i) {
            const T t = (T(i) + T(0.5)) * ds;
            const T hy = altitude_along_ray(h, mu, air.bottom_radius, t);
            const T ry = air.bottom_radius + hy;
            const T mu_sy = clamp((r * mu_s + t * nu) / ry, T(-1), T(1));
            const glm::vec<3, T> sigma_t = atmosphere_extinction(air, hy);
            const glm::vec<3, T> integral = one_minus_exp_neg_over_x(sigma_t * ds) * ds;
            G += throughput * integral *
                 atmosphere_table_source(air, field, hy, mu_sy, clamp((r * mu + t) / ry, T(-1), T(1)), cos2_azimuth);
            throughput *= beer_lambert(sigma_t * ds);
        }
        if (atmosphere_ray_hits_ground(air, h, mu)) {
            const T mu_sg = clamp((r * mu_s + length * nu) / air.bottom_radius, T(-1), T(1));
            G += throughput * atmosphere_ground_irradiance_at(air, sky_on_ground, mu_sg) *
                 (air.ground_albedo * inv_pi_v<T>);
        }
        E += G;
        b += G * (mu * mu);
        out.c2 += G * (dir.x * dir.x);
        if (aerosol_weights != nullptr)
            for (int j = 0; j < atmosphere_aerosol_field_nodes; ++j)
                out.S[j] += G * aerosol_weights[k * atmosphere_aerosol_field_nodes + j];
    }
    out.E = E / T(n_dir);
    out.b = b / T(n_dir);
    out.c2 /= T(n_dir);
    for (int j = 0; j < atmosphere_aerosol_field_nodes; ++j) out.S[j] /= T(n_dir);
    return out;
}
}  // namespace detail

// atmosphere_multiple_scattering_refined_lut(air, width, height, passes, directions, steps,
// sun_steps, vertical_moments): the multiple-scattering LUT (same size, parametrisation and
// lookup as atmosphere_multiple_scattering_lut) with three of Hillaire 2020's approximations
// removed:
//   - Hillaire sums the orders from the third on as a geometric series of the point's own
//     transfer f, as if the air all around were lit like the point. Near the ground, and as
//     the sun sets, the air above is lit far more than the point (the sun's light reaches it
//     through less air), so the series falls short: the blue horizon was 13% too dark with the
//     sun 10 degrees up. Here each pass gathers the previous pass's field from the air around,
//     texel by texel: Psi = L2 + mean over rays of the integral of T sigma Psi(h', mu_s') ds
//     (the orders as they are, with the LUT's own altitude and sun angle at every step),
//     starting from Hillaire's Psi_ms.
//   - Hillaire's ground reflects only the sun. Here it also reflects the sky's irradiance
//     (atmosphere_ground_irradiance of the previous pass, 128 rays, per LUT column).
//   - Hillaire's field is isotropic. Here each texel also keeps the field's vertical second
//     moment (written to *vertical_moments when given, for atmosphere_multiple_scattering_table)
//     and the molecules scatter the field by Rayleigh's phase over it
//     (atmosphere_multiple_scattering_source), in the passes and in the sky's march.
//   - With aerosol_field given (and sun_azimuth_moments, for the table): the aerosols turn the
//     field by Cornette-Shanks, not isotropically. Each texel keeps the field turned into a
//     view at each of atmosphere_aerosol_field_nodes zenith cosines (node-major blocks of
//     width x height texels) and its horizontal second moment towards the sun's azimuth (the
//     molecules' Rayleigh turn by the view's azimuth too), and the second order's turn uses
//     Cornette-Shanks. Near the ground the field is brightest along the horizon and the
//     aerosols' forward peak sends it into views just above it: without this the sky 2-10
//     degrees up was 2.0% rms, 3.4% worst too dark against the path tracer; with it 0.80%,
//     1.54% (docs/atmosphere.md, "The sky near the horizon").
// `passes` (default 3) such passes; the third and the fifth differ by under 0.5%. The sky with
// every output (atmosphere_make_sky_luts) is within 0.5-0.9% rms of the path-traced truth for
// the sun at 90-10 degrees and 1.4-3.5% at 2 and -2 (docs/atmosphere_truth.md); with the
// vertical moments only 0.9-2.1% and 2.4-3.9%. C++ only: every pass reads the previous LUT and
// the sky's irradiance (a shader would bake it as one compute pass per iteration with the LUTs
// bound as textures). CPU cost at 32 x 32 (one run, one thread): 2.6 s with the vertical
// moments, 2.9 s with every output (docs/atmosphere.md).
template <class T>
[[nodiscard]] inline std::vector<glm::vec<3, T>> atmosphere_multiple_scattering_refined_lut(
    const atmosphere_parameters<T>& air, int width, int height, int passes = 3, int directions = 64, int steps = 20,
    int sun_steps = 32, std::vector<glm::vec<3, T>>* vertical_moments = nullptr,
    std::vector<glm::vec<3, T>>* sun_azimuth_moments = nullptr, std::vector<glm::vec<3, T>>* aerosol_field = nullptr) {
    const int w = width > 2 ? width : 2, h = height > 2 ? height : 2;
    const glm::vec<2, T> size{T(w), T(h)};
    const std::size_t texels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    std::vector<glm::vec<3, T>> second(texels), second_moment(texels), psi(texels), moment(texels);
    constexpr int J = atmosphere_aerosol_field_nodes;
    const std::size_t nodes = texels * std::size_t(J);
    std::vector<glm::vec<3, T>> second_along(texels), along(texels), second_aerosol(nodes), aerosol(nodes);
    // The aerosol field (and Cornette-Shanks in the second order's turn) only where it is asked
    // for: without it the sky reads the aerosols' light as isotropic, and an isotropic turn
    // keeps that consistent.
    const bool aerosol_turn = aerosol_field != nullptr;
    const std::vector<T> weights =
        aerosol_turn ? detail::atmosphere_aerosol_weights<T>(directions > 1 ? directions : 1, air.mie_g) : std::vector<T>();
    const T* turn = aerosol_turn ? weights.data() : nullptr;
    std::vector<glm::vec<2, T>> where(texels);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i);
            where[k] = atmosphere_multiple_scattering_lut_altitude_mu(
                air, glm::vec<2, T>((T(i) + T(0.5)) / size.x, (T(j) + T(0.5)) / size.y), size);
            const detail::atmosphere_second_order_parts<T> p =
                detail::atmosphere_second_order(air, where[k].x, where[k].y, directions, steps, sun_steps, turn);
            second[k] = p.L2;
            second_moment[k] = p.b2;
            second_along[k] = p.c2;
            psi[k] = detail::atmosphere_geometric_orders(p);
            moment[k] = psi[k] / T(3);  // isotropic until a pass gathers the field's own
            along[k] = psi[k] / T(3);
            for (int n = 0; n < J; ++n) {
                second_aerosol[std::size_t(n) * texels + k] = p.S[n];
                aerosol[std::size_t(n) * texels + k] = psi[k];
            }
        }
    std::vector<glm::vec<3, T>> sky_on_ground, next(texels), next_moment(texels), next_along(texels), next_aerosol(nodes);
    for (int pass = 0; pass < passes; ++pass) {
        const atmosphere_multiple_scattering_table<T> field{&psi, w, h, &moment, nullptr, aerosol_turn ? &along : nullptr,
                                                            aerosol_turn ? &aerosol : nullptr};
        sky_on_ground = atmosphere_ground_irradiance_lut(air, field, w, 128, 32, sun_steps);
        for (std::size_t k = 0; k < texels; ++k) {
            const detail::atmosphere_gathered<T> g =
                detail::atmosphere_orders_gathered(air, field, sky_on_ground, where[k].x, where[k].y, directions, steps, turn);
            next[k] = second[k] + g.E;
            next_moment[k] = second_moment[k] + g.b;
            next_along[k] = second_along[k] + g.c2;
            for (int n = 0; n < J; ++n) next_aerosol[std::size_t(n) * texels + k] = second_aerosol[std::size_t(n) * texels + k] + g.S[n];
        }
        psi.swap(next);
        moment.swap(next_moment);
        along.swap(next_along);
        aerosol.swap(next_aerosol);
    }
    if (vertical_moments != nullptr) *vertical_moments = moment;
    if (sun_azimuth_moments != nullptr) *sun_azimuth_moments = along;
    if (aerosol_field != nullptr) *aerosol_field = aerosol;
    return psi;
}

// atmosphere_sky_luts<T>: the refined LUT with everything the sky's march reads, owned.
// table() hands them to atmosphere_sky_radiance and atmosphere_inscatter; it points into this
// object, so keep the object in place (not moved or destroyed) while the table is in use.
// ground_irradiance starts empty (the ground reflects the sun only); fill it with
// atmosphere_ground_irradiance_lut(air, luts.table()) for a sky-lit ground below the horizon.
template <class T>
struct atmosphere_sky_luts {
    int width = 0, height = 0;
    std::vector<glm::vec<3, T>> texels, vertical_moments, sun_azimuth_moments, aerosol_field, ground_irradiance;
    [[nodiscard]] atmosphere_multiple_scattering_table<T> table() const noexcept {
        return {&texels, width, height, &vertical_moments, ground_irradiance.empty() ? nullptr : &ground_irradiance,
                &sun_azimuth_moments, &aerosol_field};
    }
};

// atmosphere_make_sky_luts(air, width, height, passes, directions, steps, sun_steps): the
// refined LUT with its vertical and sun-azimuth moments and its aerosol field
// (atmosphere_multiple_scattering_refined_lut with every output), the sky's defaults.
template <class T>
[[nodiscard]] inline atmosphere_sky_luts<T> atmosphere_make_sky_luts(const atmosphere_parameters<T>& air, int width = 32,
                                                                     int height = 32, int passes = 3, int directions = 64,
                                                                     int steps = 20, int sun_steps = 32) {
    atmosphere_sky_luts<T> out;
    out.width = width > 2 ? width : 2;
    out.height = height > 2 ? height : 2;
    out.texels = atmosphere_multiple_scattering_refined_lut(air, out.width, out.height, passes, directions, steps, sun_steps,
                                                            &out.vertical_moments, &out.sun_azimuth_moments, &out.aerosol_field);
    return out;
}

// atmosphere_stacked_table(luts): the LUTs' parts stacked in one image for a shader's
// CM_ATMOSPHERE_TABLE (atmosphere.glsl's sky section), the layout its example reads with
// texelFetch(u_table, ivec2(x, y + part * height)): width x (atmosphere_stacked_table_parts *
// height) texels, row-major, part p at rows p * height .. p * height + height - 1, in the GLSL's
// part numbers: 0 (CM_ATMOSPHERE_TABLE_PSI) the texels, 1 (_VERTICAL) the vertical moments, 2
// (_ALONG) the sun-azimuth moments, 3 (_GROUND) zero (the ground irradiance is one row of its
// own width: give it its own texture), 4 + j (_AEROSOL + j) the aerosol field's node j. A part
// the LUTs lack (made without that output) is zero. Upload it as an RGB32F texture (what the
// example renderer's sky tables and the web demo's sky_table.bin hold).
inline constexpr int atmosphere_stacked_table_parts = 4 + atmosphere_aerosol_field_nodes;
template <class T>
[[nodiscard]] inline std::vector<glm::vec<3, T>> atmosphere_stacked_table(const atmosphere_sky_luts<T>& luts) {
    const std::size_t block = std::size_t(luts.width > 0 ? luts.width : 0) * std::size_t(luts.height > 0 ? luts.height : 0);
    std::vector<glm::vec<3, T>> out(block * std::size_t(atmosphere_stacked_table_parts), glm::vec<3, T>(T(0)));
    // Part `part` from `from`'s block `index`, when `from` holds it.
    const auto put = [&](int part, const std::vector<glm::vec<3, T>>& from, std::size_t index) {
        if (from.size() < block * (index + 1)) return;
        std::copy(from.begin() + std::ptrdiff_t(block * index), from.begin() + std::ptrdiff_t(block * (index + 1)),
                  out.begin() + std::ptrdiff_t(block * std::size_t(part)));
    };
    put(0, luts.texels, 0);
    put(1, luts.vertical_moments, 0);
    put(2, luts.sun_azimuth_moments, 0);
    for (int j = 0; j < atmosphere_aerosol_field_nodes; ++j) put(4 + j, luts.aerosol_field, std::size_t(j));
    return out;
}

// ---------------------------------------------------------------------------------------
// Exposure (Lagarde and de Rousiers 2014, 5.1): a physical camera's exposure value at ISO 100,
// and the factor that maps scene luminance (cd/m^2, or radiance in any unit scaled alike) to
// the [0, 1] of a sensor that saturates at 1.2 times the exposure's standard luminance.

// ev100_from_camera(aperture, shutter_time, iso) = log2(N^2 / t * 100 / S): aperture N (the
// f-number), shutter time t in seconds, sensitivity S. Sunny 16: f/16, 1/100 s, ISO 100 is
// log2(25600) = 14.64.
template <class T>
[[nodiscard]] inline T ev100_from_camera(T aperture, T shutter_time, T iso) noexcept {
    return std::log2(aperture * aperture / shutter_time * T(100) / iso);
}

// ev100_from_luminance(average_luminance) = log2(L * 100 / 12.5): the EV100 that exposes an
// average luminance L (cd/m^2) to middle grey (the reflected-light meter's K = 12.5).
template <class T>
[[nodiscard]] inline T ev100_from_luminance(T average_luminance) noexcept {
    return std::log2(average_luminance * T(100) / T(12.5));
}

// exposure_from_ev100(ev100) = 1 / (1.2 * 2^EV100): multiply scene luminance by it before the
// tonemap (the saturating-sensor model: 78% reflectance at 1.2 times the standard).
template <class T>
[[nodiscard]] inline T exposure_from_ev100(T ev100) noexcept {
    return T(1) / (T(1.2) * std::exp2(ev100));
}

}  // namespace cloudmath

#endif  // CLOUDMATH_ATMOSPHERE_HPP
