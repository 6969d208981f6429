// tools/reference/truths/lighting_error.cpp: see lighting_error.hpp.
#include "lighting_error.hpp"

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <glm/geometric.hpp>

#include <cloudmath/phase.hpp>
#include <cloudmath/transmittance.hpp>

#include "phase_error.hpp"  // nelder_mead
#include "strict_number.hpp"

namespace cloudmath::reference::lighting {

namespace {

constexpr double pi = 3.14159265358979323846;

glm::dvec3 to_glm(const mc::vec3& v) { return {v.x, v.y, v.z}; }

// Adds the estimate b (n_b paths) to a (n_a paths): the mean over all paths and its
// standard error, sqrt(n_a^2 se_a^2 + n_b^2 se_b^2) / (n_a + n_b).
mc::estimate combine(const mc::estimate& a, const mc::estimate& b) {
    const double na = static_cast<double>(a.samples), nb = static_cast<double>(b.samples);
    mc::estimate r;
    r.samples = a.samples + b.samples;
    r.mean = (na * a.mean + nb * b.mean) / (na + nb);
    r.std_error = std::sqrt(na * na * a.std_error * a.std_error +
                            nb * nb * b.std_error * b.std_error) / (na + nb);
    return r;
}

// Paths to add to an estimate so that its relative error reaches the target (0 if it has).
std::uint64_t extra_paths(const mc::estimate& e, const reference_options& o) {
    if (!(e.mean > 0.0)) return 0;
    const double rel = e.std_error / e.mean;
    if (rel <= o.target_rel_error) return 0;
    const double want = static_cast<double>(e.samples) * (rel / o.target_rel_error) *
                        (rel / o.target_rel_error);
    const double total = std::min(want * 1.1, static_cast<double>(o.max_paths));
    return total > static_cast<double>(e.samples)
               ? static_cast<std::uint64_t>(total) - e.samples
               : 0;
}

std::string fmt(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

double elapsed_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

double reference_row::mu() const { return glm::dot(dir, sun); }

glm::dvec3 slab_view_direction(const mc::slab_view& view) {
    const double s = std::sqrt(std::max(0.0, 1.0 - view.mu * view.mu));
    const double phi = view.phi_deg * pi / 180.0;
    return {s * std::cos(phi), s * std::sin(phi), view.transmitted ? view.mu : -view.mu};
}

reference_options holdout_reference_options() {
    reference_options o;
    o.taus = {3, 7, 15, 35, 70};
    o.sphere_view_angles_deg = {45, 80, 110, 140};
    o.sphere_points = 7;
    o.slab_sun_zenith_deg = {30, 70};
    o.slab_views = "r:0.8,90;r:0.3,0;t:0.8,90;t:0.3,180";
    o.paths = 100000;
    o.max_paths = 1600000;
    o.target_rel_error = 0.015;
    o.seed = 2;
    return o;
}

reference_set generate_reference(const reference_options& o) {
    if (o.taus.empty() || (o.sphere_view_angles_deg.empty() && o.slab_sun_zenith_deg.empty()))
        throw std::invalid_argument("generate_reference: no optical thickness or no geometry");
    if (!(o.albedo >= 0.0 && o.albedo <= 1.0))
        throw std::invalid_argument("generate_reference: albedo must be in [0, 1]");
    if (o.paths == 0 || o.max_paths < o.paths || !(o.target_rel_error > 0.0))
        throw std::invalid_argument("generate_reference: need 0 < paths <= max_paths and a "
                                    "positive target error");
    for (double t : o.taus)
        if (!(t > 0.0)) throw std::invalid_argument("generate_reference: tau must be > 0");
    for (double z : o.slab_sun_zenith_deg)
        if (!(z >= 0.0 && z < 90.0))
            throw std::invalid_argument("generate_reference: solar zenith must be in [0, 90)");
    const mc::phase_model phase = mc::make_phase(o.phase);
    const std::vector<mc::slab_view> views = mc::parse_slab_views(o.slab_views);

    reference_set set;
    set.phase_spec = o.phase;
    set.albedo = o.albedo;
    std::uint64_t job = 0;
    auto options_for = [&](std::uint64_t key) {
        mc::run_options r;
        r.seed = o.seed * 1000003u + key;  // one independent stream set per job and pass
        r.threads = o.threads;
        return r;
    };
    auto say = [&](const std::string& line) {
        if (o.log) o.log(line);
    };
    // Adds paths to every estimate above the target error: trace(i, paths) traces ray i.
    auto refine = [&](std::vector<mc::estimate>& L, const auto& trace) {
        for (std::size_t i = 0; i < L.size(); ++i)
            if (const std::uint64_t more = extra_paths(L[i], o)) L[i] = combine(L[i], trace(i, more));
    };
    const auto start = std::chrono::steady_clock::now();

    for (double tau : o.taus)
        for (double angle : o.sphere_view_angles_deg) {
            const auto t0 = std::chrono::steady_clock::now();
            const mc::sphere_camera cam = mc::make_sphere_camera_line(angle, o.sphere_points);
            const mc::sphere_parameters sp{tau, o.albedo, cam.sun_direction};
            std::vector<mc::estimate> L =
                mc::sphere_radiance(sp, phase, cam.rays, o.paths, options_for(2 * job));
            refine(L, [&](std::size_t i, std::uint64_t more) {
                return mc::sphere_radiance(sp, phase, {cam.rays[i]}, more,
                                           options_for(2 * job + 1 + 2 * i)).front();
            });
            for (std::size_t i = 0; i < L.size(); ++i) {
                reference_row r;
                r.geometry = "sphere";
                r.tau = tau;
                r.sun_deg = angle;
                r.u = cam.u[i];
                r.origin = to_glm(cam.rays[i].origin);
                r.dir = glm::normalize(to_glm(cam.rays[i].direction));
                r.sun = glm::normalize(to_glm(cam.sun_direction));
                r.radiance = L[i].mean;
                r.std_error = L[i].std_error;
                r.paths = L[i].samples;
                set.rows.push_back(r);
            }
            job += 1000;
            char line[160];
            std::snprintf(line, sizeof line, "sphere tau_d = %g, view angle %g deg: %zu rays, "
                          "%.1f s (%.0f s in all)", tau, angle, L.size(), elapsed_since(t0),
                          elapsed_since(start));
            say(line);
        }

    for (double tau : o.taus)
        for (double zenith : o.slab_sun_zenith_deg) {
            const auto t0 = std::chrono::steady_clock::now();
            const double mu0 = std::cos(zenith * pi / 180.0);
            const mc::slab_parameters sp{tau, mu0, o.albedo};
            std::vector<mc::estimate> L =
                mc::slab_radiance(sp, phase, views, o.paths, options_for(2 * job));
            refine(L, [&](std::size_t i, std::uint64_t more) {
                return mc::slab_radiance(sp, phase, {views[i]}, more,
                                         options_for(2 * job + 1 + 2 * i)).front();
            });
            const glm::dvec3 sun = slab_sun_direction(mu0);
            for (std::size_t i = 0; i < L.size(); ++i) {
                reference_row r;
                r.geometry = views[i].transmitted ? "slab_transmitted" : "slab_reflected";
                r.tau = tau;
                r.sun_deg = zenith;
                r.view_mu = views[i].mu;
                r.view_phi_deg = views[i].phi_deg;
                r.dir = slab_view_direction(views[i]);
                r.sun = sun;
                r.radiance = L[i].mean;
                r.std_error = L[i].std_error;
                r.paths = L[i].samples;
                // The frame conversion must give the Monte Carlo's own scattering angle.
                const double want = mc::slab_view_scattering_cosine(sp, views[i]);
                if (std::abs(r.mu() - want) > 1e-12)
                    throw std::logic_error("slab_view_direction disagrees with montecarlo");
                set.rows.push_back(r);
            }
            job += 1000;
            char line[160];
            std::snprintf(line, sizeof line, "slab tau = %g, sun zenith %g deg: %zu views, "
                          "%.1f s (%.0f s in all)", tau, zenith, L.size(), elapsed_since(t0),
                          elapsed_since(start));
            say(line);
        }

    set.metadata = {
        {"source", "cloudmath_lighting_error reference (tools/reference/truths/lighting_error_main.cpp)"},
        {"phase", o.phase},
        {"albedo", fmt(o.albedo)},
        {"paths_per_ray", std::to_string(o.paths) + " (more, up to " +
                              std::to_string(o.max_paths) + ", where the relative standard "
                              "error is above " + fmt(o.target_rel_error) + ")"},
        {"seed", std::to_string(o.seed)},
        {"units", "radiance L/F0 in 1/sr, sun irradiance F0 = 1, direct beam excluded"},
        {"frame", "sphere of radius 1 at the origin; slab between z = 0 (top, optical depth 0) "
                  "and its optical thickness below, sun in the x-z plane; dir = camera ray "
                  "direction, sun = unit vector toward the sun"},
    };
    return set;
}

void write_reference(const reference_set& set, const std::string& path) {
    std::ostringstream out;
    for (const auto& [k, v] : set.metadata) out << "# " << k << ": " << v << '\n';
    out << "geometry,tau,sun_deg,view_mu,view_phi_deg,u,origin_x,origin_y,origin_z,"
           "dir_x,dir_y,dir_z,sun_x,sun_y,sun_z,radiance,std_error,paths\n";
    for (const reference_row& r : set.rows) {
        out << r.geometry;
        for (double v : {r.tau, r.sun_deg, r.view_mu, r.view_phi_deg, r.u, r.origin.x,
                         r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.sun.x, r.sun.y,
                         r.sun.z, r.radiance, r.std_error})
            out << ',' << fmt(v);
        out << ',' << r.paths << '\n';
    }
    write_text_file_atomically(path, out.str());
}

reference_set read_reference(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open lighting reference " + path);
    reference_set set;
    std::string line;
    int number = 0;
    bool header = false;
    auto fail = [&](const std::string& why) {
        throw std::runtime_error(path + ":" + std::to_string(number) + ": " + why);
    };
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        if (line[0] == '#') {
            if (line.find(':') == std::string::npos) fail("metadata line without ':'");
            const auto [key, value] = parse_metadata_line(line);
            if (key == "phase") set.phase_spec = value;
            if (key == "albedo") {
                const std::optional<double> albedo = cloudmath::tools::parse_finite(value);
                if (!albedo || !(*albedo >= 0.0 && *albedo <= 1.0))
                    fail("albedo '" + value + "' is not a number in [0, 1]");
                set.albedo = *albedo;
            }
            set.metadata.emplace_back(key, value);
            continue;
        }
        if (!header) {
            if (line.rfind("geometry,tau,", 0) != 0) fail("expected the column header");
            header = true;
            continue;
        }
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
        if (f.size() != 18) fail("expected 18 columns, got " + std::to_string(f.size()));
        reference_row r;
        r.geometry = f[0];
        if (r.geometry != "sphere" && r.geometry != "slab_reflected" &&
            r.geometry != "slab_transmitted")
            fail("unknown geometry '" + r.geometry + "'");
        // Every cell the whole number, finite (strict_number.hpp): std::stod read "0.067xyz"
        // as 0.067 and accepted nan, std::stoull read "-5" paths as 2^64 - 5.
        static const char* const columns[16] = {"tau", "sun_deg", "view_mu", "view_phi_deg", "u",
                                                "origin_x", "origin_y", "origin_z", "dir_x", "dir_y",
                                                "dir_z", "sun_x", "sun_y", "sun_z", "radiance",
                                                "std_error"};
        double v[16];
        for (std::size_t i = 0; i < 16; ++i) {
            const std::optional<double> x = cloudmath::tools::parse_finite(f[i + 1]);
            if (!x) fail(std::string(columns[i]) + " '" + f[i + 1] + "' is not a finite number");
            v[i] = *x;
        }
        const std::optional<std::uint64_t> paths = cloudmath::tools::parse_integer<std::uint64_t>(f[17]);
        if (!paths || *paths == 0) fail("paths '" + f[17] + "' is not a whole number > 0");
        r.paths = *paths;
        r.tau = v[0];
        r.sun_deg = v[1];
        r.view_mu = v[2];
        r.view_phi_deg = v[3];
        r.u = v[4];
        r.origin = {v[5], v[6], v[7]};
        r.dir = {v[8], v[9], v[10]};
        r.sun = {v[11], v[12], v[13]};
        r.radiance = v[14];
        r.std_error = v[15];
        if (!(r.tau > 0.0) || !(std::abs(glm::length(r.dir) - 1.0) < 1e-9) ||
            !(std::abs(glm::length(r.sun) - 1.0) < 1e-9) || !(r.std_error >= 0.0) ||
            !std::isfinite(r.radiance))
            fail("values out of range");
        // A radiance is never negative (a Monte Carlo mean of non-negative path weights).
        if (!(r.radiance >= 0.0)) fail("radiance " + f[15] + " is negative");
        if (!r.is_sphere() && !(r.sun.z > 0.0)) fail("slab sun below the horizon");
        set.rows.push_back(r);
    }
    if (!header) throw std::runtime_error(path + ": no column header");
    if (set.rows.empty()) throw std::runtime_error(path + ": no rows");
    if (set.phase_spec.empty()) throw std::runtime_error(path + ": no '# phase:' line");
    return set;
}

ray_quadrature row_quadrature(const reference_row& r, double albedo, double panel) {
    if (r.is_sphere()) return sphere_quadrature(r.tau, albedo, r.sun, r.origin, r.dir, panel);
    return slab_quadrature(r.tau, r.sun.z, albedo, r.dir, panel);
}

std::string describe(const model_spec& s) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s N=%d a=%.4g b=%.4g c=%.4g", attenuation_name(s.form),
                  s.octaves, s.a, s.b, s.c);
    return buf;
}

evaluator::evaluator(const reference_set& set, double panel) {
    begin_.push_back(0);
    for (const reference_row& r : set.rows) {
        const ray_quadrature q = row_quadrature(r, set.albedo, panel);
        mu_.push_back(q.mu);
        const double w = 0.5 + 0.5 * q.mu;
        for (std::size_t k = 0; k < q.weight.size(); ++k) {
            weight_.push_back(q.weight[k]);
            tau_light_.push_back(q.tau_light[k]);
            // The Beer-Powder factor of sun_term, independent of a, b, c.
            powder_factor_.push_back(2.0 * cloudmath::powder(q.tau_light[k], 2.0) * (1.0 - w) + w);
        }
        begin_.push_back(weight_.size());
    }
}

std::vector<double> evaluator::radiance(const model_spec& s) const {
    const std::size_t n = mu_.size();
    const int N = std::max(s.octaves, 0);
    std::vector<double> out(n, 0.0), amp(static_cast<std::size_t>(N)),
        ext(static_cast<std::size_t>(N));
    for (std::size_t row = 0; row < n; ++row) {
        double ai = 1.0, bi = 1.0, ci = 1.0;
        for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
            amp[i] = bi * cloudmath::phase_hg(mu_[row], ci * s.g);
            ext[i] = ai;
            ai *= s.a;
            bi *= s.b;
            ci *= s.c;
        }
        double sum = 0.0;
        for (std::size_t k = begin_[row]; k < begin_[row + 1]; ++k) {
            const double t = tau_light_[k];
            double m = 0.0;
            for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i)
                m += amp[i] * (s.form == attenuation::nubis
                                   ? cloudmath::nubis_attenuation(ext[i] * t)
                                   : std::exp(-ext[i] * t));
            if (s.form == attenuation::powder) m *= powder_factor_[k];
            sum += weight_[k] * m;
        }
        out[row] = sum;
    }
    return out;
}

row_filter select_all() {
    return [](const reference_row&) { return true; };
}

bool row_counts(const reference_row& row, const row_filter& select) { return row.radiance > 0.0 && select(row); }

namespace {

// Per-row weights of the selection: 1 / (selected rows of the row's class), 0 if not
// selected or the reference is not > 0.
std::vector<double> selection_weights(const reference_set& set, const row_filter& select) {
    std::size_t sphere = 0, slab = 0;
    std::vector<bool> use(set.rows.size());
    for (std::size_t i = 0; i < set.rows.size(); ++i) {
        const reference_row& r = set.rows[i];
        use[i] = row_counts(r, select);
        if (use[i]) (r.is_sphere() ? sphere : slab) += 1;
    }
    std::vector<double> w(set.rows.size(), 0.0);
    for (std::size_t i = 0; i < set.rows.size(); ++i)
        if (use[i]) w[i] = 1.0 / static_cast<double>(set.rows[i].is_sphere() ? sphere : slab);
    return w;
}

}  // namespace

std::vector<double> image_means(const reference_set& set) {
    std::map<std::tuple<std::string, double, double>, std::pair<double, int>> sums;
    auto key = [](const reference_row& r) { return std::make_tuple(r.geometry, r.tau, r.sun_deg); };
    for (const reference_row& r : set.rows) {
        auto& [sum, n] = sums[key(r)];
        sum += r.radiance;
        ++n;
    }
    std::vector<double> out;
    out.reserve(set.rows.size());
    for (const reference_row& r : set.rows) {
        const auto& [sum, n] = sums[key(r)];
        out.push_back(sum / n);
    }
    return out;
}

error_summary measure(const reference_set& set, const std::vector<double>& model,
                      const row_filter& select) {
    if (model.size() != set.rows.size())
        throw std::invalid_argument("measure: one model value per reference row");
    const std::vector<double> w = selection_weights(set, select);
    const std::vector<double> mean = image_means(set);
    error_summary e;
    double wsum = 0.0, s1 = 0.0, s2 = 0.0;
    for (std::size_t i = 0; i < w.size(); ++i) {
        if (w[i] == 0.0) continue;
        const double r = (model[i] - set.rows[i].radiance) / mean[i];
        wsum += w[i];
        s1 += w[i] * r;
        s2 += w[i] * r * r;
        if (std::abs(r) > e.max || e.rows == 0) {
            e.max = std::abs(r);
            e.max_row = i;
        }
        ++e.rows;
    }
    if (e.rows == 0) return e;
    e.rms = std::sqrt(s2 / wsum);
    e.bias = s1 / wsum;
    return e;
}

double noise_floor(const reference_set& set, const row_filter& select) {
    const std::vector<double> w = selection_weights(set, select);
    const std::vector<double> mean = image_means(set);
    double wsum = 0.0, s2 = 0.0;
    for (std::size_t i = 0; i < w.size(); ++i) {
        if (w[i] == 0.0) continue;
        const double rel = set.rows[i].std_error / mean[i];
        wsum += w[i];
        s2 += w[i] * rel * rel;
    }
    return wsum > 0.0 ? std::sqrt(s2 / wsum) : 0.0;
}

lighting_fit fit_octaves(const evaluator& ev, const reference_set& set, attenuation form,
                         int octaves, double g, const row_filter& select,
                         const model_spec* start) {
    const std::vector<double> w = selection_weights(set, select);
    const std::vector<double> mean = image_means(set);
    double wsum = 0.0;
    for (double x : w) wsum += x;
    if (!(wsum > 0.0)) throw std::invalid_argument("fit_octaves: no row selected");
    lighting_fit best;
    best.spec = start ? *start : model_spec{form, g, 0.5, 0.5, 0.5, octaves};
    best.spec.form = form;
    best.spec.g = g;
    best.spec.octaves = octaves;
    auto residual = [&](const model_spec& s) {
        const std::vector<double> L = ev.radiance(s);
        double s2 = 0.0;
        for (std::size_t i = 0; i < w.size(); ++i) {
            if (w[i] == 0.0) continue;
            const double r = (L[i] - set.rows[i].radiance) / mean[i];
            s2 += w[i] * r * r;
        }
        return std::sqrt(s2 / wsum);
    };
    best.residual = residual(best.spec);
    best.evaluations = 1;
    if (octaves <= 1) return best;

    // x -> (0, 1) by the logistic function: every trial point is a valid model.
    auto logistic = [](double x) { return 1.0 / (1.0 + std::exp(-x)); };
    auto logit = [](double p) {
        p = std::clamp(p, 1e-9, 1.0 - 1e-9);
        return std::log(p / (1.0 - p));
    };
    auto spec_of = [&](const std::vector<double>& x) {
        model_spec s = best.spec;
        s.a = logistic(x[0]);
        s.b = logistic(x[1]);
        s.c = logistic(x[2]);
        return s;
    };
    // Starting points: the given one (or the production defaults), one with little
    // extinction scaling and strong contributions, one the other way round.
    std::vector<model_spec> starts{best.spec, model_spec{form, g, 0.8, 0.8, 0.5, octaves},
                                   model_spec{form, g, 0.2, 0.3, 0.8, octaves}};
    nelder_mead_options nm;
    nm.step = 0.7;
    nm.f_tolerance = 1e-9;
    nm.x_tolerance = 1e-6;
    nm.max_evaluations = 1500;
    nm.restarts = 2;
    for (const model_spec& s0 : starts) {
        const nelder_mead_result r = nelder_mead(
            [&](const std::vector<double>& x) { return residual(spec_of(x)); },
            {logit(s0.a), logit(s0.b), logit(s0.c)}, nm);
        best.evaluations += r.evaluations;
        if (r.value < best.residual) {
            best.residual = r.value;
            best.spec = spec_of(r.x);
        }
    }
    return best;
}

}  // namespace cloudmath::reference::lighting
