// far_shadow.cpp: see far_shadow.hpp.
#include "far_shadow.hpp"

#include "cloud_density.hpp"
#include "physical_sky.hpp"

#include <cloudmath/cloudmath.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>

namespace cloud_renderer {
namespace {

namespace cm = cloudmath;
using glm::vec2;
using glm::vec3;

// Beyond this optical depth the path's light is under 1e-4 of the sun's: the march stops.
constexpr float opaque_depth = 9.2f;

// The mean over far_shadow_grid^2 stratified start positions of one node's transmittance.
float node_mean(const scene& s, const vec3& sun_dir, const cloud_density& field, const far_shadow_table& t, float alt,
                float mu, float period, std::uint32_t seed) {
    const float R = s.planet_radius, r0 = R + s.camera_altitude;
    // The path's stretches: from where the light march ends to where it leaves the band's top,
    // less the dip below the band; none when it meets the ground.
    const vec2 ground = cm::ray_sphere_intersect_altitude(alt, mu, R, 0.0f);
    if (ground.x >= 0.0f && ground.y > ground.x) return 0.0f;
    const vec2 seg = cm::cloud_layer_segment(alt, mu, R, t.alt_lo, t.alt_hi);
    const float start = seg.y > seg.x ? std::min(seg.y, t.reach) : 0.0f;
    const float end = cm::ray_sphere_intersect_altitude(alt, mu, R, t.alt_hi).y;
    if (!(end > start)) return 1.0f;
    const vec2 dip = cm::ray_sphere_intersect_altitude(alt, mu, R, t.alt_lo);
    const bool dips = dip.x > 0.0f && dip.y > dip.x;
    const vec2 stretches[2] = {{start, dips ? std::min(dip.x, end) : end}, {dips ? std::max(dip.y, start) : end, end}};

    const float sin_mu = std::sqrt(std::max(1.0f - mu * mu, 0.0f));
    double sum = 0.0;
    const int n = far_shadow_grid;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            // A stratified start (x, z) over one period of the field, camera-relative.
            const std::uint32_t h = cm::noise_hash(seed + static_cast<std::uint32_t>(j * n + i));
            const float x = period * ((float(i) + cm::sample_jitter<float>(h, 0u, 0u)) / float(n) - 0.5f);
            const float z = period * ((float(j) + cm::sample_jitter<float>(h, 0u, 1u)) / float(n) - 0.5f);
            const float jitter = cm::sample_jitter<float>(h, 0u, 2u);
            const vec3 up = glm::normalize(vec3(x, r0, z));
            const vec3 p = up * (R + alt) - vec3(0.0f, r0, 0.0f);
            // Toward the sun's azimuth at p, at zenith cosine mu there.
            vec3 across = sun_dir - up * glm::dot(sun_dir, up);
            across = glm::length(across) > 1e-6f ? glm::normalize(across) : glm::normalize(glm::cross(up, vec3(0.0f, 0.0f, 1.0f)));
            const vec3 d = up * mu + across * sin_mu;
            float tau = 0.0f;
            for (const vec2& st : stretches) {
                const float length = st.y - st.x;
                if (!(length > 0.0f) || tau > opaque_depth) continue;
                const int steps = std::max(1, static_cast<int>(std::ceil(length / far_shadow_step)));
                const float ds = length / float(steps);
                for (int k = 0; k < steps && tau <= opaque_depth; ++k) {
                    const vec3 q = p + d * (st.x + (float(k) + jitter) * ds);
                    tau += s.extinction * field.density(q) * ds;
                }
            }
            sum += double(std::exp(-tau));
        }
    return static_cast<float>(sum / double(n * n));
}

far_shadow_table make_table(const scene& s, const vec3& sun_dir, const cloud_textures& textures, float reach) {
    far_shadow_table t = far_shadow_nodes(s, reach);
    t.texels.assign(static_cast<std::size_t>(t.n_alt * t.n_mu), 1.0f);
    const cloud_density field(s, textures);
    const float period = s.shape == cloud_shape::classic ? s.weather_tile : s.weather_wide_tile;
    const auto rows = [&](int first, int stride) {
        for (int m = first; m < t.n_mu; m += stride) {
            const float mu = t.mu_lo + (t.mu_hi - t.mu_lo) * float(m) / float(t.n_mu - 1);
            for (int a = 0; a < t.n_alt; ++a) {
                const float alt = t.alt_lo + (t.alt_hi - t.alt_lo) * float(a) / float(t.n_alt - 1);
                t.texels[static_cast<std::size_t>(m * t.n_alt + a)] =
                    node_mean(s, sun_dir, field, t, alt, mu, period, static_cast<std::uint32_t>(m * t.n_alt + a) * 7919u);
            }
        }
    };
    const int workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (int w = 1; w < workers; ++w) pool.emplace_back(rows, w, workers);
    rows(0, workers);
    for (std::thread& th : pool) th.join();
    return t;
}

}  // namespace

far_shadow_table far_shadow_nodes(const scene& s, float reach) {
    far_shadow_table t;
    const glm::vec2 band = cloud_band(s);
    t.alt_lo = band.x;
    t.alt_hi = band.y;
    t.reach = reach;
    // Below mu_lo a path from the band's top meets the ground; above mu_hi a straight path
    // from the band's bottom to its top (curvature only shortens it) is within the reach.
    const float R = s.planet_radius, top = R + t.alt_hi;
    t.mu_lo = -std::sqrt(std::max(1.0f - (R / top) * (R / top), 0.0f));
    t.mu_hi = std::min((t.alt_hi - t.alt_lo) / std::max(reach, 1.0f), 1.0f);
    return t;
}

std::vector<float> far_shadow_scene_key(const scene& s, const glm::vec3& sun, float reach) {
    return {s.camera_altitude, s.planet_radius, s.layer_bottom, s.layer_top, sun.x, sun.y, sun.z,
            s.coverage, s.cloud_type, s.extinction, s.base_tile, s.detail_tile, s.weather_tile,
            s.shape == cloud_shape::classic ? 0.0f : 1.0f, s.weather_wide_tile, s.curl_tile,
            s.curl_strength, s.type_spread, s.top_rounding, s.density_scale, reach};
}

std::shared_ptr<const far_shadow_table> far_shadow(const scene& s, const glm::vec3& sun, const cloud_textures& t, float reach,
                                                   cpu_sky_tables& tables) {
    // Everything the table depends on: geometry, sun, the field's parameters and textures.
    std::uint32_t bytes = 2166136261u;  // FNV-1a over the weather maps: which textures
    for (const std::vector<std::uint8_t>* v : {&t.weather, &t.weather_wide})
        for (std::size_t i = 0; i < v->size(); i += 61) bytes = (bytes ^ (*v)[i]) * 16777619u;
    std::vector<float> key = far_shadow_scene_key(s, sun, reach);
    key.insert(key.end(), {float(t.base_size), float(t.detail_size), float(t.weather_size), float(bytes & 0xffffu), float(bytes >> 16)});
    return tables.made_once<far_shadow_table>(key, [&] { return make_table(s, sun, t, reach); });
}

float far_shadow_lookup(const far_shadow_table& t, float altitude, float mu) {
    const float x = cm::saturate((altitude - t.alt_lo) / (t.alt_hi - t.alt_lo)) * float(t.n_alt - 1);
    const float y = cm::saturate((mu - t.mu_lo) / (t.mu_hi - t.mu_lo)) * float(t.n_mu - 1);
    // floor_to_int: a NaN altitude or cosine reads node 0, never an undefined int conversion.
    const int i = cm::detail::floor_to_int(x, 0, t.n_alt - 2), j = cm::detail::floor_to_int(y, 0, t.n_mu - 2);
    const float fx = std::clamp(x - float(i), 0.0f, 1.0f), fy = std::clamp(y - float(j), 0.0f, 1.0f);
    const auto at = [&](int a, int m) { return t.texels[static_cast<std::size_t>(m * t.n_alt + a)]; };
    const float lower = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
    const float upper = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
    return lower + (upper - lower) * fy;
}

}  // namespace cloud_renderer
