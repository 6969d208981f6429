// tools/reference/transport/cloud_medium.cpp: the renderer's clouds for the volume path tracer; see
// cloud_medium.hpp for the scene definition and the majorant grid.
#include "cloud_medium.hpp"

#include "physical_sky.hpp"

#include <cloudmath/cloudmath.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cloudmath::reference::volume {

namespace cm = cloudmath;
namespace cr = cloud_renderer;

namespace {

float gradient(float h, float type) { return cm::height_gradient_for_type(h, type); }

int wrap(long long i, int n) {
    const long long m = i % n;
    return static_cast<int>(m < 0 ? m + n : m);
}

// Texel indices whose GL_LINEAR reads can touch texture coordinates (metres / tile) in
// [a, b], with one texel of margin on each side: [first, last] (unwrapped).
std::pair<long long, long long> texel_range(double a, double b, double tile, int size) {
    const double s = static_cast<double>(size) / tile;
    return {static_cast<long long>(std::floor(a * s - 0.5)) - 1,
            static_cast<long long>(std::floor(b * s - 0.5)) + 2};
}

// The texel index range clipped to one period when it covers all of it.
std::pair<long long, long long> clip(std::pair<long long, long long> r, int size) {
    if (r.second - r.first + 1 >= size) return {0, size - 1};
    return r;
}

// What bounds the base cloud over a set of base texels: the largest R and the smallest G,
// B and A.
struct base_extremes {
    float r = 0.0f, g = 1.0f, b = 1.0f, a = 1.0f;
    void merge(const base_extremes& o) {
        r = std::max(r, o.r);
        g = std::min(g, o.g);
        b = std::min(b, o.b);
        a = std::min(a, o.a);
    }
};

}  // namespace

cloud_medium::cloud_medium(const cr::scene& s, const cr::cloud_textures& t, double cell_size,
                           int layers)
    : scene_(s), field_(scene_, t) {
    if (!(cell_size > 0.0) || layers < 1)
        throw std::invalid_argument("cloud_medium: cell size > 0 and layers >= 1");
    if (!(scene_.layer_top > scene_.layer_bottom))
        throw std::invalid_argument("cloud_medium: the layer top must be above its bottom");
    // One period of the texture fields: the weather tile, when the base tile divides it;
    // otherwise a single cell over everything (still a bound, only slow). The detailed shape
    // (cr::cloud_shape) reads the wide weather map, whose period is 4 times longer: its
    // cells are at least 1/480 of it (500 m for 240 km), to keep the grid's memory bounded.
    const bool detailed = scene_.shape == cr::cloud_shape::detailed;
    const double period = detailed ? scene_.weather_wide_tile : scene_.weather_tile, base = scene_.base_tile;
    const double ratio = period / base;
    const bool periodic = std::abs(ratio - std::round(ratio)) < 1e-6 && ratio >= 1.0;
    period_ = period;
    if (detailed) cell_size = std::max(cell_size, period / 480.0);
    cells_ = periodic ? std::max(1, static_cast<int>(std::lround(period / cell_size))) : 1;
    cell_ = period_ / cells_;
    layers_ = layers;
    layer_height_ = (static_cast<double>(scene_.layer_top) - scene_.layer_bottom) / layers_;

    // Height gradient: its largest value over each layer from samples every `step` of the
    // height fraction, plus the Lipschitz bound times half a step.
    const float type = scene_.cloud_type;
    const int fine = 1 << 16;
    double lipschitz = 0.0;
    for (int i = 0; i < fine; ++i) {
        const float h0 = static_cast<float>(i) / fine, h1 = static_cast<float>(i + 1) / fine;
        lipschitz = std::max(lipschitz, std::abs(double(gradient(h1, type)) - gradient(h0, type)) * fine);
    }
    lipschitz *= 2.0;  // the finite differences underestimate the slope: a safety factor
    std::vector<float> gradient_max(static_cast<std::size_t>(layers_));
    const int samples = 64;
    for (int k = 0; k < layers_; ++k) {
        double g = 0.0;
        for (int i = 0; i <= samples; ++i) {
            const double h = (k + static_cast<double>(i) / samples) / layers_;
            g = std::max(g, double(gradient(static_cast<float>(h), type)));
        }
        gradient_max[static_cast<std::size_t>(k)] = static_cast<float>(std::min(1.0, g + lipschitz * 0.5 / (samples * layers_)));
        if (detailed) {
            // Per-cloud types and tops: the gradient's bound is 1 wherever the field's band
            // (cloud_band: every type and top the weather map can give) reaches, 0 elsewhere.
            const glm::vec2 band = cr::cloud_band(scene_);
            const double a0 = scene_.layer_bottom + k * layer_height_, a1 = a0 + layer_height_;
            gradient_max[static_cast<std::size_t>(k)] = a1 >= band.x && a0 <= band.y ? 1.0f : 0.0f;
        }
    }

    const cr::linear_texture& wt = detailed ? field_.weather_wide() : field_.weather();
    const cr::linear_texture& bt = field_.base();
    const double full = periodic ? cell_ : 1e12;  // non-periodic: the cell spans every texel
    const auto ucells = static_cast<std::size_t>(cells_);
    // Texel ranges of each cell along x (= along z) and of each layer along y.
    std::vector<std::pair<long long, long long>> base_x(ucells), weather_x(ucells), base_y(static_cast<std::size_t>(layers_));
    for (std::size_t i = 0; i < ucells; ++i) {
        const double x0 = static_cast<double>(i) * cell_;
        base_x[i] = clip(texel_range(x0, x0 + full, base, bt.size), bt.size);
        weather_x[i] = clip(texel_range(x0, x0 + full, detailed ? scene_.weather_wide_tile : scene_.weather_tile, wt.size), wt.size);
    }
    for (int k = 0; k < layers_; ++k) {
        const double a0 = scene_.layer_bottom + k * layer_height_;
        base_y[static_cast<std::size_t>(k)] = clip(texel_range(a0, a0 + layer_height_, base, bt.size), bt.size);
    }
    const long long y_lo = base_y.front().first, y_hi = base_y.back().second;
    const auto ny = static_cast<std::size_t>(y_hi - y_lo + 1), nb = static_cast<std::size_t>(bt.size);
    // Separable reductions of the base texels: over each cell's x range (per y, z texel),
    // then over each cell's z range, then over each layer's y range.
    std::vector<base_extremes> by_x(ucells * ny * nb), by_xz(ucells * ucells * ny);
    for (std::size_t i = 0; i < ucells; ++i)
        for (std::size_t y = 0; y < ny; ++y)
            for (std::size_t z = 0; z < nb; ++z) {
                base_extremes e;
                const int ty = wrap(y_lo + static_cast<long long>(y), bt.size), tz = static_cast<int>(z);
                for (long long x = base_x[i].first; x <= base_x[i].second; ++x) {
                    const int tx = wrap(x, bt.size);
                    e.merge({bt.texel(tx, ty, tz, 0), bt.texel(tx, ty, tz, 1), bt.texel(tx, ty, tz, 2), bt.texel(tx, ty, tz, 3)});
                }
                by_x[(i * ny + y) * nb + z] = e;
            }
    for (std::size_t j = 0; j < ucells; ++j)
        for (std::size_t i = 0; i < ucells; ++i)
            for (std::size_t y = 0; y < ny; ++y) {
                base_extremes e;
                for (long long z = base_x[j].first; z <= base_x[j].second; ++z)
                    e.merge(by_x[(i * ny + y) * nb + static_cast<std::size_t>(wrap(z, bt.size))]);
                by_xz[(j * ucells + i) * ny + y] = e;
            }
    bound_.assign(ucells * ucells * static_cast<std::size_t>(layers_), 0.0f);
    for (std::size_t j = 0; j < ucells; ++j)
        for (std::size_t i = 0; i < ucells; ++i) {
            float weather_max = 0.0f;
            for (long long z = weather_x[j].first; z <= weather_x[j].second; ++z)
                for (long long x = weather_x[i].first; x <= weather_x[i].second; ++x)
                    weather_max = std::max(weather_max, wt.texel(wrap(x, wt.size), wrap(z, wt.size), 0, 0));
            const float coverage = cm::saturate(weather_max - 0.5f + scene_.coverage) + 1e-6f;
            for (int k = 0; k < layers_; ++k) {
                base_extremes e;
                const auto& yr = base_y[static_cast<std::size_t>(k)];
                for (long long y = yr.first; y <= yr.second; ++y)
                    e.merge(by_xz[(j * ucells + i) * ny + static_cast<std::size_t>(y - y_lo)]);
                // nubis_base_cloud increases with R and decreases with the low-frequency fBm
                // of G, B, A (positive weights): its bound takes max R and min G, B, A.
                const float base_cloud = std::min(1.0f, cm::nubis_base_cloud(glm::vec4(e.r, e.g, e.b, e.a)));
                const float shaped = base_cloud * gradient_max[static_cast<std::size_t>(k)];
                // The detailed shape's coverage only shrinks with height (top rounding) and
                // its density is the eroded one times density_scale, saturated.
                const float covered = cm::apply_coverage(shaped * (1.0f + 1e-5f) + 1e-6f, coverage) *
                                      (detailed ? scene_.density_scale : 1.0f);
                bound_[(static_cast<std::size_t>(k) * ucells + j) * ucells + i] =
                    covered > 0.0f ? std::min(1.0f, covered) * (1.0f + 1e-4f) : 0.0f;
            }
        }
}

float cloud_medium::cell_bound(int i, int j, int k) const {
    return bound_[(static_cast<std::size_t>(k) * static_cast<std::size_t>(cells_) + static_cast<std::size_t>(j)) *
                      static_cast<std::size_t>(cells_) + static_cast<std::size_t>(i)];
}

double cloud_medium::altitude(const vec3& p) const {
    const double r0 = static_cast<double>(scene_.planet_radius) + scene_.camera_altitude;
    const double y = p.y + r0;
    return std::sqrt(p.x * p.x + y * y + p.z * p.z) - scene_.planet_radius;
}

double cloud_medium::density(const vec3& p) const {
    const float alt = static_cast<float>(altitude(p));
    return field_.density(glm::vec3(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)), alt);
}

double cloud_medium::extinction(const vec3& p) const { return scene_.extinction * density(p); }

double cloud_medium::density_bound(double x0, double x1, double z0, double z1, double alt0,
                                   double alt1) const {
    if (alt1 <= scene_.layer_bottom || alt0 >= scene_.layer_top) return 0.0;
    const auto range = [&](double a, double b) {
        const long long i0 = static_cast<long long>(std::floor(a / cell_));
        const long long i1 = static_cast<long long>(std::floor(b / cell_));
        return i1 - i0 + 1 >= cells_ ? std::make_pair(0LL, static_cast<long long>(cells_ - 1)) : std::make_pair(i0, i1);
    };
    const auto xi = range(x0, x1), zi = range(z0, z1);
    const int k0 = std::clamp(static_cast<int>(std::floor((alt0 - scene_.layer_bottom) / layer_height_)), 0, layers_ - 1);
    const int k1 = std::clamp(static_cast<int>(std::floor((alt1 - scene_.layer_bottom) / layer_height_)), 0, layers_ - 1);
    float m = 0.0f;
    for (int k = k0; k <= k1; ++k)
        for (long long j = zi.first; j <= zi.second; ++j)
            for (long long i = xi.first; i <= xi.second; ++i) m = std::max(m, cell_bound(wrap(i, cells_), wrap(j, cells_), k));
    return m;
}

medium_exit cloud_medium::exit(const vec3& p, const vec3& d) const {
    const double R = scene_.planet_radius;
    const double r0 = R + static_cast<double>(scene_.camera_altitude);
    const vec3 from_centre{p.x, p.y + r0, p.z};
    const double r = std::sqrt(dot(from_centre, from_centre));
    const double alt = r - R, cos_zenith = dot(from_centre, d) / r;
    const glm::dvec2 ground = cm::ray_sphere_intersect_altitude(std::max(alt, 0.0), cos_zenith, R, 0.0);
    if (ground.x >= 0.0 && ground.y > ground.x) return {ground.x, true};
    const double top = scene_.layer_top;
    const glm::dvec2 to_top = cm::ray_sphere_intersect_altitude(alt, cos_zenith, R, top);
    if (alt <= top) return {std::max(to_top.y, 0.0), false};
    return {to_top.x >= 0.0 && to_top.y > to_top.x ? to_top.y : 0.0, false};
}

void cloud_medium::majorants(const vec3& p, const vec3& d, double t_min, double t_max,
                             const majorant_visitor& visit) const {
    const double R = scene_.planet_radius;
    const double r0 = R + static_cast<double>(scene_.camera_altitude);
    const vec3 c{p.x, p.y + r0, p.z};  // p from the planet's centre
    const double rr = dot(c, c), b = dot(c, d);
    const auto alt_at = [&](double t) { return std::sqrt(std::max(0.0, rr + t * (2.0 * b + t))) - R; };
    const double closest = -b;  // altitude along the line is smallest here (convex in t)
    const double wx = p.x + static_cast<double>(scene_.wind.x), wz = p.z + static_cast<double>(scene_.wind.y);
    t_max = std::min(t_max, t_min + 1e8);
    const double step = cell_;
    double a = t_min, alt_a = alt_at(a);
    while (a < t_max) {
        const double e = std::min(t_max, a + step);
        const double alt_e = alt_at(e);
        double lo = std::min(alt_a, alt_e);
        const double hi = std::max(alt_a, alt_e);
        if (closest > a && closest < e) lo = std::min(lo, alt_at(closest));
        if (hi > scene_.layer_bottom && lo < scene_.layer_top) {
            const double xa = wx + a * d.x, xe = wx + e * d.x, za = wz + a * d.z, ze = wz + e * d.z;
            const double m = density_bound(std::min(xa, xe), std::max(xa, xe), std::min(za, ze), std::max(za, ze), lo, hi);
            if (m > 0.0 && !visit(a, e, scene_.extinction * m)) return;
        }
        a = e;
        alt_a = alt_e;
    }
}

// ---------------------------------------------------------------------------------------
lighting make_cloud_lighting(const cr::scene& s) {
    const cr::frame_constants k = cr::make_frame_constants(s);
    lighting l;
    l.sun_direction = {k.sun_dir.x, k.sun_dir.y, k.sun_dir.z};
    l.sun_irradiance = {k.sun_radiance.r, k.sun_radiance.g, k.sun_radiance.b};
    if (s.sky == cr::sky_model::physical)
        // The renderer's sun by height in the layer (scene.hpp's sun_at_height).
        l.sun_at = [s, k](const vec3& p) {
            const float altitude = cm::point_altitude(glm::vec3(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)),
                                                      s.camera_altitude, s.planet_radius);
            const glm::vec3 c = cr::sun_at_height(k, true, cm::height_fraction(altitude, s.layer_bottom, s.layer_top));
            return rgb{c.r, c.g, c.b};
        };
    // The physical sky seen from where the paths leave (the layer's top): its sky-view table there.
    // The sun alone (scene::light): no sky, and k's ground and background are black.
    // (Shared: the lambda below keeps it for as long as the paths run.)
    const std::shared_ptr<const cr::sky_view_table> top_sky =
        s.sky == cr::sky_model::physical && s.light != cr::light_sources::sun ? cr::physical_sky_view(s.layer_top, k.sun_dir) : nullptr;
    l.escaped = [k, top_sky](const vec3&, const vec3& d, bool ground) {
        const glm::vec3 dir(static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z));
        const glm::vec3 c = ground ? k.ground : top_sky != nullptr ? cr::sky_view_lookup(*top_sky, dir, k.sun_dir) : cr::sky_radiance(k, dir, false);
        return rgb{c.r, c.g, c.b};
    };
    return l;
}

std::string renderer_phase_spec(const cr::scene& s) {
    const cr::frame_constants k = cr::make_frame_constants(s);
    std::ostringstream o;
    o << "dual_hg:" << k.phase_g << "," << k.phase_g_back << "," << k.phase_w;
    return o.str();
}

std::vector<camera_ray> make_camera_rays(const cr::scene& s, int width, int height) {
    const cr::frame_constants k = cr::make_frame_constants(s);
    std::vector<camera_ray> rays;
    rays.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec3 dir = cr::pixel_direction(k, x, y, width, height);  // the renderer's, in float
            const glm::vec2 seg = cm::cloud_layer_segment(s.camera_altitude, dir.y, s.planet_radius, s.layer_bottom, s.layer_top);
            camera_ray r;
            r.origin = {0.0, 0.0, 0.0};
            r.direction = {dir.x, dir.y, dir.z};
            if (seg.y > seg.x) {
                r.t_begin = seg.x;
                r.t_end = std::min(seg.y, seg.x + s.max_distance);
            } else {
                r.t_begin = r.t_end = 0.0;
            }
            // No sun disc: the truth measures cloud light, and the disc (18,000 times the
            // irradiance) would dominate any image metric where it is in view.
            const glm::vec3 bg = cr::background(s, k, dir, false);
            r.background = {bg.r, bg.g, bg.b};
            rays.push_back(r);
        }
    return rays;
}

}  // namespace cloudmath::reference::volume
