#include "cloud_density.hpp"

#include "physical_sky.hpp"

#include <cloudmath/cloudmath.hpp>
#include <cloudmath/noise_bake.hpp>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstddef>

namespace cloud_renderer {
namespace {

namespace cm = cloudmath;
using glm::vec2;
using glm::vec3;
using glm::vec4;

}  // namespace

float linear_texture::texel(int x, int y, int z, int c) const {
    const std::size_t i = ((static_cast<std::size_t>(z) * static_cast<std::size_t>(size) + static_cast<std::size_t>(y)) *
                               static_cast<std::size_t>(size) +
                           static_cast<std::size_t>(x)) *
                              static_cast<std::size_t>(channels) +
                          static_cast<std::size_t>(c);
    return float(data[i]) * (1.0f / 255.0f);
}

// GL_LINEAR with GL_REPEAT: cloudmath's texture_trilinear_repeat over this texture's bytes.
vec4 linear_texture::texel4(int x, int y, int z) const {
    // One address for the texel's channels (texel() per channel recomputed it: this is the
    // density's inner loop in the path tracer); the same bytes / 255 as texel().
    const std::uint8_t* t = data + ((static_cast<std::size_t>(z) * static_cast<std::size_t>(size) + static_cast<std::size_t>(y)) *
                                        static_cast<std::size_t>(size) +
                                    static_cast<std::size_t>(x)) *
                                       static_cast<std::size_t>(channels);
    constexpr float scale = 1.0f / 255.0f;
    switch (channels) {
    case 4: return vec4(float(t[0]) * scale, float(t[1]) * scale, float(t[2]) * scale, float(t[3]) * scale);
    case 3: return vec4(float(t[0]) * scale, float(t[1]) * scale, float(t[2]) * scale, 0.0f);
    default: {
        vec4 v(0.0f);
        for (int c = 0; c < channels; ++c) v[c] = float(t[c]) * scale;
        return v;
    }
    }
}

vec4 linear_texture::sample3(vec3 uvw) const {
    return cm::texture_trilinear_repeat(uvw, glm::ivec3(size), [this](int x, int y, int z) { return texel4(x, y, z); });
}

vec4 linear_texture::sample2(vec2 uv) const {
    return cm::texture_bilinear_repeat(uv, glm::ivec2(size), [this](int x, int y) { return texel4(x, y, 0); });
}

cloud_density::cloud_density(const scene& s, const cloud_textures& t)
    : s_(s), base_{t.base.data(), t.base_size, 4},
      detail_{t.detail.data(), t.detail_size, 3},
      weather_{t.weather.data(), t.weather_size, 3},
      weather_wide_{t.weather_wide.data(), t.weather_wide_size, 3},
      curl_{t.curl.data(), t.curl_size, 3} {}

float cloud_density::altitude(vec3 p) const { return cm::point_altitude(p, s_.camera_altitude, s_.planet_radius); }

float cloud_density::base_density(vec3 p, float alt, long* texture_reads) const {
    const float h = cm::height_fraction(alt, s_.layer_bottom, s_.layer_top);
    if (h <= 0.0f || h >= 1.0f) return 0.0f;
    if (texture_reads) *texture_reads += 2;
    const vec3 q(p.x + s_.wind.x, alt, p.z + s_.wind.y);
    if (s_.shape == cloud_shape::detailed) {
        const vec3 w = vec3(weather_wide_.sample2(vec2(q.x, q.z) / s_.weather_wide_tile));
        const vec4 b = base_.sample3(q / s_.base_tile);
        return cm::cloud_shape_density(b, w, h, s_.coverage, s_.cloud_type, s_.type_spread, s_.top_rounding);
    }
    const float coverage = cm::saturate(weather_.sample2(vec2(q.x, q.z) / s_.weather_tile).r - 0.5f + s_.coverage);
    const vec4 b = base_.sample3(q / s_.base_tile);
    const float shaped = cm::nubis_base_cloud(b) * cm::height_gradient_for_type(h, s_.cloud_type);
    return cm::apply_coverage(shaped, coverage);
}

float cloud_density::density(vec3 p, float alt, long* texture_reads) const {
    return detail_density(p, alt, base_density(p, alt, texture_reads), texture_reads);
}

float cloud_density::detail_density(vec3 p, float alt, float covered, long* texture_reads) const {
    if (covered <= 0.0f) return 0.0f;
    if (texture_reads) *texture_reads += 1;
    const float h = cm::height_fraction(alt, s_.layer_bottom, s_.layer_top);
    vec3 q(p.x + s_.wind.x, alt, p.z + s_.wind.y);
    if (s_.shape == cloud_shape::detailed) {
        // Curl noise displaces the detail, most at the cloud's base (wispy bases, billowy tops).
        if (texture_reads) *texture_reads += 1;
        const vec3 c = vec3(curl_.sample2(vec2(q.x, q.z) / s_.curl_tile));
        const vec3 curl(cm::curl_bake_decode(c.x), cm::curl_bake_decode(c.y), cm::curl_bake_decode(c.z));
        q += curl * (s_.curl_strength * (1.0f - h));
        const vec3 d = vec3(detail_.sample3(q / s_.detail_tile));
        return cm::saturate(cm::erode(covered, cm::nubis_detail_erosion(d, h)) * s_.density_scale);
    }
    const vec3 d = vec3(detail_.sample3(q / s_.detail_tile));
    return cm::erode(covered, cm::nubis_detail_erosion(d, h));
}

vec3 sky_radiance(const frame_constants& k, vec3 dir, bool sun_disc) {
    const float mu = glm::dot(dir, k.sun_dir);
    vec3 sky;
    if (k.sky_view != nullptr) {
        sky = sky_view_lookup(*k.sky_view, dir, k.sun_dir);  // the physical sky: its sky-view table
    } else {
        sky = glm::mix(k.sky_horizon, k.sky_zenith, std::sqrt(cm::saturate(dir.y)));
        sky += k.sun_radiance * (k.aureole * cm::phase_hg(mu, 0.75f));
    }
    // The disc at its physical radiance: the irradiance over its solid angle, limb-darkened.
    if (sun_disc) sky += k.sun_radiance * cm::sun_disc_radiance(1.0f, mu, k.sun_angular_radius, 0.6f);
    return sky;
}

vec3 background(const scene& s, const frame_constants& k, vec3 dir, bool sun_disc) {
    const vec2 ground = cm::ray_sphere_intersect_altitude(s.camera_altitude, dir.y, s.planet_radius, 0.0f);
    if (ground.x >= 0.0f && ground.y > ground.x) return k.ground;
    return sky_radiance(k, dir, sun_disc);
}

vec3 tonemap(vec3 c, float exposure) { return glm::pow(vec3(1.0f) - glm::exp(-c * exposure), vec3(1.0f / 2.2f)); }

}  // namespace cloud_renderer
