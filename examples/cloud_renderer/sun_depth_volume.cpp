// sun_depth_volume.cpp: see sun_depth_volume.hpp.
#include "sun_depth_volume.hpp"

#include "cloud_density.hpp"
#include "physical_sky.hpp"

#include <cloudmath/cloudmath.hpp>

#include <algorithm>
#include <cmath>
#include <thread>

namespace cloud_renderer {
namespace {

namespace cm = cloudmath;

// Metres per step of the sweep's stretches (at most; the node spacing if smaller).
constexpr float build_step = 100.0f;
using glm::vec2;
using glm::vec3;

// Bilinear value of slice a at (u, w); 0 beyond the last node toward the sun (the path left
// the volume there: its clouds are not counted), clamped at the other sides.
float slice_at(const sun_depth_volume& v, int a, float u, float w) {
    const float x = (u - v.u0) / v.spacing_u, y = (w - v.w0) / v.spacing;
    if (!(x <= float(v.nu - 1))) return v.transmittance ? 1.0f : 0.0f;
    const float xc = std::clamp(x, 0.0f, float(v.nu - 1)), yc = std::clamp(y, 0.0f, float(v.nw - 1));
    const int i = std::min(int(xc), v.nu - 2), j = std::min(int(yc), v.nw - 2);
    const float fx = xc - float(i), fy = yc - float(j);
    const auto at = [&](int ii, int jj) {
        return v.depth[(static_cast<std::size_t>(a) * static_cast<std::size_t>(v.nw) + static_cast<std::size_t>(jj)) *
                           static_cast<std::size_t>(v.nu) + static_cast<std::size_t>(ii)];
    };
    const float lower = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
    const float upper = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
    return lower + (upper - lower) * fy;
}

sun_depth_volume make_volume(const scene& s, const vec3& sun_dir, const cloud_textures& textures, float spacing,
                             float spacing_u, bool transmittance) {
    sun_depth_volume v;
    const vec2 band = cloud_band(s);
    v.alt_lo = band.x;
    v.alt_hi = band.y;
    v.spacing = spacing;
    const vec2 horizontal(sun_dir.x, sun_dir.z);
    v.eu = glm::length(horizontal) > 1e-6f ? horizontal / glm::length(horizontal) : vec2(1.0f, 0.0f);
    v.ew = vec2(-v.eu.y, v.eu.x);
    // The view's reach (the layer entered where a level ray meets it, then max_distance), and toward the
    // sun as far as a path from the band's far side can run inside it (at most 200 km).
    const double Rb = double(s.planet_radius) + double(band.x), Rc = double(s.planet_radius) + double(s.camera_altitude);
    const float horizon = float(std::sqrt(std::max(Rb * Rb - Rc * Rc, 0.0)));  // a level ray meets the band's bottom
    const float reach = horizon + s.max_distance + 10000.0f;
    const float sine = std::max(std::fabs(sun_dir.y), 0.02f);
    const float ahead = std::min((band.y - band.x) / sine, 200000.0f);
    v.u0 = -reach;
    v.w0 = -reach;
    // Along the sun's azimuth, nodes spacing_u apart (1 km by default): a slice's value between
    // them mixes paths that start up to spacing_u / 2 earlier or later along the sun.
    v.spacing_u = spacing_u;
    v.nu = int(std::ceil((2.0f * reach + ahead) / v.spacing_u)) + 1;
    v.nw = int(std::ceil(2.0f * reach / spacing)) + 1;
    v.na = std::clamp(int(std::ceil((band.y - band.x) / (0.5f * spacing))) + 1, 2, 256);
    v.transmittance = transmittance;
    v.depth.assign(static_cast<std::size_t>(v.nu) * static_cast<std::size_t>(v.nw) * static_cast<std::size_t>(v.na),
                   transmittance ? 1.0f : 0.0f);

    const cloud_density field(s, textures);
    const double R = double(s.planet_radius), r0 = R + double(s.camera_altitude);
    const bool rising = sun_dir.y >= 0.0f;
    const float step = std::min(spacing, build_step);
    const auto alt_of = [&](int a) { return v.alt_lo + (v.alt_hi - v.alt_lo) * float(a) / float(v.na - 1); };
    const int exit_slice = rising ? v.na - 1 : 0, dir = rising ? -1 : 1;
    for (int a = exit_slice + dir; a >= 0 && a < v.na; a += dir) {
        const int next = a - dir;
        const double alt = double(alt_of(a)), alt_next = double(alt_of(next));
        const auto rows = [&](int first, int stride) {
            for (int j = first; j < v.nw; j += stride)
                for (int i = 0; i < v.nu; ++i) {
                    const float u = v.u0 + float(i) * v.spacing_u, w = v.w0 + float(j) * spacing;
                    const vec2 xz = v.eu * u + v.ew * w;
                    const double rr = (R + alt) * (R + alt) - double(xz.x) * double(xz.x) - double(xz.y) * double(xz.y);
                    float value = v.transmittance ? 1.0f : 0.0f;
                    if (rr > 0.0) {
                        // Q: the node from the planet's centre; the path reaches radius R + alt_next
                        // at s: s^2 + 2 b s + c = 0, c = (alt - alt_next)(2R + alt + alt_next).
                        const double qx = double(xz.x), qy = std::sqrt(rr), qz = double(xz.y);
                        const double b = qx * double(sun_dir.x) + qy * double(sun_dir.y) + qz * double(sun_dir.z);
                        const double c = (alt - alt_next) * (2.0 * R + alt + alt_next);
                        const double disc = b * b - c;
                        double length = -1.0;
                        if (disc >= 0.0) {
                            const double root = std::sqrt(disc);
                            // rising: c < 0, the one positive root; falling: c > 0, the nearer
                            // positive root when b < 0 (c / (-b + root), free of cancellation).
                            if (c < 0.0) length = -b + root;
                            else if (b < 0.0) length = c / (-b + root);
                        }
                        const vec3 p(xz.x, float(qy - r0), xz.y);
                        if (length > 0.0) {
                            const int n = std::max(1, int(std::ceil(length / double(step))));
                            const float ds = float(length / double(n));
                            float tau = 0.0f;
                            for (int m = 0; m < n; ++m) {
                                const vec3 q = p + sun_dir * ((float(m) + 0.5f) * ds);
                                tau += s.extinction * field.density(q) * ds;
                            }
                            const vec3 land = p + sun_dir * float(length);
                            const vec2 lxz(land.x, land.z);
                            const float beyond = slice_at(v, next, glm::dot(lxz, v.eu), glm::dot(lxz, v.ew));
                            value = v.transmittance ? std::exp(-tau) * beyond : tau + beyond;
                        } else {
                            // The path turns before the next slice (a falling path that climbs
                            // back): march it to where it leaves the band.
                            const float mu = float(b / (R + alt));
                            const vec2 seg = cm::cloud_layer_segment(float(alt), mu, s.planet_radius, v.alt_lo, v.alt_hi);
                            const float span = seg.y > seg.x ? seg.y : 0.0f;
                            const int n = std::max(1, int(std::ceil(span / step)));
                            const float ds = span / float(n);
                            for (int m = 0; m < n; ++m) value += s.extinction * field.density(p + sun_dir * ((float(m) + 0.5f) * ds)) * ds;
                            if (v.transmittance) value = std::exp(-value);
                        }
                    }
                    v.depth[(static_cast<std::size_t>(a) * static_cast<std::size_t>(v.nw) + static_cast<std::size_t>(j)) *
                                static_cast<std::size_t>(v.nu) + static_cast<std::size_t>(i)] = value;
                }
        };
        const int workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        std::vector<std::thread> pool;
        for (int t = 1; t < workers; ++t) pool.emplace_back(rows, t, workers);
        rows(0, workers);
        for (std::thread& th : pool) th.join();
    }
    return v;
}

}  // namespace

const sun_depth_volume& sun_depth(const scene& s, const glm::vec3& sun, const cloud_textures& t, float spacing,
                                  float spacing_u, bool transmittance) {
    const std::vector<float> key{s.camera_altitude, s.planet_radius, s.layer_bottom, s.layer_top, sun.x, sun.y, sun.z,
                                 s.coverage, s.cloud_type, s.extinction, s.base_tile, s.detail_tile, s.weather_tile,
                                 s.shape == cloud_shape::classic ? 0.0f : 1.0f, s.weather_wide_tile, s.curl_tile,
                                 s.curl_strength, s.type_spread, s.top_rounding, s.density_scale, s.max_distance, spacing, spacing_u, transmittance ? 1.0f : 0.0f,
                                 float(t.base_size), float(t.detail_size), float(t.weather_size)};
    return made_once<sun_depth_volume>(key, [&] { return make_volume(s, sun, t, spacing, spacing_u, transmittance); });
}

float sun_depth_lookup(const sun_depth_volume& v, const glm::vec3& p, float alt) {
    if (!(alt >= v.alt_lo && alt <= v.alt_hi)) return v.transmittance ? 1.0f : 0.0f;
    const vec2 xz(p.x, p.z);
    const float u = glm::dot(xz, v.eu), w = glm::dot(xz, v.ew);
    const float z = (alt - v.alt_lo) / (v.alt_hi - v.alt_lo) * float(v.na - 1);
    const int a = std::min(int(z), v.na - 2);
    const float fz = z - float(a);
    const float lower = slice_at(v, a, u, w), upper = slice_at(v, a + 1, u, w);
    return lower + (upper - lower) * fz;
}

glm::vec2 sun_depth_next_slice(const sun_depth_volume& v, const glm::vec3& p, float alt, const glm::vec3& sun_dir, float R,
                               float r0) {
    const bool rising = sun_dir.y >= 0.0f;
    const float z = (alt - v.alt_lo) / (v.alt_hi - v.alt_lo) * float(v.na - 1);
    // The first slice strictly beyond p toward the sun's side of the band.
    const int a = rising ? int(std::floor(z)) + 1 : int(std::ceil(z)) - 1;
    if (a < 0 || a >= v.na) return {0.0f, -1.0f};
    const double alt_next = double(v.alt_lo) + double(v.alt_hi - v.alt_lo) * double(a) / double(v.na - 1);
    const double qx = double(p.x), qy = double(p.y) + double(r0), qz = double(p.z);
    const double b = qx * double(sun_dir.x) + qy * double(sun_dir.y) + qz * double(sun_dir.z);
    const double c = (double(alt) - alt_next) * (2.0 * double(R) + double(alt) + alt_next);
    const double disc = b * b - c;
    if (disc < 0.0) return {0.0f, -1.0f};
    const double root = std::sqrt(disc);
    const double length = c < 0.0 ? -b + root : b < 0.0 ? c / (-b + root) : -1.0;
    if (!(length >= 0.0)) return {0.0f, -1.0f};
    return {float(length), float(a)};
}

float sun_depth_on_slice(const sun_depth_volume& v, int a, const glm::vec3& p) {
    const vec2 xz(p.x, p.z);
    return slice_at(v, a, glm::dot(xz, v.eu), glm::dot(xz, v.ew));
}

}  // namespace cloud_renderer
