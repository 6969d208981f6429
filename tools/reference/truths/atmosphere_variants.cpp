// tools/reference/truths/atmosphere_variants.cpp: see atmosphere_variants.hpp.
#include "atmosphere_variants.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <cloudmath/atmosphere.hpp>

namespace cloudmath::reference::atmo {

namespace {

using vec3 = glm::vec3;
using air_t = atmosphere_parameters<float>;

// A LUT texel: the isotropic mean E of the multiple-scattering field (Psi_ms) and its vertical
// second moment b = mean of L (d . up)^2 (E / 3 for an isotropic field).
struct texel {
    vec3 E{0.0f}, b{0.0f};
};

struct lut {
    int w = 0, h = 0;
    bool sqrt_u = false;
    std::vector<texel> t;
};

float column_u(bool sqrt_u, float mu_s) {
    const float c = std::clamp(mu_s, -1.0f, 1.0f);
    return sqrt_u ? 0.5f + 0.5f * std::copysign(std::sqrt(std::fabs(c)), c) : 0.5f + 0.5f * c;
}

float column_mu(bool sqrt_u, float x) {
    const float m = 2.0f * x - 1.0f;
    return sqrt_u ? m * std::fabs(m) : m;
}

// (altitude, mu_s) of texel (i, j).
glm::vec2 texel_place(const air_t& air, const lut& L, int i, int j) {
    const float x = float(i) / float(L.w - 1), y = float(j) / float(L.h - 1);
    return {y * (air.top_radius - air.bottom_radius), column_mu(L.sqrt_u, x)};
}

texel lookup(const air_t& air, const lut& L, float altitude, float mu_s) {
    const float x = column_u(L.sqrt_u, mu_s) * float(L.w - 1);
    const float y = std::clamp(altitude / (air.top_radius - air.bottom_radius), 0.0f, 1.0f) * float(L.h - 1);
    const int x0 = std::clamp(int(std::floor(x)), 0, L.w - 2), y0 = std::clamp(int(std::floor(y)), 0, L.h - 2);
    const float fx = std::clamp(x - float(x0), 0.0f, 1.0f), fy = std::clamp(y - float(y0), 0.0f, 1.0f);
    const auto at = [&](int i, int j) { return L.t[std::size_t(j * L.w + i)]; };
    const auto mix = [](const texel& a, const texel& b, float s) { return texel{a.E + (b.E - a.E) * s, a.b + (b.b - a.b) * s}; };
    return mix(mix(at(x0, y0), at(x0 + 1, y0), fx), mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

vec3 rayleigh_at(const air_t& air, float h) { return air.rayleigh_scattering * std::exp(-std::max(h, 0.0f) / air.rayleigh_scale_height); }
vec3 mie_at(const air_t& air, float h) { return vec3(air.mie_scattering * std::exp(-std::max(h, 0.0f) / air.mie_scale_height)); }

// What the field `m` scatters towards a direction whose vertical cosine is mu (per unit
// length): with the moment, Rayleigh's phase over the field's vertical second moment (the
// field taken as symmetric about the vertical); without, isotropic.
vec3 field_scattered(const air_t& air, const ms_variant& v, const texel& m, float h, float mu) {
    if (!v.moment) return (rayleigh_at(air, h) + mie_at(air, h)) * m.E;
    const vec3 a = 0.5f * (m.E - m.b);  // the horizontal second moment, each axis
    return rayleigh_at(air, h) * 0.75f * (m.E + a * (1.0f - mu * mu) + m.b * mu * mu) + mie_at(air, h) * m.E;
}

vec3 fibonacci(int k, int n, float& mu) {
    const float golden_angle = pi_v<float> * (3.0f - std::sqrt(5.0f));
    mu = 1.0f - (2.0f * float(k) + 1.0f) / float(n);
    const float s = std::sqrt(std::max(1.0f - mu * mu, 0.0f)), phi = golden_angle * float(k);
    return {s * std::cos(phi), mu, s * std::sin(phi)};
}

// The second order at a point (L2, its vertical moment, and Hillaire's f).
struct second_order {
    vec3 L2{0.0f}, b{0.0f}, f{0.0f};
};

second_order gather_second(const air_t& air, const ms_variant& v, float h, float mu_s) {
    const int n_dir = 64, n = 20;
    const float r = air.bottom_radius + h;
    const vec3 sun(std::sqrt(std::max(1.0f - mu_s * mu_s, 0.0f)), mu_s, 0.0f);
    second_order out;
    for (int k = 0; k < n_dir; ++k) {
        float mu = 0.0f;
        const vec3 dir = fibonacci(k, n_dir, mu);
        const float length = detail::atmosphere_ray_length(air, h, mu), ds = length / float(n);
        const float nu = glm::dot(dir, sun);
        vec3 throughput(1.0f), L(0.0f), F(0.0f);
        for (int i = 0; i < n; ++i) {
            const float t = (float(i) + 0.5f) * ds;
            const float hy = altitude_along_ray(h, mu, air.bottom_radius, t);
            const float mu_sy = std::clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), -1.0f, 1.0f);
            const vec3 sigma_t = atmosphere_extinction(air, hy);
            const vec3 integral = one_minus_exp_neg_over_x(sigma_t * ds) * ds;
            const vec3 turn = rayleigh_at(air, hy) * (v.rayleigh_phase ? phase_rayleigh(nu) : inv_four_pi_v<float>) +
                              mie_at(air, hy) * (v.mie_phase ? phase_cornette_shanks(nu, air.mie_g) : inv_four_pi_v<float>);
            L += throughput * turn * atmosphere_transmittance(air, hy, mu_sy, 32) * integral;
            F += throughput * atmosphere_scattering_coefficient(air, hy) * integral;
            throughput *= beer_lambert(sigma_t * ds);
        }
        if (atmosphere_ray_hits_ground(air, h, mu)) {
            const float mu_sg = std::clamp((r * mu_s + length * nu) / air.bottom_radius, -1.0f, 1.0f);
            L += throughput * detail::atmosphere_lit_ground(air, mu_sg, 32);
        }
        out.L2 += L / float(n_dir);
        out.b += L * (mu * mu) / float(n_dir);
        out.f += F / float(n_dir);
    }
    return out;
}

// The sky's radiance from sea level with the variant's LUT.
vec3 sky(const air_t& air, const ms_variant& v, const lut& L, const vec3& view, const vec3& sun) {
    const int n = 32;
    const float r = air.bottom_radius, mu = view.y, nu = glm::dot(view, sun);
    const float D = detail::atmosphere_ray_length(air, 0.0f, mu);
    vec3 throughput(1.0f), radiance(0.0f);
    for (int i = 0; i < n; ++i) {
        const float x0 = float(i) / float(n), x1 = float(i + 1) / float(n);
        const float t0 = D * x0 * x0, t1 = D * x1 * x1, ds = t1 - t0, t = 0.5f * (t0 + t1);
        const float hy = altitude_along_ray(0.0f, mu, air.bottom_radius, t);
        const float ry = air.bottom_radius + hy;
        const float mu_sy = std::clamp((r * sun.y + t * nu) / ry, -1.0f, 1.0f);
        const float mu_vy = std::clamp((r * mu + t) / ry, -1.0f, 1.0f);  // the view's vertical cosine there
        const vec3 sigma_t = atmosphere_extinction(air, hy);
        const vec3 source = atmosphere_scattering(air, hy, nu) * atmosphere_transmittance(air, hy, mu_sy, 32) +
                            field_scattered(air, v, lookup(air, L, hy, mu_sy), hy, mu_vy);
        radiance += throughput * source * (one_minus_exp_neg_over_x(sigma_t * ds) * ds);
        throughput *= beer_lambert(sigma_t * ds);
    }
    if (atmosphere_ray_hits_ground(air, 0.0f, mu)) {
        const float mu_sg = std::clamp((r * sun.y + D * nu) / air.bottom_radius, -1.0f, 1.0f);
        radiance += throughput * detail::atmosphere_lit_ground(air, mu_sg, 32);
    }
    return radiance;
}

// The sky's irradiance on the ground, per LUT column (128 rays of equal solid angle).
std::vector<vec3> sky_on_ground(const air_t& air, const ms_variant& v, const lut& L) {
    std::vector<vec3> E(std::size_t(L.w), vec3(0.0f));
    const float golden_angle = pi_v<float> * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < L.w; ++i) {
        const float mu_s = texel_place(air, L, i, 0).y;
        const vec3 sun(std::sqrt(std::max(1.0f - mu_s * mu_s, 0.0f)), mu_s, 0.0f);
        for (int k = 0; k < 128; ++k) {
            const float mu = (float(k) + 0.5f) / 128.0f, s = std::sqrt(1.0f - mu * mu), phi = golden_angle * float(k);
            E[std::size_t(i)] += sky(air, v, L, vec3(s * std::cos(phi), mu, s * std::sin(phi)), sun) * mu;
        }
        E[std::size_t(i)] *= 2.0f * pi_v<float> / 128.0f;
    }
    return E;
}

// One pass: each texel gathers the previous field from the air around (and the sky-lit ground).
lut gather_pass(const air_t& air, const ms_variant& v, const lut& old, const std::vector<second_order>& base) {
    const std::vector<vec3> ground = v.sky_lit_ground ? sky_on_ground(air, v, old) : std::vector<vec3>();
    lut next = old;
    for (int j = 0; j < old.h; ++j)
        for (int i = 0; i < old.w; ++i) {
            const glm::vec2 place = texel_place(air, old, i, j);
            const float h = place.x, mu_s = place.y, r = air.bottom_radius + h;
            const vec3 sun(std::sqrt(std::max(1.0f - mu_s * mu_s, 0.0f)), mu_s, 0.0f);
            vec3 E(0.0f), b(0.0f);
            for (int k = 0; k < 64; ++k) {
                float mu = 0.0f;
                const vec3 dir = fibonacci(k, 64, mu);
                const float length = detail::atmosphere_ray_length(air, h, mu), ds = length / 20.0f;
                const float nu = glm::dot(dir, sun);
                vec3 throughput(1.0f), G(0.0f);
                for (int s = 0; s < 20; ++s) {
                    const float t = (float(s) + 0.5f) * ds;
                    const float hy = altitude_along_ray(h, mu, air.bottom_radius, t);
                    const float mu_sy = std::clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), -1.0f, 1.0f);
                    const float mu_dy = std::clamp((r * mu + t) / (air.bottom_radius + hy), -1.0f, 1.0f);
                    const vec3 sigma_t = atmosphere_extinction(air, hy);
                    G += throughput * (one_minus_exp_neg_over_x(sigma_t * ds) * ds) *
                         field_scattered(air, v, lookup(air, old, hy, mu_sy), hy, mu_dy);
                    throughput *= beer_lambert(sigma_t * ds);
                }
                if (v.sky_lit_ground && atmosphere_ray_hits_ground(air, h, mu)) {
                    const float mu_sg = std::clamp((r * mu_s + length * nu) / air.bottom_radius, -1.0f, 1.0f);
                    const float x = column_u(old.sqrt_u, mu_sg) * float(old.w - 1);
                    const int x0 = std::clamp(int(std::floor(x)), 0, old.w - 2);
                    const float fx = std::clamp(x - float(x0), 0.0f, 1.0f);
                    G += throughput * (ground[std::size_t(x0)] * (1.0f - fx) + ground[std::size_t(x0) + 1] * fx) *
                         (air.ground_albedo * inv_pi_v<float>);
                }
                E += G / 64.0f;
                b += G * (mu * mu) / 64.0f;
            }
            const second_order& s = base[std::size_t(j * old.w + i)];
            next.t[std::size_t(j * old.w + i)] = texel{s.L2 + E, s.b + b};
        }
    return next;
}

lut make_lut(const air_t& air, const ms_variant& v) {
    lut L;
    L.w = v.width;
    L.h = 32;
    L.sqrt_u = v.sqrt_u;
    L.t.resize(std::size_t(L.w * L.h));
    std::vector<second_order> base(L.t.size());
    for (int j = 0; j < L.h; ++j)
        for (int i = 0; i < L.w; ++i) {
            const glm::vec2 place = texel_place(air, L, i, j);
            const std::size_t k = std::size_t(j * L.w + i);
            base[k] = gather_second(air, v, place.x, place.y);
            // Hillaire's series; an isotropic field's moment until a pass gathers the real one.
            const vec3 E = base[k].L2 / (vec3(1.0f) - glm::min(base[k].f, vec3(0.999f)));
            L.t[k] = texel{E, E / 3.0f};
        }
    for (int pass = 0; pass < v.passes; ++pass) L = gather_pass(air, v, L, base);
    return L;
}

}  // namespace

std::vector<ms_variant> ms_variants() {
    return {
        {"Hillaire 2020 (the model before)", false, false, 0, false, false, false, 32},
        {"the orders gathered (3 passes)", false, false, 3, false, false, false, 32},
        {"the orders gathered, Rayleigh over the field's vertical moment", false, false, 3, false, false, true, 32},
        {"the orders gathered, second order by Rayleigh and Cornette-Shanks", true, true, 3, false, false, false, 32},
        {"the orders gathered, second order by Rayleigh", true, false, 3, false, false, false, 32},
        {"the same with the sky-lit ground", true, false, 3, true, false, false, 32},
        {"the same with columns by sqrt(mu_s)", true, false, 3, true, true, false, 32},
        {"the same with linear columns, 128 wide", true, false, 3, true, false, false, 128},
        {"the same with Rayleigh over the field's vertical moment (the library's)", true, false, 3, true, true, true, 32},
    };
}

std::vector<std::array<double, 3>> variant_radiance(const ms_variant& v, const std::vector<truth_row>& rows) {
    const air_t air = earth_atmosphere<float>();
    const lut L = make_lut(air, v);
    std::vector<std::array<double, 3>> out;
    out.reserve(rows.size());
    for (const truth_row& r : rows) {
        const mc::vec3 d = direction_from_degrees(r.view_elevation, r.view_azimuth);
        const mc::vec3 s = direction_from_degrees(r.sun_elevation, 0.0);
        const vec3 L3 = sky(air, v, L, vec3(glm::dvec3(d.x, d.y, d.z)), vec3(glm::dvec3(s.x, s.y, s.z)));
        out.push_back({double(L3.x), double(L3.y), double(L3.z)});
    }
    return out;
}

}  // namespace cloudmath::reference::atmo
