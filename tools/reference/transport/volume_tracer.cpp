// tools/reference/transport/volume_tracer.cpp: delta tracking, ratio tracking and the path loop; see
// volume_tracer.hpp for the methods and their sources.
#include "volume_tracer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cloudmath::reference::volume {

using namespace mc::detail;

namespace {

// Ratio tracking hands over to Russian roulette below this transmittance.
constexpr double transmittance_roulette = 0.1;

// Extinction lookups made on this thread (the pilot's cost measure).
thread_local std::uint64_t extinction_lookups = 0;

// Random streams of the pilot run, apart from the estimate's (0x70C0000 + ray).
constexpr std::uint64_t pilot_key = 0x9170B000000ULL;
constexpr std::uint64_t estimate_key = 0x70C0000ULL;

void add_scaled(rgb& sum, double s, const rgb& c) {
    sum.r += s * c.r;
    sum.g += s * c.g;
    sum.b += s * c.b;
}

}  // namespace

// ---------------------------------------------------------------------------------------
homogeneous_medium::homogeneous_medium(double sigma_t, double majorant_scale)
    : sigma_t_(sigma_t), majorant_(sigma_t * majorant_scale) {
    if (!(sigma_t > 0.0) || !(majorant_scale >= 1.0))
        throw std::invalid_argument("homogeneous medium: sigma_t > 0 and majorant_scale >= 1");
}
double homogeneous_medium::extinction(const vec3& p) const { return contains(p) ? sigma_t_ : 0.0; }
medium_exit homogeneous_medium::exit(const vec3& p, const vec3& d) const {
    return {chord(p, d).second, false};
}
void homogeneous_medium::majorants(const vec3& p, const vec3& d, double t_min, double t_max,
                                   const majorant_visitor& visit) const {
    const std::pair<double, double> c = chord(p, d);
    const double a = std::max(c.first, t_min), b = std::min(c.second, t_max);
    if (b > a) visit(a, b, majorant_);
}

bool homogeneous_sphere::contains(const vec3& p) const { return dot(p, p) <= 1.0; }
std::pair<double, double> homogeneous_sphere::chord(const vec3& p, const vec3& d) const {
    const double b = dot(p, d);
    const double c = dot(p, p) - 1.0;
    const double disc = b * b - c;
    if (c <= 0.0) return {0.0, distance_to_unit_sphere(p, d)};
    if (!(disc > 0.0) || b >= 0.0) return {0.0, 0.0};
    const double root = std::sqrt(disc);
    return {c / (-b + root), -b + root};
}

homogeneous_slab::homogeneous_slab(double tau, double majorant_scale)
    : homogeneous_medium(1.0, majorant_scale), tau_(tau) {
    if (!(tau > 0.0)) throw std::invalid_argument("homogeneous_slab: tau > 0");
}
bool homogeneous_slab::contains(const vec3& p) const { return p.z >= 0.0 && p.z <= tau_; }
std::pair<double, double> homogeneous_slab::chord(const vec3& p, const vec3& d) const {
    if (d.z == 0.0) return contains(p) ? std::make_pair(0.0, infinity) : std::make_pair(0.0, 0.0);
    double a = (0.0 - p.z) / d.z, b = (tau_ - p.z) / d.z;
    if (a > b) std::swap(a, b);
    a = std::max(a, 0.0);
    return b > a ? std::make_pair(a, b) : std::make_pair(0.0, 0.0);
}

// ---------------------------------------------------------------------------------------
path_tracer::path_tracer(const medium& m, const mc::phase_model& phase, double albedo,
                         const lighting& light, unsigned max_order)
    : medium_(m), phase_(phase), albedo_(albedo), light_(light), max_order_(max_order) {
    if (!(albedo >= 0.0 && albedo <= 1.0))
        throw std::invalid_argument("albedo must be in [0, 1]");
    const double len = std::sqrt(dot(light.sun_direction, light.sun_direction));
    if (!(len > 0.0) || !std::isfinite(len))
        throw std::invalid_argument("sun direction must be a finite non-zero vector");
    sun_ = (1.0 / len) * light.sun_direction;
}

double path_tracer::free_flight(const vec3& p, const vec3& d, double t0, double t1,
                                random_stream& rng) const {
    double hit = infinity;
    medium_.majorants(p, d, t0, t1, [&](double a, double b, double majorant) {
        if (!(majorant > 0.0)) return true;
        for (double t = a;;) {
            t += rng.free_path() / majorant;
            if (t >= b) return true;
            ++extinction_lookups;
            if (rng.uniform() * majorant < medium_.extinction(p + t * d)) {
                hit = t;
                return false;
            }
        }
    });
    return hit;
}

double path_tracer::transmittance(const vec3& p, const vec3& d, double t1,
                                  random_stream& rng) const {
    double tr = 1.0;
    medium_.majorants(p, d, 0.0, t1, [&](double a, double b, double majorant) {
        if (!(majorant > 0.0)) return true;
        for (double t = a;;) {
            t += rng.free_path() / majorant;
            if (t >= b) return true;
            ++extinction_lookups;
            tr *= 1.0 - medium_.extinction(p + t * d) / majorant;
            if (tr < transmittance_roulette) {
                if (rng.uniform() * transmittance_roulette >= tr) {
                    tr = 0.0;
                    return false;
                }
                tr = transmittance_roulette;
            }
        }
    });
    return tr;
}

rgb path_tracer::sample(const camera_ray& ray, random_stream& rng) const {
    vec3 pos = ray.origin;
    vec3 dir = normalized(ray.direction);
    rgb radiance;
    double throughput = 1.0;
    const auto escape = [&](const medium_exit& e) {
        if (light_.escaped) add_scaled(radiance, throughput, light_.escaped(pos + e.distance * dir, dir, e.ground));
    };

    // The first flight: limited to the camera ray's stretch, or up to the medium's exit.
    double t;
    if (std::isfinite(ray.t_end)) {
        t = free_flight(pos, dir, ray.t_begin, ray.t_end, rng);
        if (t == infinity) {
            add_scaled(radiance, throughput, ray.background);
            return radiance;
        }
    } else {
        const medium_exit e = medium_.exit(pos, dir);
        t = free_flight(pos, dir, ray.t_begin, e.distance, rng);
        if (t == infinity) {
            escape(e);
            return radiance;
        }
    }
    for (unsigned order = 1;; ++order) {
        pos = pos + t * dir;
        // Next-event estimation toward the sun (a shadow ray ending on the ground is dark).
        const medium_exit to_sun = medium_.exit(pos, sun_);
        if (!to_sun.ground) {
            const double tr = transmittance(pos, sun_, to_sun.distance, rng);
            if (tr > 0.0)
                add_scaled(radiance, throughput * albedo_ * phase_.evaluate(dot(dir, sun_)) * tr,
                           light_.sun_at ? light_.sun_at(pos) : light_.sun_irradiance);
        }
        if (max_order_ != 0 && order >= max_order_) break;
        throughput *= albedo_;
        if (throughput <= 0.0) break;
        const mc::phase_model::sample_result next = phase_.sample(rng.uniform());
        throughput *= next.weight;
        dir = scatter_direction(dir, next.mu, rng.uniform());
        if (throughput < roulette_threshold) {
            if (rng.uniform() * roulette_threshold >= throughput) break;
            throughput = roulette_threshold;
        }
        const medium_exit e = medium_.exit(pos, dir);
        t = free_flight(pos, dir, 0.0, e.distance, rng);
        if (t == infinity) {
            escape(e);
            break;
        }
    }
    return radiance;
}

// ---------------------------------------------------------------------------------------
namespace {

// One path of ray `item` into the tally, with its extinction lookups.
auto sample_into(const path_tracer& tracer, const std::vector<camera_ray>& rays) {
    return [&tracer, &rays](std::size_t item, random_stream& rng, path_tally& t) {
        const std::uint64_t before = extinction_lookups;
        const rgb L = tracer.sample(rays[item], rng);
        t.lookups += static_cast<double>(extinction_lookups - before);
        t.r.add(L.r);
        t.g.add(L.g);
        t.b.add(L.b);
        ++t.paths;
    };
}

}  // namespace

rgb_estimate make_rgb_estimate(const path_tally& t) {
    rgb_estimate e{make_estimate(t.r, t.paths), make_estimate(t.g, t.paths), make_estimate(t.b, t.paths)};
    if (t.paths < 2) e.r.std_error = e.g.std_error = e.b.std_error = 0.0;
    return e;
}

std::vector<path_tally> trace_chunks(const path_tracer& tracer, const std::vector<camera_ray>& rays,
                                     const std::vector<chunk_job>& jobs, const mc::run_options& options) {
    for (const chunk_job& j : jobs) {
        if (j.ray >= rays.size()) throw std::invalid_argument("trace_chunks: a job's ray is out of range");
        if (j.paths < 1 || j.paths > paths_per_chunk)
            throw std::invalid_argument("trace_chunks: a job holds 1 to paths_per_chunk paths");
    }
    std::vector<path_tally> out(jobs.size());
    const auto sample = sample_into(tracer, rays);
    run_chunks(jobs.size(), options, [&](std::size_t k) {
        const chunk_job& j = jobs[k];
        random_stream rng(options.seed, estimate_key + j.ray, j.chunk);
        for (std::uint64_t i = 0; i < j.paths; ++i) sample(j.ray, rng, out[k]);
    });
    return out;
}

std::vector<rgb_estimate> estimate_radiance(const path_tracer& tracer,
                                            const std::vector<camera_ray>& rays,
                                            std::uint64_t paths_per_ray,
                                            const mc::run_options& options) {
    const std::vector<path_tally> totals =
        tally_per_item<path_tally>(rays.size(), paths_per_ray, options, estimate_key, sample_into(tracer, rays));
    std::vector<rgb_estimate> out;
    out.reserve(rays.size());
    for (const path_tally& t : totals) out.push_back(make_rgb_estimate(t));
    return out;
}

std::vector<rgb_estimate> estimate_radiance(const path_tracer& tracer,
                                            const std::vector<camera_ray>& rays,
                                            const std::vector<std::uint64_t>& paths_per_ray,
                                            const mc::run_options& options) {
    if (paths_per_ray.size() != rays.size())
        throw std::invalid_argument("estimate_radiance: one path count per ray");
    const std::vector<path_tally> totals =
        tally_per_item<path_tally>(paths_per_ray, options, estimate_key, sample_into(tracer, rays));
    std::vector<rgb_estimate> out;
    out.reserve(rays.size());
    for (const path_tally& t : totals) out.push_back(make_rgb_estimate(t));
    return out;
}

pilot_estimate estimate_radiance_pilot(const path_tracer& tracer, const std::vector<camera_ray>& rays,
                                       std::uint64_t paths_per_ray, const mc::run_options& options) {
    if (paths_per_ray < 2) throw std::invalid_argument("estimate_radiance_pilot: at least 2 paths per ray");
    const std::vector<path_tally> totals =
        tally_per_item<path_tally>(rays.size(), paths_per_ray, options, pilot_key, sample_into(tracer, rays));
    pilot_estimate out;
    out.radiance.reserve(rays.size());
    out.cost_per_path.reserve(rays.size());
    for (const path_tally& t : totals) {
        out.radiance.push_back(make_rgb_estimate(t));
        out.cost_per_path.push_back(1.0 + t.lookups / static_cast<double>(paths_per_ray));
    }
    return out;
}

path_allocation allocate_paths(const std::vector<double>& variance, const std::vector<double>& cost,
                               double target_variance_sum, std::uint64_t min_paths, std::uint64_t max_paths) {
    if (variance.size() != cost.size()) throw std::invalid_argument("allocate_paths: one cost per variance");
    if (!(target_variance_sum > 0.0) || !std::isfinite(target_variance_sum))
        throw std::invalid_argument("allocate_paths: the target variance must be positive and finite");
    if (min_paths < 2 || min_paths > max_paths)
        throw std::invalid_argument("allocate_paths: 2 <= min_paths <= max_paths");
    for (std::size_t i = 0; i < variance.size(); ++i) {
        if (!(variance[i] >= 0.0) || !std::isfinite(variance[i]))
            throw std::invalid_argument("allocate_paths: variances must be finite and >= 0");
        if (!(cost[i] > 0.0) || !std::isfinite(cost[i]))
            throw std::invalid_argument("allocate_paths: costs must be finite and > 0");
    }
    const auto lo = static_cast<double>(min_paths), hi = static_cast<double>(max_paths);
    // n_i(lambda) = clamp(ceil(lambda sqrt(variance_i / cost_i)), min, max): the sum of
    // variance_i / n_i falls as lambda grows; bisect lambda (in log space) for the target.
    const auto counts = [&](double lambda) {
        path_allocation a;
        a.paths.resize(variance.size());
        for (std::size_t i = 0; i < variance.size(); ++i) {
            const double want = variance[i] > 0.0 ? lambda * std::sqrt(variance[i] / cost[i]) : 0.0;
            const double n = std::clamp(std::ceil(want), lo, hi);
            a.paths[i] = static_cast<std::uint64_t>(n);
            a.predicted_variance_sum += variance[i] / n;
            a.predicted_cost += n * cost[i];
        }
        return a;
    };
    const path_allocation fewest = counts(0.0);  // min_paths everywhere
    if (fewest.predicted_variance_sum <= target_variance_sum) return fewest;
    const path_allocation most = counts(std::numeric_limits<double>::infinity());  // max_paths everywhere
    if (most.predicted_variance_sum > target_variance_sum) return most;
    double a = 0.0, b = 1.0;
    while (counts(b).predicted_variance_sum > target_variance_sum) {
        a = b;
        b *= 2.0;
    }
    for (int i = 0; i < 200 && b > a * (1.0 + 1e-12); ++i) {
        const double m = 0.5 * (a + b);
        (counts(m).predicted_variance_sum > target_variance_sum ? a : b) = m;
    }
    return counts(b);
}

}  // namespace cloudmath::reference::volume
