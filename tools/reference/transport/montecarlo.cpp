// tools/reference/transport/montecarlo.cpp: the Monte Carlo path tracer; see montecarlo.hpp for the
// conventions, the methods and their sources.
#include "montecarlo.hpp"
#include "montecarlo_detail.hpp"
#include "strict_number.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include <cloudmath/phase.hpp>

namespace cloudmath::reference::mc {

using namespace detail;

namespace {

// ---------------------------------------------------------------------------------------
// Geometries for backward tracing. Lengths in units where the extinction is sigma_t.
struct slab_geometry {
    double sigma_t = 1.0;  // positions are in optical depth units
    double tau = 1.0;
    double mu0 = 1.0;
    vec3 sun;  // toward the sun
    double exit_distance(const vec3& p, const vec3& d) const {
        if (d.z > 0.0) return (tau - p.z) / d.z;
        if (d.z < 0.0) return p.z / -d.z;
        return infinity;
    }
    double sun_optical_depth(const vec3& p) const { return std::max(0.0, tau - p.z) / mu0; }
};

struct sphere_geometry {
    double sigma_t = 1.0;
    vec3 sun;
    double exit_distance(const vec3& p, const vec3& d) const {
        return distance_to_unit_sphere(p, d);
    }
    double sun_optical_depth(const vec3& p) const {
        return sigma_t * distance_to_unit_sphere(p, sun);
    }
};

// One camera path from pos (inside or on the medium) along dir: the sum over its scattering
// vertices of throughput * albedo * p(mu) * exp(-optical depth toward the sun).
template <class Geometry>
double trace_camera_path(const Geometry& geo, const phase_model& phase, double albedo,
                         unsigned max_order, vec3 pos, vec3 dir, random_stream& rng) {
    double throughput = 1.0;
    double value = 0.0;
    for (unsigned order = 1;; ++order) {
        const double s = rng.free_path() / geo.sigma_t;
        if (s >= geo.exit_distance(pos, dir)) break;
        pos = pos + s * dir;
        value += throughput * albedo * phase.evaluate(dot(dir, geo.sun)) *
                 std::exp(-geo.sun_optical_depth(pos));
        if (max_order != 0 && order >= max_order) break;
        throughput *= albedo;
        if (throughput <= 0.0) break;
        const phase_model::sample_result next = phase.sample(rng.uniform());
        throughput *= next.weight;
        dir = scatter_direction(dir, next.mu, rng.uniform());
        if (throughput < roulette_threshold) {
            if (rng.uniform() * roulette_threshold >= throughput) break;
            throughput = roulette_threshold;
        }
    }
    return value;
}

void check_slab(const slab_parameters& slab) {
    if (!(slab.tau > 0.0) || !std::isfinite(slab.tau))
        throw std::invalid_argument("slab optical thickness must be finite and > 0");
    if (!(slab.mu0 > 0.0 && slab.mu0 <= 1.0))
        throw std::invalid_argument("slab mu0 must be in (0, 1]");
    if (!(slab.albedo >= 0.0 && slab.albedo <= 1.0))
        throw std::invalid_argument("albedo must be in [0, 1]");
}

vec3 slab_sun_direction(double mu0) { return {std::sqrt((1.0 - mu0) * (1.0 + mu0)), 0.0, mu0}; }

// Direction the camera looks along (away from the camera) for a slab view.
vec3 slab_view_direction(const slab_view& v) {
    const double s = std::sqrt(std::max(0.0, (1.0 - v.mu) * (1.0 + v.mu)));
    const double phi = v.phi_deg * (pi / 180.0);
    return {s * std::cos(phi), s * std::sin(phi), v.transmitted ? v.mu : -v.mu};
}

// ---------------------------------------------------------------------------------------
// Phase-spec parsing.
std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (;;) {
        const auto pos = s.find(sep, start);
        out.push_back(s.substr(start, pos == std::string::npos ? std::string::npos : pos - start));
        if (pos == std::string::npos) return out;
        start = pos + 1;
    }
}

// Spaces around the number are allowed ("hg: 0.85"), nothing else (strict_number.hpp).
double parse_number(const std::string& text, const std::string& context) {
    const std::optional<double> v = cloudmath::tools::parse_finite(trim(text));
    if (!v) throw std::invalid_argument(context + ": '" + text + "' is not a finite number");
    return *v;
}

std::vector<double> parse_numbers(const std::string& args, std::size_t count,
                                  const std::string& spec, const char* usage) {
    const std::vector<std::string> parts = split(args, ',');
    if (args.empty() || parts.size() != count)
        throw std::invalid_argument("phase '" + spec + "': expected " + usage);
    std::vector<double> v;
    for (const auto& p : parts) v.push_back(parse_number(p, "phase '" + spec + "'"));
    return v;
}

void check_g(double g, const std::string& spec) {
    if (!(g > -1.0 && g < 1.0))
        throw std::invalid_argument("phase '" + spec + "': g must be in (-1, 1)");
}

std::shared_ptr<const phase_table> tabulate_lobe(phase_model::shape kind, double g,
                                                 double alpha) {
    auto table = std::make_shared<phase_table>(tabulate_phase(default_angles_deg(), [&](double mu) {
        switch (kind) {
            case phase_model::shape::rayleigh: return phase_rayleigh(mu);
            case phase_model::shape::cornette_shanks: return phase_cornette_shanks(mu, g);
            case phase_model::shape::draine: return phase_draine(mu, g, alpha);
            default: return phase_hg(mu, g);
        }
    }));
    return table;
}

phase_model::lobe analytic_lobe(phase_model::shape kind, double weight, double g = 0.0,
                                double alpha = 0.0) {
    phase_model::lobe l;
    l.kind = kind;
    l.weight = weight;
    l.g = g;
    l.alpha = alpha;
    if (kind != phase_model::shape::hg && kind != phase_model::shape::isotropic)
        l.table = tabulate_lobe(kind, g, alpha);
    return l;
}

double lobe_value(const phase_model::lobe& l, double mu) {
    switch (l.kind) {
        case phase_model::shape::isotropic: return phase_isotropic<double>();
        case phase_model::shape::hg: return phase_hg(mu, l.g);
        case phase_model::shape::rayleigh: return phase_rayleigh(mu);
        case phase_model::shape::cornette_shanks: return phase_cornette_shanks(mu, l.g);
        case phase_model::shape::draine: return phase_draine(mu, l.g, l.alpha);
        case phase_model::shape::table: return l.table->evaluate(mu) / l.table->integral();
    }
    return 0.0;
}

double lobe_pdf(const phase_model::lobe& l, double mu) {
    switch (l.kind) {
        case phase_model::shape::isotropic: return phase_isotropic<double>();
        case phase_model::shape::hg: return phase_hg(mu, l.g);
        default: return l.table->evaluate(mu) / l.table->integral();
    }
}

double lobe_sample(const phase_model::lobe& l, double u) {
    switch (l.kind) {
        case phase_model::shape::isotropic: return std::clamp(2.0 * u - 1.0, -1.0, 1.0);
        case phase_model::shape::hg: return sample_phase_hg(l.g, u);
        default: return l.table->sample_mu(u);
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------
phase_model::phase_model(std::string spec, std::vector<lobe> lobes)
    : spec_(std::move(spec)) {
    double total = 0.0;
    for (auto& l : lobes) {
        if (!(l.weight >= 0.0)) throw std::invalid_argument("phase lobe weight must be >= 0");
        if (l.kind != shape::hg && l.kind != shape::isotropic && !l.table)
            throw std::invalid_argument("phase lobe needs its tabulation");
        if (l.weight > 0.0) {
            total += l.weight;
            lobes_.push_back(l);
        }
    }
    if (lobes_.empty() || !(total > 0.0))
        throw std::invalid_argument("phase model needs a lobe of positive weight");
    for (auto& l : lobes_) l.weight /= total;
    exact_ = true;
    for (const auto& l : lobes_)
        if (l.kind != shape::hg && l.kind != shape::isotropic && l.kind != shape::table)
            exact_ = false;
    // A table lobe mixed with others is still exact (evaluated as sampled); nothing to add.
}

double phase_model::evaluate(double mu) const {
    mu = std::clamp(mu, -1.0, 1.0);
    double p = 0.0;
    for (const auto& l : lobes_) p += l.weight * lobe_value(l, mu);
    return p;
}

double phase_model::sampling_pdf(double mu) const {
    mu = std::clamp(mu, -1.0, 1.0);
    double p = 0.0;
    for (const auto& l : lobes_) p += l.weight * lobe_pdf(l, mu);
    return p;
}

phase_model::sample_result phase_model::sample(double u) const {
    // One uniform picks the lobe and, rescaled inside the lobe's interval, samples it.
    const lobe* chosen = &lobes_.back();
    double start = 1.0 - chosen->weight;
    double acc = 0.0;
    for (const auto& l : lobes_) {
        if (u < acc + l.weight) {
            chosen = &l;
            start = acc;
            break;
        }
        acc += l.weight;
    }
    const double v = std::clamp((u - start) / chosen->weight, 0.0, std::nextafter(1.0, 0.0));
    const double mu = lobe_sample(*chosen, v);
    if (exact_) return {mu, 1.0};
    return {mu, evaluate(mu) / sampling_pdf(mu)};
}

phase_model make_phase(const std::string& spec_in) {
    const std::string spec = trim(spec_in);
    const auto colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    const std::string args = colon == std::string::npos ? "" : spec.substr(colon + 1);
    using shape = phase_model::shape;
    if (name == "isotropic" || name == "rayleigh") {
        if (colon != std::string::npos)
            throw std::invalid_argument("phase '" + spec + "' takes no parameters");
        return phase_model(spec, {analytic_lobe(name == "rayleigh" ? shape::rayleigh
                                                                   : shape::isotropic,
                                                1.0)});
    }
    if (name == "hg" || name == "cs") {
        const double g = parse_numbers(args, 1, spec, (name + ":G").c_str())[0];
        check_g(g, spec);
        return phase_model(spec, {analytic_lobe(name == "hg" ? shape::hg : shape::cornette_shanks,
                                                1.0, g)});
    }
    if (name == "dual_hg") {
        const auto v = parse_numbers(args, 3, spec, "dual_hg:G0,G1,W");
        check_g(v[0], spec);
        check_g(v[1], spec);
        if (!(v[2] >= 0.0 && v[2] <= 1.0))
            throw std::invalid_argument("phase '" + spec + "': W must be in [0, 1]");
        return phase_model(spec, {analytic_lobe(shape::hg, 1.0 - v[2], v[0]),
                                  analytic_lobe(shape::hg, v[2], v[1])});
    }
    if (name == "draine") {
        const auto v = parse_numbers(args, 2, spec, "draine:G,ALPHA");
        check_g(v[0], spec);
        if (!(v[1] >= 0.0))
            throw std::invalid_argument("phase '" + spec + "': ALPHA must be >= 0");
        return phase_model(spec, {analytic_lobe(shape::draine, 1.0, v[0], v[1])});
    }
    if (name == "mie_approx") {
        const double d = parse_numbers(args, 1, spec, "mie_approx:D_UM")[0];
        if (!(d > 0.0 && d <= 50.0))
            throw std::invalid_argument("phase '" + spec +
                                        "': droplet diameter must be in (0, 50] micrometres");
        const auto p = mie_approx_params(d);
        return phase_model(spec, {analytic_lobe(shape::hg, 1.0 - p.w_draine, p.g_hg),
                                  analytic_lobe(shape::draine, p.w_draine, p.g_draine, p.alpha)});
    }
    if (name == "table") {
        if (trim(args).empty())
            throw std::invalid_argument("phase '" + spec + "': expected table:PATH");
        phase_model::lobe l;
        l.kind = shape::table;
        l.table = std::make_shared<phase_table>(read_phase_table(trim(args)));
        return phase_model(spec, {l});
    }
    throw std::invalid_argument("unknown phase '" + spec +
                                "' (expected isotropic, rayleigh, hg:G, dual_hg:G0,G1,W, cs:G, "
                                "draine:G,ALPHA, mie_approx:D_UM or table:PATH)");
}

// ---------------------------------------------------------------------------------------
namespace {

struct slab_chunk_tally {
    moments reflected, diffuse, direct, absorbed, beyond, weight;
    std::vector<moments> hist_reflected, hist_transmitted;
};

}  // namespace

slab_flux_result trace_slab(const slab_parameters& slab, const phase_model& phase,
                            std::uint64_t photons, unsigned bins, const run_options& options) {
    check_slab(slab);
    if (photons == 0) throw std::invalid_argument("photon count must be >= 1");
    if (bins == 0) throw std::invalid_argument("histogram needs at least 1 bin");
    const std::uint64_t chunks = chunk_count(photons);
    std::vector<slab_chunk_tally> tallies(static_cast<std::size_t>(chunks));
    const vec3 beam = -1.0 * slab_sun_direction(slab.mu0);  // propagation of the sun beam
    const double nb = static_cast<double>(bins);
    auto bin_of = [&](double mu) {
        return std::min<std::size_t>(bins - 1u, static_cast<std::size_t>(std::max(0.0, mu) * nb));
    };

    run_chunks(static_cast<std::size_t>(chunks), options, [&](std::size_t c) {
        slab_chunk_tally& t = tallies[c];
        t.hist_reflected.assign(bins, moments{});
        t.hist_transmitted.assign(bins, moments{});
        random_stream rng(options.seed, 0x51AB0000ULL, c);
        const std::uint64_t n = chunk_size(photons, c);
        for (std::uint64_t i = 0; i < n; ++i) {
            double z = slab.tau;
            vec3 dir = beam;
            double weight = 1.0;
            unsigned scatterings = 0;
            // Each photon ends in exactly one bucket, with its whole weight.
            double r = 0.0, td = 0.0, tdir = 0.0, a = 0.0, beyond = 0.0;
            for (;;) {
                const double s = rng.free_path();
                const double exit = dir.z > 0.0   ? (slab.tau - z) / dir.z
                                    : dir.z < 0.0 ? z / -dir.z
                                                  : infinity;
                if (s >= exit) {
                    if (dir.z > 0.0) {
                        r = weight;
                        t.hist_reflected[bin_of(dir.z)].add(weight);
                    } else if (scatterings == 0) {
                        tdir = weight;
                    } else {
                        td = weight;
                        t.hist_transmitted[bin_of(-dir.z)].add(weight);
                    }
                    break;
                }
                z = std::clamp(z + s * dir.z, 0.0, slab.tau);
                if (options.max_order != 0 && scatterings >= options.max_order) {
                    beyond = weight;
                    break;
                }
                if (rng.uniform() >= slab.albedo) {
                    a = weight;
                    break;
                }
                ++scatterings;
                const phase_model::sample_result next = phase.sample(rng.uniform());
                weight *= next.weight;
                dir = scatter_direction(dir, next.mu, rng.uniform());
            }
            t.reflected.add(r);
            t.diffuse.add(td);
            t.direct.add(tdir);
            t.absorbed.add(a);
            t.beyond.add(beyond);
            t.weight.add(weight);
        }
    });

    slab_chunk_tally total;
    total.hist_reflected.assign(bins, moments{});
    total.hist_transmitted.assign(bins, moments{});
    for (const auto& t : tallies) {
        total.reflected.merge(t.reflected);
        total.diffuse.merge(t.diffuse);
        total.direct.merge(t.direct);
        total.absorbed.merge(t.absorbed);
        total.beyond.merge(t.beyond);
        total.weight.merge(t.weight);
        for (std::size_t b = 0; b < bins; ++b) {
            total.hist_reflected[b].merge(t.hist_reflected[b]);
            total.hist_transmitted[b].merge(t.hist_transmitted[b]);
        }
    }
    slab_flux_result out;
    out.reflected = make_estimate(total.reflected, photons);
    out.transmitted_diffuse = make_estimate(total.diffuse, photons);
    out.transmitted_direct = make_estimate(total.direct, photons);
    out.absorbed = make_estimate(total.absorbed, photons);
    out.beyond_max_order = make_estimate(total.beyond, photons);
    out.photon_weight = make_estimate(total.weight, photons);
    out.mu_edges.resize(bins + 1u);
    for (unsigned b = 0; b <= bins; ++b) out.mu_edges[b] = static_cast<double>(b) / nb;
    for (std::size_t b = 0; b < bins; ++b) {
        const double lo = out.mu_edges[b], hi = out.mu_edges[b + 1];
        // Weight fraction -> radiance: the bin receives 2 pi L mu_centre (hi - lo) of the
        // mu0 F0 incident per unit area.
        const double scale = slab.mu0 / (2.0 * pi * (hi - lo) * 0.5 * (lo + hi));
        out.reflected_radiance.push_back(make_estimate(total.hist_reflected[b], photons, scale));
        out.transmitted_radiance.push_back(
            make_estimate(total.hist_transmitted[b], photons, scale));
    }
    return out;
}

// ---------------------------------------------------------------------------------------
std::vector<slab_view> parse_slab_views(const std::string& list) {
    std::vector<slab_view> views;
    for (const std::string& item_raw : split(list, ';')) {
        const std::string item = trim(item_raw);
        if (item.empty()) continue;
        const auto colon = item.find(':');
        const std::string side = colon == std::string::npos ? "" : trim(item.substr(0, colon));
        if (side != "r" && side != "t")
            throw std::invalid_argument("view '" + item + "': expected r:MU,PHI or t:MU,PHI");
        const auto parts = split(item.substr(colon + 1), ',');
        if (parts.size() != 2)
            throw std::invalid_argument("view '" + item + "': expected r:MU,PHI or t:MU,PHI");
        slab_view v;
        v.transmitted = side == "t";
        v.mu = parse_number(parts[0], "view '" + item + "'");
        v.phi_deg = parse_number(parts[1], "view '" + item + "'");
        if (!(v.mu > 0.0 && v.mu <= 1.0))
            throw std::invalid_argument("view '" + item + "': MU must be in (0, 1]");
        views.push_back(v);
    }
    if (views.empty()) throw std::invalid_argument("no view directions given");
    return views;
}

double slab_view_scattering_cosine(const slab_parameters& slab, const slab_view& view) {
    return std::clamp(dot(slab_view_direction(view), slab_sun_direction(slab.mu0)), -1.0, 1.0);
}

double slab_view_scattering_angle_deg(const slab_parameters& slab, const slab_view& view) {
    const vec3 v = slab_view_direction(view), s = slab_sun_direction(slab.mu0);
    const vec3 c = cross(v, s);
    return std::atan2(std::sqrt(dot(c, c)), dot(v, s)) * (180.0 / pi);
}

namespace {

// Runs `paths` samples of sample_path(item, rng) for every item, in chunks keyed by (item,
// chunk), and returns one estimate per item.
template <class PathFn>
std::vector<estimate> estimate_per_item(std::size_t items, std::uint64_t paths,
                                        const run_options& options, PathFn sample_path) {
    const std::vector<moments> totals = tally_per_item<moments>(
        items, paths, options, 0xCA3E0000ULL,
        [&](std::size_t item, random_stream& rng, moments& m) { m.add(sample_path(item, rng)); });
    std::vector<estimate> out;
    out.reserve(items);
    for (const moments& m : totals) out.push_back(make_estimate(m, paths));
    return out;
}

}  // namespace

std::vector<estimate> slab_radiance(const slab_parameters& slab, const phase_model& phase,
                                    const std::vector<slab_view>& views,
                                    std::uint64_t paths_per_view, const run_options& options) {
    check_slab(slab);
    slab_geometry geo;
    geo.tau = slab.tau;
    geo.mu0 = slab.mu0;
    geo.sun = slab_sun_direction(slab.mu0);
    std::vector<vec3> dirs;
    for (const auto& v : views) {
        if (!(v.mu > 0.0 && v.mu <= 1.0))
            throw std::invalid_argument("slab view mu must be in (0, 1]");
        dirs.push_back(slab_view_direction(v));
    }
    return estimate_per_item(views.size(), paths_per_view, options,
                             [&](std::size_t item, random_stream& rng) {
                                 const vec3 start{0.0, 0.0,
                                                  views[item].transmitted ? 0.0 : slab.tau};
                                 return trace_camera_path(geo, phase, slab.albedo,
                                                          options.max_order, start, dirs[item],
                                                          rng);
                             });
}

std::vector<estimate> sphere_radiance(const sphere_parameters& sphere, const phase_model& phase,
                                      const std::vector<ray>& rays, std::uint64_t paths_per_ray,
                                      const run_options& options) {
    if (!(sphere.albedo >= 0.0 && sphere.albedo <= 1.0))
        throw std::invalid_argument("albedo must be in [0, 1]");
    if (!(sphere.optical_diameter > 0.0) || !std::isfinite(sphere.optical_diameter))
        throw std::invalid_argument("sphere optical diameter must be finite and > 0");
    const double sun_len = std::sqrt(dot(sphere.sun_direction, sphere.sun_direction));
    if (!(sun_len > 0.0) || !std::isfinite(sun_len))
        throw std::invalid_argument("sun direction must be a finite non-zero vector");
    sphere_geometry geo;
    geo.sigma_t = 0.5 * sphere.optical_diameter;
    geo.sun = (1.0 / sun_len) * sphere.sun_direction;

    // Entry point of each ray (or a miss): computed once per ray.
    struct entry {
        bool hit = false;
        vec3 pos, dir;
    };
    std::vector<entry> entries;
    for (const auto& r : rays) {
        entry e;
        const double len = std::sqrt(dot(r.direction, r.direction));
        if (!(len > 0.0) || !std::isfinite(len))
            throw std::invalid_argument("camera ray direction must be a finite non-zero vector");
        e.dir = (1.0 / len) * r.direction;
        const double b = dot(r.origin, e.dir);
        const double c = dot(r.origin, r.origin) - 1.0;
        if (c <= 0.0) {
            e.hit = true;  // origin inside the sphere
            e.pos = r.origin;
        } else {
            const double disc = b * b - c;
            if (disc > 0.0 && b < 0.0) {
                // Near root -b - sqrt(disc) written as c / (-b + sqrt(disc)): no cancellation.
                e.hit = true;
                e.pos = r.origin + (c / (-b + std::sqrt(disc))) * e.dir;
            }
        }
        entries.push_back(e);
    }
    return estimate_per_item(rays.size(), paths_per_ray, options,
                             [&](std::size_t item, random_stream& rng) {
                                 const entry& e = entries[item];
                                 if (!e.hit) return 0.0;
                                 return trace_camera_path(geo, phase, sphere.albedo,
                                                          options.max_order, e.pos, e.dir, rng);
                             });
}

// ---------------------------------------------------------------------------------------
namespace {

sphere_camera camera_axes(double view_angle_deg) {
    if (!(view_angle_deg >= 0.0 && view_angle_deg <= 180.0))
        throw std::invalid_argument("view angle must be in [0, 180] degrees");
    const double a = view_angle_deg * (pi / 180.0);
    sphere_camera cam;
    cam.sun_direction = {0.0, 0.0, 1.0};
    cam.view_direction = {std::sin(a), 0.0, std::cos(a)};
    cam.axis_u = {-std::cos(a), 0.0, std::sin(a)};
    cam.axis_v = cross(cam.view_direction, cam.axis_u);
    return cam;
}

void add_camera_ray(sphere_camera& cam, double u, double v) {
    cam.u.push_back(u);
    cam.v.push_back(v);
    cam.rays.push_back({u * cam.axis_u + v * cam.axis_v + (-2.0) * cam.view_direction,
                        cam.view_direction});
}

double cell_centre(unsigned i, unsigned n) {
    return -1.0 + (2.0 * static_cast<double>(i) + 1.0) / static_cast<double>(n);
}

}  // namespace

sphere_camera make_sphere_camera_line(double view_angle_deg, unsigned points) {
    if (points == 0) throw std::invalid_argument("camera needs at least 1 point");
    sphere_camera cam = camera_axes(view_angle_deg);
    for (unsigned i = 0; i < points; ++i) add_camera_ray(cam, cell_centre(i, points), 0.0);
    return cam;
}

sphere_camera make_sphere_camera_grid(double view_angle_deg, unsigned n) {
    if (n == 0) throw std::invalid_argument("camera grid needs n >= 1");
    sphere_camera cam = camera_axes(view_angle_deg);
    for (unsigned j = 0; j < n; ++j)
        for (unsigned i = 0; i < n; ++i) add_camera_ray(cam, cell_centre(i, n), cell_centre(j, n));
    return cam;
}

}  // namespace cloudmath::reference::mc
