#include "cpu_renderer.hpp"

#include <cloudmath/cloudmath.hpp>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace cloud_renderer {
namespace {

namespace cm = cloudmath;
using glm::vec2;
using glm::vec3;
using glm::vec4;

// OpenGL's GL_REPEAT wrap of an integer texel index.
int wrap(int i, int size) {
    const int m = i % size;
    return m < 0 ? m + size : m;
}

// texture() of a UNORM8 texture with GL_LINEAR filtering and GL_REPEAT: texel centres at
// (i + 0.5) / size, weights from the fractional part, value byte / 255.
struct linear_texture {
    const std::uint8_t* data;
    int size, channels;

    float texel(int x, int y, int z, int c) const {
        const std::size_t i = ((static_cast<std::size_t>(z) * static_cast<std::size_t>(size) + static_cast<std::size_t>(y)) *
                                   static_cast<std::size_t>(size) +
                               static_cast<std::size_t>(x)) *
                                  static_cast<std::size_t>(channels) +
                              static_cast<std::size_t>(c);
        return float(data[i]) * (1.0f / 255.0f);
    }
    vec4 sample3(vec3 uvw) const {
        const vec3 x = uvw * float(size) - 0.5f;
        const vec3 f0 = glm::floor(x);
        const vec3 f = x - f0;
        const int x0 = wrap(int(f0.x), size), y0 = wrap(int(f0.y), size), z0 = wrap(int(f0.z), size);
        const int x1 = wrap(x0 + 1, size), y1 = wrap(y0 + 1, size), z1 = wrap(z0 + 1, size);
        vec4 out(0.0f);
        for (int c = 0; c < channels; ++c) {
            const float c00 = glm::mix(texel(x0, y0, z0, c), texel(x1, y0, z0, c), f.x);
            const float c10 = glm::mix(texel(x0, y1, z0, c), texel(x1, y1, z0, c), f.x);
            const float c01 = glm::mix(texel(x0, y0, z1, c), texel(x1, y0, z1, c), f.x);
            const float c11 = glm::mix(texel(x0, y1, z1, c), texel(x1, y1, z1, c), f.x);
            out[c] = glm::mix(glm::mix(c00, c10, f.y), glm::mix(c01, c11, f.y), f.z);
        }
        return out;
    }
    vec4 sample2(vec2 uv) const {
        const vec2 x = uv * float(size) - 0.5f;
        const vec2 f0 = glm::floor(x);
        const vec2 f = x - f0;
        const int x0 = wrap(int(f0.x), size), y0 = wrap(int(f0.y), size);
        const int x1 = wrap(x0 + 1, size), y1 = wrap(y0 + 1, size);
        vec4 out(0.0f);
        for (int c = 0; c < channels; ++c)
            out[c] = glm::mix(glm::mix(texel(x0, y0, 0, c), texel(x1, y0, 0, c), f.x),
                              glm::mix(texel(x0, y1, 0, c), texel(x1, y1, 0, c), f.x), f.y);
        return out;
    }
};

// The shader's functions (cr_*), with the uniforms as members.
struct pixel_program {
    const scene& s;
    const variant& v;
    frame_constants k;
    linear_texture base, detail, weather;
    cm::mie_approx_parameters<float> mie;

    pixel_program(const scene& sc, const variant& va, const cloud_textures& t)
        : s(sc), v(va), k(make_frame_constants(sc)), base{t.base.data(), t.base_size, 4},
          detail{t.detail.data(), t.detail_size, 3}, weather{t.weather.data(), t.weather_size, 3},
          mie(cm::mie_approx_params(k.droplet_diameter)) {}

    float altitude(vec3 p) const {
        const float t = glm::length(p);
        return t > 0.0f ? cm::altitude_along_ray(s.camera_altitude, p.y / t, s.planet_radius, t) : s.camera_altitude;
    }

    float density(vec3 p, float alt) const {
        const float h = cm::height_fraction(alt, s.layer_bottom, s.layer_top);
        if (h <= 0.0f || h >= 1.0f) return 0.0f;
        const vec3 q(p.x + s.wind.x, alt, p.z + s.wind.y);
        const float coverage = cm::saturate(weather.sample2(vec2(q.x, q.z) / s.weather_tile).r - 0.5f + s.coverage);
        const vec4 b = base.sample3(q / s.base_tile);
        const float shaped = cm::nubis_base_cloud(b) * cm::height_gradient_for_type(h, s.cloud_type);
        const float covered = cm::apply_coverage(shaped, coverage);
        if (covered <= 0.0f) return 0.0f;
        const vec3 d = vec3(detail.sample3(q / s.detail_tile));
        return cm::erode(covered, cm::nubis_detail_erosion(d, h));
    }

    float cone_extinction(vec3 p) const { return s.extinction * density(p, altitude(p)); }

    float phase(float mu, float scale) const {
        switch (v.phase) {
        case phase_model::hg: return cm::phase_hg(mu, scale * k.phase_g);
        case phase_model::dual_hg: return cm::phase_hg_dual(mu, scale * k.phase_g, scale * k.phase_g_back, k.phase_w);
        case phase_model::cornette_shanks: return cm::phase_cornette_shanks(mu, scale * k.phase_g);
        case phase_model::mie: break;
        }
        cm::mie_approx_parameters<float> m = mie;
        m.g_hg *= scale;
        m.g_draine *= scale;
        return cm::phase_mie_approx(mu, m);
    }

    float light_optical_depth(vec3 p, float alt) const {
        if (v.light == light_mode::cone) {
            const cm::cone_light_config<float> cone{v.cone_samples, k.cone_step, k.cone_spread, k.cone_far_distance,
                                                    k.cone_far_length};
            return cm::cone_optical_depth(p, k.sun_dir, cone, [this](const vec3& q) { return cone_extinction(q); });
        }
        const vec3 up = glm::normalize(vec3(p.x, p.y + (s.planet_radius + s.camera_altitude), p.z));
        const vec2 seg = cm::cloud_layer_segment(alt, glm::dot(k.sun_dir, up), s.planet_radius, s.layer_bottom, s.layer_top);
        const float length_to_exit = seg.y > seg.x ? std::min(seg.y, k.light_march_max) : 0.0f;
        const float ds = length_to_exit / float(v.light_steps);
        float tau = 0.0f;
        for (int i = 0; i < v.light_steps; ++i) tau += cone_extinction(p + k.sun_dir * ((float(i) + 0.5f) * ds)) * ds;
        return tau;
    }

    vec3 in_scattering(float tau_light, float mu, float h) const {
        float sun = cm::multiple_scattering_with(tau_light, mu, k.ms_a, k.ms_b, k.ms_c, v.octaves,
                                                 [this](float m, float scale) { return phase(m, scale); });
        if (v.powder) sun *= glm::mix(2.0f * cm::powder(tau_light, 2.0f), 1.0f, 0.5f + 0.5f * mu);
        return k.sun_radiance * sun + glm::mix(k.ambient_bottom, k.ambient_top, h);
    }

    vec3 background(vec3 dir) const {
        const vec2 ground = cm::ray_sphere_intersect_altitude(s.camera_altitude, dir.y, s.planet_radius, 0.0f);
        if (ground.x >= 0.0f && ground.y > ground.x) return k.ground;
        const float mu = glm::dot(dir, k.sun_dir);
        vec3 sky = glm::mix(k.sky_horizon, k.sky_zenith, std::sqrt(cm::saturate(dir.y)));
        sky += k.sun_radiance * (0.05f * cm::phase_hg(mu, 0.75f));
        if (mu >= k.sun_cos_radius) sky += k.sun_radiance * 4.0f;
        return sky;
    }

    vec3 tonemap(vec3 c) const { return glm::pow(vec3(1.0f) - glm::exp(-c * s.exposure), vec3(1.0f / 2.2f)); }

    static float jitter(int x, int y) {
        const std::uint32_t h = cm::noise_hash(static_cast<std::uint32_t>(x) + static_cast<std::uint32_t>(y) * 8192u);
        return float(h >> 8u) * (1.0f / 16777216.0f);
    }

    // main() of the shader for the pixel whose centre is (x + 0.5, y + 0.5).
    vec4 shade(int x, int y, int width, int height) const {
        const vec2 ndc = vec2(float(x) + 0.5f, float(y) + 0.5f) / vec2(float(width), float(height)) * 2.0f - 1.0f;
        const float aspect = float(width) / float(height);
        const vec3 dir = glm::normalize(k.forward + k.right * (ndc.x * aspect * k.tan_half_fov) + k.up * (ndc.y * k.tan_half_fov));

        cm::march_accumulator<vec3, vec3> acc;
        const vec2 seg = cm::cloud_layer_segment(s.camera_altitude, dir.y, s.planet_radius, s.layer_bottom, s.layer_top);
        if (seg.y > seg.x) {
            const float t1 = std::min(seg.y, seg.x + s.max_distance);
            const float ds = (t1 - seg.x) / float(v.view_steps);
            const float offset = v.jitter ? jitter(x, y) : 0.5f;
            const float mu = glm::dot(dir, k.sun_dir);
            for (int i = 0; i < v.view_steps; ++i) {
                const float t = seg.x + (float(i) + offset) * ds;
                const float alt = cm::altitude_along_ray(s.camera_altitude, dir.y, s.planet_radius, t);
                const float d = density(dir * t, alt);
                if (d <= 0.0f) continue;
                const float sigma_t = s.extinction * d;
                const float tau_light = light_optical_depth(dir * t, alt);
                const float h = cm::height_fraction(alt, s.layer_bottom, s.layer_top);
                const vec3 S = (s.albedo * sigma_t) * in_scattering(tau_light, mu, h);
                if (v.integration == integration_mode::analytic) {
                    acc.add_segment(S, sigma_t, ds);
                } else {
                    acc.luminance += acc.transmittance * S * ds;  // the textbook Riemann sum
                    acc.transmittance *= cm::beer_lambert(sigma_t * ds);
                }
                if (acc.is_opaque(k.min_transmittance)) break;
            }
        }
        const vec3 color = background(dir) * acc.transmittance + acc.luminance;
        const vec3 t = acc.transmittance;
        return vec4(tonemap(color), 1.0f - (t.r + t.g + t.b) / 3.0f);
    }
};

}  // namespace

image render_cpu(const scene& s, const variant& v, const cloud_textures& textures, int width, int height, unsigned threads) {
    image img;
    img.width = width;
    img.height = height;
    img.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), vec4(0.0f));
    const pixel_program program(s, v, textures);
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::atomic<int> next_row{0};
    const auto work = [&] {
        for (int y; (y = next_row.fetch_add(1)) < height;)
            for (int x = 0; x < width; ++x) img.at(x, y) = program.shade(x, y, width, height);
    };
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    return img;
}

}  // namespace cloud_renderer
