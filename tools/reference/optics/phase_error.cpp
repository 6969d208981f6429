// tools/reference/optics/phase_error.cpp: see phase_error.hpp. Comparison metrics, log-space fits
// with a Nelder-Mead minimiser, the report's model variants and the SVG plots.
#include "phase_error.hpp"

#include <algorithm>
#include <cloudmath/phase.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace cloudmath::reference {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double infinity = std::numeric_limits<double>::infinity();

double cos_deg(double theta) {
    // Exact values at the ends and the middle, as phase_table does.
    if (theta == 0.0) return 1.0;
    if (theta == 90.0) return 0.0;
    if (theta == 180.0) return -1.0;
    return std::cos(theta * (pi / 180.0));
}

// Index of the region holding angle theta (the last region includes its upper end).
std::size_t region_of(double theta) {
    const auto& regions = phase_error_regions();
    for (std::size_t r = 0; r < regions.size(); ++r)
        if (theta >= regions[r].theta_min_deg && theta < regions[r].theta_max_deg) return r;
    return regions.size() - 1;
}

// The comparison nodes: table angles and region boundaries, each interval subdivided.
std::vector<double> comparison_angles(const phase_table& table) {
    std::vector<double> breaks = table.theta_deg;
    for (const auto& r : phase_error_regions()) {
        breaks.push_back(r.theta_min_deg);
        breaks.push_back(r.theta_max_deg);
    }
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    std::vector<double> out;
    out.reserve(breaks.size() * compare_subdivisions);
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
        for (int k = 0; k < compare_subdivisions; ++k)
            out.push_back(breaks[i] + (breaks[i + 1] - breaks[i]) * k / compare_subdivisions);
    out.push_back(breaks.back());
    return out;
}

// ln(model / table) with the conventions of compare(): 0 when both are 0.
double log_ratio(double model, double table) {
    if (model == table) return 0.0;
    if (!(model > 0.0) || !(table > 0.0)) return infinity;
    return std::log(model / table);
}

double relative_error(double model, double table) {
    if (model == table) return 0.0;
    if (!(table > 0.0)) return infinity;
    return std::abs(model / table - 1.0);
}

// Integral over [0, h] of |d| for d linear from d0 to d1, crossings included.
double abs_linear_integral(double d0, double d1, double h) {
    if ((d0 >= 0.0 && d1 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0))
        return 0.5 * (std::abs(d0) + std::abs(d1)) * h;
    return h * (d0 * d0 + d1 * d1) / (2.0 * (std::abs(d0) + std::abs(d1)));
}

}  // namespace

const std::vector<angular_region>& phase_error_regions() {
    static const std::vector<angular_region> regions = {
        {"forward", 0.0, 5.0,
         "diffraction peak: about lambda/d rad wide (0.55 um / 12 um = 2.6 deg) with its "
         "first rings; about half of the scattered light"},
        {"side", 5.0, 160.0,
         "side scattering: the broad minimum near 100-120 deg and the cloud bow near 140 deg"},
        {"backward", 160.0, 180.0,
         "backscatter: the rise towards 180 deg and the glory within a few degrees of it"},
    };
    return regions;
}

// ---------------------------------------------------------------------------------------
phase_comparison compare(const phase_table& table, const phase_function& model) {
    const auto& regions = phase_error_regions();
    const std::vector<double> theta = comparison_angles(table);
    const std::size_t n = theta.size();
    std::vector<double> mu(n), pt(n), pm(n);
    for (std::size_t i = 0; i < n; ++i) {
        mu[i] = cos_deg(theta[i]);
        pt[i] = table.evaluate(mu[i]);
        pm[i] = model(mu[i]);
    }

    phase_comparison c;
    c.regions.resize(regions.size());
    std::vector<double> solid_angle(regions.size(), 0.0), log_sq(regions.size(), 0.0);
    for (std::size_t r = 0; r < regions.size(); ++r) c.regions[r].region = regions[r];

    // Maxima over the nodes.
    for (std::size_t i = 0; i < n; ++i) {
        region_error& e = c.regions[region_of(theta[i])];
        const double rel = relative_error(pm[i], pt[i]);
        if (rel > e.max_rel_error) {
            e.max_rel_error = rel;
            e.max_at_deg = theta[i];
        }
    }
    // Integrals over the intervals (theta ascending, so mu descending).
    double model_integral = 0.0, model_first_moment = 0.0, misdirected = 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double h = mu[i] - mu[i + 1];
        const std::size_t r = region_of(0.5 * (theta[i] + theta[i + 1]));
        const double l0 = log_ratio(pm[i], pt[i]), l1 = log_ratio(pm[i + 1], pt[i + 1]);
        solid_angle[r] += h;
        log_sq[r] += 0.5 * (l0 * l0 + l1 * l1) * h;
        c.regions[r].table_energy += 0.5 * (pt[i] + pt[i + 1]) * h;
        const double wrong = abs_linear_integral(pm[i] - pt[i], pm[i + 1] - pt[i + 1], h);
        c.regions[r].misdirected += wrong;
        misdirected += wrong;
        model_integral += 0.5 * (pm[i] + pm[i + 1]) * h;
        // Exact first moment of the linear interpolant on [m0, m1] (as phase_table does).
        const double m0 = mu[i + 1], m1 = mu[i], p0 = pm[i + 1], p1 = pm[i];
        model_first_moment += h / 6.0 * (p0 * (2.0 * m0 + m1) + p1 * (m0 + 2.0 * m1));
    }
    for (std::size_t r = 0; r < regions.size(); ++r) {
        region_error& e = c.regions[r];
        e.rms_factor =
            solid_angle[r] > 0.0 ? std::expm1(std::sqrt(log_sq[r] / solid_angle[r])) : 0.0;
        e.misdirected *= pi;  // 0.5 * 2 pi
        e.table_energy *= 2.0 * pi;
    }
    c.misdirected_energy = pi * misdirected;
    c.model_integral = 2.0 * pi * model_integral;
    c.model_mean_cosine = model_integral > 0.0 ? model_first_moment / model_integral : 0.0;
    c.table_integral = table.integral();
    c.table_mean_cosine = table.mean_cosine() / table.integral();
    return c;
}

// ---------------------------------------------------------------------------------------
log_fit_target make_fit_target(const phase_table& table) {
    log_fit_target t;
    const std::vector<double>& th = table.theta_deg;
    const std::size_t n = th.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!(table.phase[i] > 0.0)) continue;
        const double lo = i > 0 ? th[i - 1] : th[i];
        const double hi = i + 1 < n ? th[i + 1] : th[i];
        t.mu.push_back(cos_deg(th[i]));
        t.log_phase.push_back(std::log(table.phase[i]));
        t.weight.push_back(0.5 * (hi - lo));
        t.weight_sum += 0.5 * (hi - lo);
    }
    if (t.mu.empty() || !(t.weight_sum > 0.0))
        throw std::invalid_argument("phase table has no positive values to fit");
    t.mean_cosine = table.mean_cosine() / table.integral();
    return t;
}

namespace {

// sum w r^2 / sum w for a callable model; infinite when the model is not > 0 somewhere.
template <class F>
double mean_square_log(const log_fit_target& t, F&& model) {
    double s = 0.0;
    for (std::size_t i = 0; i < t.mu.size(); ++i) {
        const double v = model(t.mu[i]);
        if (!(v > 0.0) || !std::isfinite(v)) return infinity;
        const double r = std::log(v) - t.log_phase[i];
        s += t.weight[i] * r * r;
    }
    return s / t.weight_sum;
}

}  // namespace

double log_residual(const log_fit_target& target, const phase_function& model) {
    return std::sqrt(mean_square_log(target, model));
}

// ---------------------------------------------------------------------------------------
namespace {

// One Nelder-Mead run from x0; returns the best vertex.
nelder_mead_result simplex_run(const std::function<double(const std::vector<double>&)>& f,
                               const std::vector<double>& x0, const nelder_mead_options& o) {
    const std::size_t n = x0.size();
    std::vector<std::vector<double>> x(n + 1, x0);
    std::vector<double> v(n + 1);
    int evaluations = 0;
    auto eval = [&](const std::vector<double>& p) {
        ++evaluations;
        const double y = f(p);
        return std::isnan(y) ? infinity : y;  // NaN would break every comparison below
    };
    for (std::size_t k = 0; k < n; ++k) x[k + 1][k] += o.step;
    for (std::size_t i = 0; i <= n; ++i) v[i] = eval(x[i]);

    std::vector<std::size_t> order(n + 1);
    std::vector<double> centroid(n), trial(n), trial2(n);
    auto along = [&](double t, const std::vector<double>& from, std::vector<double>& out) {
        // out = centroid + t (centroid - from)
        for (std::size_t k = 0; k < n; ++k) out[k] = centroid[k] + t * (centroid[k] - from[k]);
    };
    while (true) {
        std::iota(order.begin(), order.end(), std::size_t{0});
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
        const std::size_t best = order.front(), worst = order.back(), second = order[n - 1];
        double diameter = 0.0;
        for (std::size_t i = 0; i <= n; ++i)
            for (std::size_t k = 0; k < n; ++k)
                diameter = std::max(diameter, std::abs(x[i][k] - x[best][k]));
        const bool flat = v[worst] - v[best] <= o.f_tolerance || v[worst] == v[best];
        if ((flat && diameter <= o.x_tolerance) || evaluations >= o.max_evaluations) break;

        std::fill(centroid.begin(), centroid.end(), 0.0);
        for (std::size_t i = 0; i <= n; ++i)
            if (i != worst)
                for (std::size_t k = 0; k < n; ++k) centroid[k] += x[i][k] / static_cast<double>(n);

        along(1.0, x[worst], trial);  // reflection
        const double vr = eval(trial);
        if (vr < v[best]) {
            along(2.0, x[worst], trial2);  // expansion
            const double ve = eval(trial2);
            if (ve < vr) {
                x[worst] = trial2;
                v[worst] = ve;
            } else {
                x[worst] = trial;
                v[worst] = vr;
            }
            continue;
        }
        if (vr < v[second]) {
            x[worst] = trial;
            v[worst] = vr;
            continue;
        }
        // Contraction: outside when the reflection beat the worst point, inside otherwise.
        const bool outside = vr < v[worst];
        if (outside)
            along(0.5, x[worst], trial2);
        else
            along(-0.5, x[worst], trial2);
        const double vc = eval(trial2);
        if (outside ? vc <= vr : vc < v[worst]) {
            x[worst] = trial2;
            v[worst] = vc;
            continue;
        }
        // Shrink towards the best vertex.
        for (std::size_t i = 0; i <= n; ++i) {
            if (i == best) continue;
            for (std::size_t k = 0; k < n; ++k) x[i][k] = x[best][k] + 0.5 * (x[i][k] - x[best][k]);
            v[i] = eval(x[i]);
        }
    }
    const auto best = static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
    return {x[best], v[best], evaluations};
}

}  // namespace

nelder_mead_result nelder_mead(const std::function<double(const std::vector<double>&)>& f,
                               std::vector<double> x0, const nelder_mead_options& options) {
    nelder_mead_result best = simplex_run(f, x0, options);
    for (int restart = 0; restart < options.restarts; ++restart) {
        const nelder_mead_result again = simplex_run(f, best.x, options);
        const int evaluations = best.evaluations + again.evaluations;
        const double improvement = best.value - again.value;
        if (again.value < best.value) best = again;
        best.evaluations = evaluations;
        if (!(improvement > options.f_tolerance)) break;
    }
    return best;
}

// ---------------------------------------------------------------------------------------
namespace {

// How each model parameter maps to the minimiser's unconstrained coordinate.
enum class param_kind { eccentricity, weight, positive };

double decode(param_kind kind, double x) {
    switch (kind) {
        case param_kind::eccentricity:
            return phase_g_max<double> * std::tanh(x);
        case param_kind::weight:
            return 1.0 / (1.0 + std::exp(-x));
        case param_kind::positive:
            return std::exp(x);
    }
    return x;
}

double encode(param_kind kind, double value) {
    switch (kind) {
        case param_kind::eccentricity:
            return std::atanh(std::clamp(value / phase_g_max<double>, -0.999999, 0.999999));
        case param_kind::weight: {
            const double w = std::clamp(value, 1e-6, 1.0 - 1e-6);
            return std::log(w / (1.0 - w));
        }
        case param_kind::positive:
            return std::log(std::max(value, 1e-12));
    }
    return value;
}

// Fits eval(mu, parameters) from every start (natural units) and keeps the best.
template <class Eval>
fit_result fit_model(const log_fit_target& t, const std::vector<param_kind>& kinds,
                     const std::vector<std::vector<double>>& starts, Eval eval) {
    const std::size_t n = kinds.size();
    auto to_natural = [&](const std::vector<double>& x) {
        std::vector<double> p(n);
        for (std::size_t k = 0; k < n; ++k) p[k] = decode(kinds[k], x[k]);
        return p;
    };
    const auto objective = [&](const std::vector<double>& x) {
        const std::vector<double> p = to_natural(x);
        return mean_square_log(t, [&](double mu) { return eval(mu, p); });
    };
    nelder_mead_options options;
    options.max_evaluations = 1500 * static_cast<int>(n);
    fit_result result;
    double best = infinity;
    for (const auto& start : starts) {
        std::vector<double> x0(n);
        for (std::size_t k = 0; k < n; ++k) x0[k] = encode(kinds[k], start[k]);
        const nelder_mead_result r = nelder_mead(objective, x0, options);
        result.evaluations += r.evaluations;
        if (r.value < best || result.parameters.empty()) {
            best = r.value;
            result.parameters = to_natural(r.x);
        }
    }
    result.residual = std::sqrt(best);
    return result;
}

// A few starting eccentricities for one-lobe models.
std::vector<std::vector<double>> one_lobe_starts(const log_fit_target& t) {
    return {{t.mean_cosine}, {0.3}, {0.7}, {0.9}, {0.97}};
}

}  // namespace

fit_result fit_hg(const log_fit_target& t) {
    return fit_model(t, {param_kind::eccentricity}, one_lobe_starts(t),
                     [](double mu, const std::vector<double>& p) { return phase_hg(mu, p[0]); });
}

fit_result fit_hg_dual(const log_fit_target& t) {
    std::vector<std::vector<double>> starts;
    for (double g0 : {0.9, 0.97})
        for (double g1 : {-0.3, 0.3, 0.6})
            for (double w : {0.2, 0.5}) starts.push_back({g0, g1, w});
    fit_result r =
        fit_model(t, {param_kind::eccentricity, param_kind::eccentricity, param_kind::weight},
                  starts, [](double mu, const std::vector<double>& p) {
                      return phase_hg_dual(mu, p[0], p[1], p[2]);
                  });
    // (g0, g1, w) and (g1, g0, 1 - w) are the same function: report the forward lobe first.
    if (r.parameters[0] < r.parameters[1]) {
        std::swap(r.parameters[0], r.parameters[1]);
        r.parameters[2] = 1.0 - r.parameters[2];
    }
    return r;
}

fit_result fit_cornette_shanks(const log_fit_target& t) {
    return fit_model(
        t, {param_kind::eccentricity}, one_lobe_starts(t),
        [](double mu, const std::vector<double>& p) { return phase_cornette_shanks(mu, p[0]); });
}

fit_result fit_draine(const log_fit_target& t) {
    std::vector<std::vector<double>> starts;
    for (double g : {0.5, 0.8, 0.95})
        for (double alpha : {0.5, 5.0, 50.0}) starts.push_back({g, alpha});
    return fit_model(
        t, {param_kind::eccentricity, param_kind::positive}, starts,
        [](double mu, const std::vector<double>& p) { return phase_draine(mu, p[0], p[1]); });
}

fit_result fit_mie_approx_diameter(const log_fit_target& t) {
    return fit_model(
        t, {param_kind::positive}, {{2.0}, {5.0}, {10.0}, {20.0}, {40.0}},
        [](double mu, const std::vector<double>& p) { return phase_mie_approx(mu, p[0]); });
}

fit_result fit_mie_approx_parameters(const log_fit_target& t) {
    // The published fit at several sizes, and one generic start off that curve.
    std::vector<std::vector<double>> starts;
    for (double d : {4.0, 8.0, 12.0, 16.0, 24.0, 40.0}) {
        const auto p = mie_approx_params(d);
        starts.push_back({p.g_hg, p.g_draine, p.alpha, p.w_draine});
    }
    starts.push_back({0.95, 0.5, 10.0, 0.3});
    return fit_model(
        t,
        {param_kind::eccentricity, param_kind::eccentricity, param_kind::positive,
         param_kind::weight},
        starts, [](double mu, const std::vector<double>& p) {
            return phase_mie_approx(mu, mie_approx_parameters<double>{p[0], p[1], p[2], p[3]});
        });
}

double cornette_shanks_mean_cosine(double g) {
    return 3.0 * g * (4.0 + g * g) / (5.0 * (2.0 + g * g));
}

double cornette_shanks_g_for_mean_cosine(double mean_cosine) {
    // Bisection: the mean cosine increases with g (derivative 3 (8 + 2 g^2 + g^4) /
    // (5 (2 + g^2)^2) > 0) from -1 at g = -1 to 1 at g = 1.
    double lo = -1.0, hi = 1.0;
    for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi) break;
        (cornette_shanks_mean_cosine(mid) < mean_cosine ? lo : hi) = mid;
    }
    return std::clamp(0.5 * (lo + hi), -phase_g_max<double>, phase_g_max<double>);
}

// ---------------------------------------------------------------------------------------
std::vector<phase_variant> phase_variants(const phase_table& table, double r_eff_um,
                                          const std::function<void(double)>& progress) {
    const log_fit_target target = make_fit_target(table);
    const double mean_cosine = target.mean_cosine;
    std::vector<phase_variant> out;
    constexpr double steps = 8.0;  // fits below, for the progress fraction
    double done = 0.0;
    auto report = [&] {
        done += 1.0;
        if (progress) progress(std::min(1.0, done / steps));
    };
    auto add = [&](std::string id, std::string function, std::string label, std::string method,
                   std::vector<std::pair<std::string, double>> parameters, phase_function model) {
        phase_variant v{std::move(id),     std::move(function),   std::move(label),
                        std::move(method), std::move(parameters), 0.0,
                        std::move(model)};
        v.residual = log_residual(target, v.model);
        out.push_back(std::move(v));
    };

    const double g_moment = std::clamp(mean_cosine, -phase_g_max<double>, phase_g_max<double>);
    add("hg_moment", "phase_hg", "HG, g = table mean cosine", "moment matched", {{"g", g_moment}},
        [g_moment](double mu) { return phase_hg(mu, g_moment); });
    const fit_result hg = fit_hg(target);
    report();
    const double g_hg = hg.parameters[0];
    add("hg_fit", "phase_hg", "HG, g fitted", "fitted", {{"g", g_hg}},
        [g_hg](double mu) { return phase_hg(mu, g_hg); });

    add("dual_frostbite", "phase_hg_dual", "Dual-lobe HG, Frostbite example", "published example",
        {{"g0", 0.8}, {"g1", -0.5}, {"w", 0.5}},
        [](double mu) { return phase_hg_dual(mu, 0.8, -0.5, 0.5); });
    const fit_result dual = fit_hg_dual(target);
    report();
    const double g0 = dual.parameters[0], g1 = dual.parameters[1], w = dual.parameters[2];
    add("dual_fit", "phase_hg_dual", "Dual-lobe HG, fitted", "fitted",
        {{"g0", g0}, {"g1", g1}, {"w", w}},
        [g0, g1, w](double mu) { return phase_hg_dual(mu, g0, g1, w); });

    // Schlick's rational stand-in for HG with the same g (k = k(g), cloudmath's
    // phase_hg_schlick): what a renderer gets when it swaps HG for the cheaper form.
    add("schlick_moment", "phase_hg_schlick", "Schlick, k(g), g = table mean cosine",
        "moment matched", {{"g", g_moment}},
        [g_moment](double mu) { return phase_hg_schlick(mu, g_moment); });

    const double g_cs_moment = cornette_shanks_g_for_mean_cosine(mean_cosine);
    add("cs_moment", "phase_cornette_shanks", "Cornette-Shanks, mean cosine matched",
        "moment matched", {{"g", g_cs_moment}},
        [g_cs_moment](double mu) { return phase_cornette_shanks(mu, g_cs_moment); });
    const fit_result cs = fit_cornette_shanks(target);
    report();
    const double g_cs = cs.parameters[0];
    add("cs_fit", "phase_cornette_shanks", "Cornette-Shanks, g fitted", "fitted", {{"g", g_cs}},
        [g_cs](double mu) { return phase_cornette_shanks(mu, g_cs); });

    const fit_result draine = fit_draine(target);
    report();
    const double g_d = draine.parameters[0], alpha = draine.parameters[1];
    add("draine_fit", "phase_draine", "Draine, fitted", "fitted", {{"g", g_d}, {"alpha", alpha}},
        [g_d, alpha](double mu) { return phase_draine(mu, g_d, alpha); });

    if (r_eff_um > 0.0) {
        const double d = 2.0 * r_eff_um;
        const auto p = mie_approx_params(d);
        add("mie_approx_d2reff", "phase_mie_approx", "Jendersie-d'Eon, d = 2 r_eff",
            "size = 2 r_eff",
            {{"d_um", d},
             {"g_hg", p.g_hg},
             {"g_draine", p.g_draine},
             {"alpha", p.alpha},
             {"w_draine", p.w_draine}},
            [p](double mu) { return phase_mie_approx(mu, p); });
    }
    report();
    const fit_result mie_d = fit_mie_approx_diameter(target);
    report();
    {
        const double d = mie_d.parameters[0];
        const auto p = mie_approx_params(d);
        add("mie_approx_dfit", "phase_mie_approx", "Jendersie-d'Eon, d fitted", "fitted",
            {{"d_um", std::min(d, 50.0)},
             {"g_hg", p.g_hg},
             {"g_draine", p.g_draine},
             {"alpha", p.alpha},
             {"w_draine", p.w_draine}},
            [p](double mu) { return phase_mie_approx(mu, p); });
    }
    const fit_result mie4 = fit_mie_approx_parameters(target);
    report();
    {
        const mie_approx_parameters<double> p{mie4.parameters[0], mie4.parameters[1],
                                              mie4.parameters[2], mie4.parameters[3]};
        add("mie_approx_fit", "phase_mie_approx", "Jendersie-d'Eon form, 4 parameters fitted",
            "fitted",
            {{"g_hg", p.g_hg},
             {"g_draine", p.g_draine},
             {"alpha", p.alpha},
             {"w_draine", p.w_draine}},
            [p](double mu) { return phase_mie_approx(mu, p); });
    }
    report();
    return out;
}

// ---------------------------------------------------------------------------------------
// SVG.
std::string xml_escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char ch : text) {
        switch (ch) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                out += ch;
        }
    }
    return out;
}

namespace {

struct point {
    double x, y;
};

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    std::string s = buf;
    if (s == "-0.0") s = "0.0";
    return s;
}

// Distance of p from the segment a-b.
double segment_distance(point p, point a, point b) {
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double len2 = dx * dx + dy * dy;
    double t = len2 > 0.0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// Ramer-Douglas-Peucker with an explicit stack; keeps the end points.
std::vector<point> simplify(const std::vector<point>& in, double tolerance) {
    if (in.size() <= 2) return in;
    std::vector<char> keep(in.size(), 0);
    keep.front() = keep.back() = 1;
    std::vector<std::pair<std::size_t, std::size_t>> stack{{0, in.size() - 1}};
    while (!stack.empty()) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        double worst = -1.0;
        std::size_t at = a;
        for (std::size_t i = a + 1; i < b; ++i) {
            const double d = segment_distance(in[i], in[a], in[b]);
            if (d > worst) {
                worst = d;
                at = i;
            }
        }
        if (worst > tolerance) {
            keep[at] = 1;
            stack.emplace_back(a, at);
            stack.emplace_back(at, b);
        }
    }
    std::vector<point> out;
    for (std::size_t i = 0; i < in.size(); ++i)
        if (keep[i]) out.push_back(in[i]);
    return out;
}

// Simplifies with 0.2 px tolerance, coarser until at most max_points remain.
std::vector<point> decimate(const std::vector<point>& in, std::size_t max_points) {
    double tolerance = 0.2;
    std::vector<point> out = simplify(in, tolerance);
    while (out.size() > max_points) {
        tolerance *= 1.5;
        out = simplify(in, tolerance);
    }
    return out;
}

class svg_builder {
public:
    svg_builder(int width, int height) {
        text_ = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) +
                "\" height=\"" + std::to_string(height) + "\" viewBox=\"0 0 " +
                std::to_string(width) + " " + std::to_string(height) +
                "\" font-family=\"sans-serif\" font-size=\"12\">\n"
                "<rect width=\"" +
                std::to_string(width) + "\" height=\"" + std::to_string(height) +
                "\" fill=\"white\"/>\n";
    }
    void line(point a, point b, const std::string& stroke, double width,
              const std::string& dash = "") {
        text_ += "<line x1=\"" + num(a.x) + "\" y1=\"" + num(a.y) + "\" x2=\"" + num(b.x) +
                 "\" y2=\"" + num(b.y) + "\" stroke=\"" + stroke + "\" stroke-width=\"" +
                 num(width) + "\"" + dash_attribute(dash) + "/>\n";
    }
    void circle(point c, double r, const std::string& stroke) {
        text_ += "<circle cx=\"" + num(c.x) + "\" cy=\"" + num(c.y) + "\" r=\"" + num(r) +
                 "\" fill=\"none\" stroke=\"" + stroke + "\" stroke-width=\"1.0\"/>\n";
    }
    // anchor: start, middle or end; body is raw SVG text content (already escaped).
    void text(point at, const std::string& anchor, const std::string& body,
              const std::string& extra = "") {
        text_ += "<text x=\"" + num(at.x) + "\" y=\"" + num(at.y) + "\" text-anchor=\"" + anchor +
                 "\"" + extra + ">" + body + "</text>\n";
    }
    void polyline(const std::vector<point>& pts, const plot_curve& c) {
        text_ += "<polyline fill=\"none\" stroke=\"" + xml_escape(c.colour) + "\" stroke-width=\"" +
                 num(c.width) + "\" stroke-linejoin=\"round\"" + dash_attribute(c.dash) +
                 " points=\"";
        for (std::size_t i = 0; i < pts.size(); ++i) {
            if (i) text_ += ' ';
            text_ += num(pts[i].x) + "," + num(pts[i].y);
        }
        text_ += "\"/>\n";
    }
    void legend(point at, const std::vector<plot_curve>& curves) {
        for (std::size_t i = 0; i < curves.size(); ++i) {
            const double y = at.y + 18.0 * static_cast<double>(i);
            text_ += "<line x1=\"" + num(at.x) + "\" y1=\"" + num(y) + "\" x2=\"" +
                     num(at.x + 26.0) + "\" y2=\"" + num(y) + "\" stroke=\"" +
                     xml_escape(curves[i].colour) + "\" stroke-width=\"" + num(curves[i].width) +
                     "\"" + dash_attribute(curves[i].dash) + "/>\n";
            text({at.x + 32.0, y + 4.0}, "start", xml_escape(curves[i].label));
        }
    }
    std::string finish() { return text_ + "</svg>\n"; }

private:
    static std::string dash_attribute(const std::string& dash) {
        return dash.empty() ? "" : " stroke-dasharray=\"" + xml_escape(dash) + "\"";
    }
    std::string text_;
};

// The title, centred at x: its first line large, further lines ('\n'-separated) smaller.
void title_lines(svg_builder& svg, double x, const std::string& title) {
    std::size_t begin = 0;
    double y = 20.0;
    for (bool first = true;; first = false) {
        const std::size_t end = title.find('\n', begin);
        const std::string line = title.substr(begin, end == std::string::npos ? end : end - begin);
        svg.text({x, y}, "middle", xml_escape(line),
                 first ? " font-size=\"14\"" : " font-size=\"11\"");
        if (end == std::string::npos) break;
        begin = end + 1;
        y += 15.0;
    }
}

// "10" with a superscript exponent.
std::string decade_label(int k) {
    return "10<tspan dy=\"-6\" font-size=\"9\">" + std::to_string(k) + "</tspan>";
}

// Decades [lo, hi] covering the positive values of the curves with theta <= theta_max.
std::pair<int, int> decade_range(const std::vector<plot_curve>& curves, double theta_max,
                                 int max_decades) {
    double vmin = infinity, vmax = 0.0;
    for (const auto& c : curves)
        for (std::size_t i = 0; i < c.theta_deg.size() && i < c.phase.size(); ++i) {
            if (c.theta_deg[i] > theta_max || !(c.phase[i] > 0.0) || !std::isfinite(c.phase[i]))
                continue;
            vmin = std::min(vmin, c.phase[i]);
            vmax = std::max(vmax, c.phase[i]);
        }
    if (!(vmax > 0.0)) return {-1, 0};
    const int hi = static_cast<int>(std::ceil(std::log10(vmax) - 1e-9));
    int lo = static_cast<int>(std::floor(std::log10(vmin) + 1e-9));
    lo = std::max(lo, hi - max_decades);
    if (lo >= hi) lo = hi - 1;
    return {lo, hi};
}

}  // namespace

std::string svg_phase_cartesian(const std::vector<plot_curve>& curves, const std::string& title,
                                double theta_max_deg) {
    const double left = 70.0, right = 620.0, top = 52.0, bottom = 440.0;
    svg_builder svg(960, 490);
    const auto [lo, hi] = decade_range(curves, theta_max_deg, 9);
    auto to_x = [&](double theta) { return left + (right - left) * theta / theta_max_deg; };
    auto to_y = [&](double p) {
        const double l = p > 0.0 ? std::log10(p) : -infinity;
        const double t = std::clamp((l - lo) / (hi - lo), 0.0, 1.0);
        return bottom - (bottom - top) * t;
    };
    title_lines(svg, (left + right) / 2.0, title);
    // Grid: decades horizontally, a readable angle step vertically.
    for (int k = lo; k <= hi; ++k) {
        const double y = to_y(std::pow(10.0, k));
        svg.line({left, y}, {right, y}, "#cccccc", 1.0);
        svg.text({left - 6.0, y + 4.0}, "end", decade_label(k));
    }
    double step = 60.0;
    for (double s : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 60.0})
        if (theta_max_deg / s <= 10.0) {
            step = s;
            break;
        }
    for (int i = 0; i * step <= theta_max_deg + 1e-9; ++i) {
        const double theta = i * step, x = to_x(theta);
        svg.line({x, top}, {x, bottom}, "#cccccc", 1.0);
        char label[32];
        std::snprintf(label, sizeof label, "%g", theta);
        svg.text({x, bottom + 16.0}, "middle", label);
    }
    svg.line({left, top}, {left, bottom}, "black", 1.0);
    svg.line({left, bottom}, {right, bottom}, "black", 1.0);
    svg.text({(left + right) / 2.0, bottom + 36.0}, "middle", "scattering angle (deg)");
    svg.text({18.0, (top + bottom) / 2.0}, "middle", "phase (1/sr), log scale",
             " transform=\"rotate(-90 18 " + num((top + bottom) / 2.0) + ")\"");
    for (const auto& c : curves) {
        std::vector<point> pts;
        for (std::size_t i = 0; i < c.theta_deg.size() && i < c.phase.size(); ++i)
            if (c.theta_deg[i] <= theta_max_deg + 1e-12)
                pts.push_back({to_x(c.theta_deg[i]), to_y(c.phase[i])});
        svg.polyline(decimate(pts, svg_max_points_per_curve), c);
    }
    svg.legend({right + 24.0, top + 10.0}, curves);
    return svg.finish();
}

std::string svg_phase_polar(const std::vector<plot_curve>& curves, const std::string& title,
                            double floor_per_sr) {
    const point centre{310.0, 340.0};
    const double radius = 270.0;
    svg_builder svg(960, 660);
    const int hi = decade_range(curves, 180.0, 60).second;
    const double floor_log = std::log10(floor_per_sr);
    const double top_log = std::max(static_cast<double>(hi), floor_log + 1.0);
    auto to_r = [&](double p) {
        const double l = p > 0.0 ? std::log10(p) : -infinity;
        return radius * std::clamp((l - floor_log) / (top_log - floor_log), 0.0, 1.0);
    };
    title_lines(svg, centre.x, title);
    const int first_decade = static_cast<int>(std::ceil(floor_log - 1e-9));
    for (int k = first_decade; k <= hi; ++k)
        if (to_r(std::pow(10.0, k)) > 0.0) svg.circle(centre, to_r(std::pow(10.0, k)), "#cccccc");
    for (int a = 0; a <= 180; a += 30) {
        const double t = a * pi / 180.0, c = std::cos(t), s = std::sin(t);
        svg.line({centre.x - radius * c, centre.y}, {centre.x + radius * c, centre.y}, "#cccccc",
                 1.0);
        svg.line(centre, {centre.x + radius * c, centre.y - radius * s}, "#cccccc", 1.0);
        svg.line(centre, {centre.x + radius * c, centre.y + radius * s}, "#cccccc", 1.0);
        const std::string label = std::to_string(a) + "&#176;";
        svg.text({centre.x + (radius + 16.0) * c, centre.y - (radius + 16.0) * s + 4.0}, "middle",
                 label, " font-size=\"11\"");
    }
    char scale[160];
    std::snprintf(scale, sizeof scale,
                  "radius: log10 phase, %g /sr (centre) to %g /sr; forward scattering to the right",
                  floor_per_sr, std::pow(10.0, top_log));
    svg.text({centre.x, centre.y + radius + 30.0}, "middle", scale, " font-size=\"11\"");
    for (const auto& c : curves) {
        std::vector<point> upper;
        for (std::size_t i = 0; i < c.theta_deg.size() && i < c.phase.size(); ++i) {
            const double t = c.theta_deg[i] * pi / 180.0, r = to_r(c.phase[i]);
            upper.push_back({centre.x + r * std::cos(t), centre.y - r * std::sin(t)});
        }
        // Upper half 0 -> 180 deg, then its mirror image back to 0: one closed polyline.
        std::vector<point> loop = decimate(upper, svg_max_points_per_curve / 2);
        for (std::size_t i = loop.size(); i-- > 0;)
            loop.push_back({loop[i].x, 2.0 * centre.y - loop[i].y});
        svg.polyline(loop, c);
    }
    // Decade labels along the lower vertical radius (clear of the angle labels), over the
    // curves with a white halo.
    for (int k = first_decade; k <= hi; ++k) {
        const double r = to_r(std::pow(10.0, k));
        if (r > 0.0)
            svg.text({centre.x + 3.0, centre.y + r - 3.0}, "start", decade_label(k),
                     " font-size=\"10\" fill=\"#555555\" stroke=\"white\" "
                     "stroke-width=\"3\" paint-order=\"stroke\"");
    }
    svg.legend({640.0, 70.0}, curves);
    return svg.finish();
}

}  // namespace cloudmath::reference
