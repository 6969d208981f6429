// physical_sky.cpp: see physical_sky.hpp.
#include "physical_sky.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace cloud_renderer {
namespace {

constexpr float pi = 3.14159265358979f;

std::atomic<int> cpu_builds{0};  // cpu_sky_table_builds

// The haze table's coordinates of a direction and distance (physical_sky.hpp), as clouds.frag's
// cr_haze computes them.
glm::vec3 coordinates(const haze_table& t, const glm::vec3& dir, const glm::vec3& sun_dir, float distance) {
    const glm::vec2 c = sky_coordinates(dir, sun_dir);
    const float d = std::sqrt(std::clamp(distance / t.max_distance, 0.0f, 1.0f)) * float(t.n_d - 1);
    return {d, c.x * float(t.n_az - 1), c.y * float(t.n_el - 1)};
}

// The direction of node (az, el) of a table of n_az x n_el directions (sky_coordinates's
// inverse), the sun at azimuth 0: only its elevation matters.
glm::vec3 node_direction(int az, int el, int n_az, int n_el) {
    const float s = 2.0f * float(el) / float(n_el - 1) - 1.0f;  // sign(mu) sqrt|mu|
    const float mu = std::copysign(s * s, s);
    const float sin_zenith = std::sqrt(std::max(1.0f - mu * mu, 0.0f));
    const float phi = pi * float(az) / float(n_az - 1);
    return {sin_zenith * std::cos(phi), mu, sin_zenith * std::sin(phi)};
}


haze_table make_table(float camera_altitude, const glm::vec3& sun_dir) {
    const physical_air& a = earth_air();
    ++cpu_builds;
    haze_table t;
    t.texels.resize(static_cast<std::size_t>(t.n_d * t.n_az * t.n_el));
    const glm::vec3 sun = sun_at_azimuth_zero(sun_dir);
    for (int j = 0; j < t.n_el; ++j) {
        for (int i = 0; i < t.n_az; ++i) {
            const glm::vec3 dir = node_direction(i, j, t.n_az, t.n_el);
            for (int k = 0; k < t.n_d; ++k) {
                const float x = float(k) / float(t.n_d - 1);
                const float d = t.max_distance * x * x;
                const glm::vec3 L =
                    k == 0 ? glm::vec3(0.0f)
                           : sun_lux * cloudmath::atmosphere_inscatter(a.air, a.ms, camera_altitude, dir, sun, d, 16, 16).radiance;
                t.texels[static_cast<std::size_t>(j * t.n_d * t.n_az + i * t.n_d + k)] = L;
            }
        }
    }
    return t;
}

sky_view_table make_sky_view(float altitude, const glm::vec3& sun_dir) {
    const physical_air& a = earth_air();
    ++cpu_builds;
    sky_view_table t;
    t.texels.resize(static_cast<std::size_t>(t.n_az * t.n_el));
    const glm::vec3 sun = sun_at_azimuth_zero(sun_dir);
    for (int j = 0; j < t.n_el; ++j)
        for (int i = 0; i < t.n_az; ++i)
            t.texels[static_cast<std::size_t>(j * t.n_az + i)] =
                sun_lux * cloudmath::atmosphere_sky_radiance(a.air, a.ms, altitude, node_direction(i, j, t.n_az, t.n_el), sun);
    return t;
}

}  // namespace

int cpu_sky_table_builds() { return cpu_builds.load(); }

glm::vec3 sun_at_azimuth_zero(const glm::vec3& sun_dir) {
    return {std::sqrt(std::max(1.0f - sun_dir.y * sun_dir.y, 0.0f)), sun_dir.y, 0.0f};
}

glm::vec2 sky_coordinates(const glm::vec3& dir, const glm::vec3& sun_dir) {
    const float mu = std::clamp(dir.y, -1.0f, 1.0f);
    const float el = 0.5f + 0.5f * std::copysign(std::sqrt(std::fabs(mu)), mu);
    const float h = std::sqrt(dir.x * dir.x + dir.z * dir.z), hs = std::sqrt(sun_dir.x * sun_dir.x + sun_dir.z * sun_dir.z);
    const float cos_phi = h > 1e-6f && hs > 1e-6f ? std::clamp((dir.x * sun_dir.x + dir.z * sun_dir.z) / (h * hs), -1.0f, 1.0f) : 1.0f;
    return {std::acos(cos_phi) / pi, el};
}

cpu_sky_tables& shared_cpu_sky_tables() {
    static cpu_sky_tables tables;
    return tables;
}

std::shared_ptr<const sky_view_table> physical_sky_view(float altitude, const glm::vec3& sun_dir, cpu_sky_tables& tables) {
    return tables.made_once<sky_view_table>({altitude, sun_dir.x, sun_dir.y, sun_dir.z}, [&] { return make_sky_view(altitude, sun_dir); });
}

glm::vec3 sky_view_lookup(const sky_view_table& t, const glm::vec3& dir, const glm::vec3& sun_dir) {
    const glm::vec2 c = sky_coordinates(dir, sun_dir) * glm::vec2(float(t.n_az - 1), float(t.n_el - 1));
    // floor_to_int: a NaN direction reads node 0, never an undefined int conversion.
    const int a0 = cloudmath::detail::floor_to_int(c.x, 0, t.n_az - 2), e0 = cloudmath::detail::floor_to_int(c.y, 0, t.n_el - 2);
    const float fa = std::clamp(c.x - float(a0), 0.0f, 1.0f), fe = std::clamp(c.y - float(e0), 0.0f, 1.0f);
    const auto at = [&](int az, int el) { return t.texels[static_cast<std::size_t>(el * t.n_az + az)]; };
    return glm::mix(glm::mix(at(a0, e0), at(a0 + 1, e0), fa), glm::mix(at(a0, e0 + 1), at(a0 + 1, e0 + 1), fa), fe);
}

sky_hemisphere upper_hemisphere(const sky_view_table& t, const glm::vec3& sun_dir) {
    constexpr int n = 64;
    const glm::vec3 sun = sun_at_azimuth_zero(sun_dir);
    sky_hemisphere h;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float c = (float(j) + 0.5f) / float(n), sn = std::sqrt(1.0f - c * c);
            const float phi = (float(i) + 0.5f) / float(n) * pi;
            const glm::vec3 L = sky_view_lookup(t, glm::vec3(sn * std::cos(phi), c, sn * std::sin(phi)), sun);
            h.mean_radiance += L;
            h.irradiance += L * c;
        }
    h.mean_radiance /= float(n * n);                      // (1 / 2 pi) integral of L over the hemisphere
    h.irradiance *= 2.0f * pi / float(n * n);  // integral of L cos over it
    return h;
}

const physical_air& earth_air() {
    static const physical_air a;
    return a;
}

std::shared_ptr<const haze_table> physical_haze(float camera_altitude, const glm::vec3& sun_dir, cpu_sky_tables& tables) {
    return tables.made_once<haze_table>({camera_altitude, sun_dir.x, sun_dir.y, sun_dir.z},
                                        [&] { return make_table(camera_altitude, sun_dir); });
}

glm::vec3 haze_lookup(const haze_table& t, const glm::vec3& dir, const glm::vec3& sun_dir, float distance) {
    const glm::vec3 c = coordinates(t, dir, sun_dir, distance);
    // floor_to_int: a NaN direction or distance reads node 0, never an undefined int conversion.
    const int d0 = cloudmath::detail::floor_to_int(c.x, 0, t.n_d - 2), a0 = cloudmath::detail::floor_to_int(c.y, 0, t.n_az - 2),
              e0 = cloudmath::detail::floor_to_int(c.z, 0, t.n_el - 2);
    const float fd = std::clamp(c.x - float(d0), 0.0f, 1.0f), fa = std::clamp(c.y - float(a0), 0.0f, 1.0f),
                fe = std::clamp(c.z - float(e0), 0.0f, 1.0f);
    const auto at = [&](int d, int az, int el) {
        return t.texels[static_cast<std::size_t>(el * t.n_d * t.n_az + az * t.n_d + d)];
    };
    const auto row = [&](int az, int el) { return glm::mix(at(d0, az, el), at(d0 + 1, az, el), fd); };
    const glm::vec3 lower = glm::mix(row(a0, e0), row(a0 + 1, e0), fa);
    const glm::vec3 upper = glm::mix(row(a0, e0 + 1), row(a0 + 1, e0 + 1), fa);
    return glm::mix(lower, upper, fe);
}

}  // namespace cloud_renderer
