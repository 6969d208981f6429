// Speed against error of every lighting variant cloudmath offers, and of the textbook forms
// it replaces: for each variant the float time per evaluation (scalar calls, and the batch
// form where batch.hpp has one) and the maximum and RMS relative error against a long
// double (or quad, where the textbook form cancels) reference over the documented domain and
// its hard cases. Writes docs/speed_vs_error.md (table), .csv (the same data) and .svg (a
// log-log plot with the Pareto front of each family of interchangeable variants).
//
// Usage: cloudmath_speed_vs_error [--out-dir DIR] [--glsl-cost FILE] [--phase-error FILE]
//                                 [--lighting-error FILE] [--command TEXT] [--quick]
//   --out-dir    where speed_vs_error.{md,csv,svg} go (default: <source>/docs)
//   --glsl-cost  docs/glsl_cost.md, parsed for the SPIR-V instruction counts
//   --phase-error, --lighting-error  docs/phase_error.csv and docs/lighting_error.csv, the
//                errors against the physical references (tools/reference)
//   --command    the command line quoted in the report (scripts/speed-vs-error.sh passes it)
//   --quick      fewer timing rounds (for a smoke test; the numbers are noisier)
// scripts/speed-vs-error.sh builds this in a Release tree and runs it.
//
// Every number in the outputs is measured here; nothing is typed in. Times: median over
// interleaved rounds (each round times every variant once, in a shuffled order), so a burst
// of load on a shared machine hits all variants alike. The timed loops and the batch calls
// are in kernels.cpp (see kernels.hpp for why).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cloudmath/batch.hpp>
#include <cloudmath/cloudmath.hpp>
#include <cloudmath/fast_math.hpp>

#include "atomic_file.hpp"
#include "kernels.hpp"
#include "naive.hpp"
#include "speed_vs_error_build_info.hpp"

namespace cm = cloudmath;

namespace {

using cm_report::pass_inputs;
namespace kernels = cm_report::kernels;

using ld = long double;
// Quad precision (GCC's __float128) for the references whose textbook form cancels even in
// long double; __extension__ keeps -Wpedantic quiet.
__extension__ typedef __float128 quad;

const ld PI = 3.141592653589793238462643383279502884L;
const double nan_value = std::numeric_limits<double>::quiet_NaN();
// Relative errors are |got - ref| / max(|ref|, 1e-20): results below 1e-20 (a transmittance
// of exp(-46)) are judged by their absolute error. They are invisible in any image, and float
// has no relative precision left near its denormals (1.2e-38): std::exp returns denormals
// and 0 there, exp_vectorizable clamps at 1.2e-38, and a phase value of 1e5 times a denormal
// transmittance keeps only a few bits. Above the floor every digit counts.
const ld error_floor_ref = 1e-20L;
// The plot's y floor: errors below it (exact within rounding would be ~6e-8) are drawn here.
const double plot_error_floor = 1e-9;

// Deterministic uniform numbers (SplitMix64).
struct splitmix64 {
    std::uint64_t state;
    explicit splitmix64(std::uint64_t seed) : state(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    float uniform(double lo, double hi) { return static_cast<float>(lo + (hi - lo) * uniform()); }
    float log_uniform(double lo, double hi) {
        return static_cast<float>(std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * uniform()));
    }
};

// ---------------------------------------------------------------------------------------
// Formatting.
std::string printf_string(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}
std::string fmt_input(double v) { return printf_string("%.7g", v); }
std::string fmt_error(double e) {
    if (std::isnan(e)) return "-";
    if (std::isinf(e)) return "inf";
    if (e == 0) return "0";
    return printf_string("%.1e", e);
}
std::string fmt_ns(double ns) {
    if (std::isnan(ns)) return "-";
    if (ns < 10) return printf_string("%.2f", ns);
    if (ns < 100) return printf_string("%.1f", ns);
    return printf_string("%.0f", ns);
}

// ---------------------------------------------------------------------------------------
// References. Inputs are the exact float values the code under test sees, so the errors
// measure the algorithm's rounding (and its approximation), not the rounding of the inputs.

quad sqrt_q(quad x) {  // long double estimate refined by two Newton steps
    if (x <= 0) return 0;
    quad r = std::sqrt(static_cast<ld>(x));
    r = (r + x / r) / 2;
    r = (r + x / r) / 2;
    return r;
}

// (1 + g^2 - 2 g mu)^(3/2) with the base in quad: its cancellation near the peaks (8 digits
// at |g| = 0.9999) still leaves ~1e-26 there.
ld hg_pow15_ref(ld mu, ld g) {
    const quad m = mu, gq = g;
    const quad d = 1 + gq * gq - 2 * gq * m;
    return static_cast<ld>(d * sqrt_q(d));
}
ld hg_ref(ld mu, ld g) { return (1 - g * g) / (4 * PI * hg_pow15_ref(mu, g)); }
ld cornette_shanks_ref(ld mu, ld g) {
    return 3 / (8 * PI) * (1 - g * g) / (2 + g * g) * (1 + mu * mu) / hg_pow15_ref(mu, g);
}
ld draine_ref(ld mu, ld g, ld alpha) {
    return (1 - g * g) * (1 + alpha * mu * mu) / (4 * PI * (1 + alpha * (1 + 2 * g * g) / 3) * hg_pow15_ref(mu, g));
}

// Jendersie & d'Eon 2023 fit (REFERENCES.md), evaluated in long double from its published
// formulas: the reference for the library's float evaluation.
struct mie_ref_params {
    ld g_hg, g_draine, alpha, w_draine;
};
mie_ref_params mie_params_ref(ld d) {
    mie_ref_params p{};
    if (d <= 0.1L) {
        p.g_hg = 13.8L * d * d;
        p.g_draine = 1.1456L * d * std::sin(9.29044L * d);
        p.alpha = 250;
        p.w_draine = 0.252977L - 312.983L * std::pow(d, 4.3L);
    } else if (d < 1.5L) {
        const ld L = std::log(d);
        p.g_hg = 0.862L - 0.143L * L * L;
        p.g_draine = 0.379685L * std::cos(1.19692L * std::cos(((L - 0.238604L) * (L + 1.00667L)) / (0.507522L - 0.15677L * L)) +
                                          1.37932L * L + 0.0625835L) +
                     0.344213L;
        p.alpha = 250;
        p.w_draine = 0.146209L * std::cos(3.38707L * L + 2.11193L) + 0.316072L + 0.0778917L * L;
    } else if (d < 5) {
        const ld L = std::log(d);
        p.g_hg = 0.0604931L * std::log(L) + 0.940256L;
        p.g_draine = 0.500411L - 0.081287L / (-2 * L + std::tan(L) + 1.27551L);
        p.alpha = 7.30354L * L + 6.31675L;
        p.w_draine = 0.026914L * (L - std::cos(5.68947L * (std::log(L) - 0.0292149L))) + 0.3764L;
    } else {
        p.g_hg = std::exp(-0.0990567L / (d - 1.67154L));
        p.g_draine = std::exp(-2.20679L / (d + 3.91029L) - 0.428934L);
        p.alpha = std::exp(3.62489L - 8.29288L / (d + 5.52825L));
        p.w_draine = std::exp(-0.599085L / (d - 0.641583L) - 0.665888L);
    }
    return p;
}
ld mie_ref(ld mu, const mie_ref_params& p) {
    return (1 - p.w_draine) * hg_ref(mu, p.g_hg) + p.w_draine * draine_ref(mu, p.g_draine, p.alpha);
}

// Exact step integral S (1 - exp(-sigma ds)) / sigma, S ds at sigma = 0.
ld step_integral_ref(ld S, ld sigma, ld ds) {
    const ld x = sigma * ds;
    return x == 0 ? S * ds : S * ds * (-std::expm1(-x) / x);
}

// Roots of |(0, R + h) + t d|^2 = (R + H)^2 (d with zenith cosine mu) in quad precision,
// textbook formula: the cancellation of c = r^2 - (R + H)^2 costs 14 of quad's 34 digits.
struct roots_ref {
    bool hit;
    ld t0, t1;
};
roots_ref altitude_roots_ref(ld h, ld mu, ld R, ld H) {
    const quad r = quad(R) + quad(h), rs = quad(R) + quad(H), m = mu;
    const quad b = r * m;
    const quad c = r * r - rs * rs;
    const quad disc = b * b - c;
    if (disc < 0) return {false, -1, -1};
    const quad sq = sqrt_q(disc);
    return {true, static_cast<ld>(-b - sq), static_cast<ld>(-b + sq)};
}

// Midpoint rule with `steps` samples over [0, length] along origin + s dir, in long double.
ld light_optical_depth_ref(const glm::vec3& o, const glm::vec3& d, ld length, int steps) {
    const ld ds = length / steps;
    ld tau = 0;
    for (int i = 0; i < steps; ++i) {
        const ld s = (i + 0.5L) * ds;
        tau += cm_report::cloud_extinction<ld>(ld(o.x) + s * ld(d.x), ld(o.y) + s * ld(d.y), ld(o.z) + s * ld(d.z));
    }
    return tau * ds;
}

// ---------------------------------------------------------------------------------------
// Error statistics of one variant over its domain.
// A non-finite result (Inf or NaN) makes the maximum infinite; the RMS is taken over the
// finite results and the non-finite ones are counted apart.
struct error_stats {
    ld max_rel = 0, sum_sq = 0;
    std::size_t count = 0, finite = 0, non_finite = 0;
    std::string worst;  // where the maximum occurs (the first non-finite result, if any)

    template <class Where>
    void add(ld got, ld ref, Where&& where) {
        ld e;
        if (!std::isfinite(got)) {
            e = std::numeric_limits<ld>::infinity();
            ++non_finite;
        } else {
            e = std::fabs(got - ref) / std::max(std::fabs(ref), error_floor_ref);
            sum_sq += e * e;
            ++finite;
        }
        if (count == 0 || e > max_rel) {
            max_rel = e;
            worst = where();
        }
        ++count;
    }
    bool empty() const { return count == 0; }
    double max() const { return count ? static_cast<double>(max_rel) : nan_value; }
    double rms() const { return finite ? static_cast<double>(std::sqrt(sum_sq / static_cast<ld>(finite))) : nan_value; }
    // "Max error at" text: the worst input, and how many results were not finite.
    std::string where_text() const {
        if (non_finite == 0) return worst;
        return worst + " (" + std::to_string(non_finite) + " of " + std::to_string(count) + " results Inf or NaN)";
    }
};

// One row of the report.
struct variant {
    std::string group;   // module (header) the variant belongs to
    std::string family;  // variants that compute the same quantity and can replace each other
    std::string name;    // table name
    std::string label;   // short plot label
    bool phase = false;  // a phase-function row
    std::string physical = "-";  // error against the physical reference (fill_physical_column)
    // GPU cost: the first line of docs/glsl_cost.md for this GLSL function whose expression
    // contains glsl_expression; cost_suffix is appended (e.g. "/step").
    std::string glsl_function, glsl_expression, cost_suffix;
    std::function<void()> scalar_pass, batch_pass;  // one timed pass over the inputs
    double scalar_evals = 0, batch_evals = 0;       // evaluations per pass
    std::string batch_note;                         // what the batch column times, when unusual
    error_stats err, batch_err;
    std::string error_note;  // what the error is measured against, when not the usual
    double scalar_ns = nan_value, batch_ns = nan_value;
    double scalar_spread = nan_value, batch_spread = nan_value;  // half IQR / median
    std::string gpu_cost = "-";
    bool front = false;  // on the Pareto front of its family

    double plot_ns() const { return std::isnan(scalar_ns) ? batch_ns : scalar_ns; }
    double plot_error() const {
        const double e = err.empty() ? batch_err.max() : err.max();
        return std::max(e, plot_error_floor);
    }
};

variant& add_variant(std::deque<variant>& rows, const std::string& group, const std::string& family,
                     const std::string& name, const std::string& label) {
    rows.emplace_back();
    variant& v = rows.back();
    v.group = group;
    v.family = family;
    v.name = name;
    v.label = label;
    return v;
}

// ---------------------------------------------------------------------------------------
// Error domains.

// mu: 401 uniform points on [-1, 1] (+-1 included) and +-(1 - 10^-k), k = 1..7.
std::vector<float> mu_grid(int uniform_points = 401) {
    std::vector<float> mus;
    for (int i = 0; i < uniform_points; ++i)
        mus.push_back(static_cast<float>(-1.0L + 2.0L * i / (uniform_points - 1)));
    for (int k = 1; k <= 7; ++k) {
        const ld d = std::pow(10.0L, -k);
        mus.push_back(static_cast<float>(1 - d));
        mus.push_back(static_cast<float>(-1 + d));
    }
    return mus;
}

// tau: 0, 10^-8 .. 10^4 (per_decade points a decade) and a uniform grid on (0, 10].
std::vector<float> tau_grid(int per_decade = 10, float uniform_step = 0.05f) {
    std::vector<float> taus{0.0f};
    for (int i = -8 * per_decade; i <= 4 * per_decade; ++i)
        taus.push_back(static_cast<float>(std::pow(10.0L, static_cast<ld>(i) / per_decade)));
    for (int i = 1; static_cast<double>(i) * uniform_step <= 10.0 + 1e-9; ++i)
        taus.push_back(static_cast<float>(static_cast<double>(i) * uniform_step));
    return taus;
}

const std::vector<float> phase_g_values = {-0.9999f, -0.999f, -0.99f, -0.9f, -0.5f, 0.0f, 0.3f, 0.5f,
                                           0.8f,     0.9f,    0.95f,  0.99f, 0.995f, 0.999f, 0.9999f};
const std::vector<float> draine_alphas = {0.0f, 0.5f, 1.0f, 5.0f, 22.0f, 250.0f};
const std::vector<float> mie_diameters = {0.05f, 0.5f, 1.0f, 2.0f, 3.0f, 5.0f, 10.0f, 20.0f, 35.0f, 50.0f};  // um
const std::vector<float> ms_g_values = {-0.5f, 0.0f, 0.5f, 0.8f, 0.9f, 0.99f, 0.999f};
constexpr int mie_table_entries = 1800;     // 0.1 degree apart
constexpr int light_error_points = 512;     // rays of the light-march comparison
constexpr int light_reference_steps = 4096; // steps of its reference march

// ---------------------------------------------------------------------------------------
// Inputs of the timed passes: arrays spanning the documented domains, in random order so
// that branches are not predictable from the order. The kernels read them through `view`.
struct timing_inputs {
    static constexpr std::size_t n = 4096;       // light functions
    static constexpr std::size_t n_heavy = 256;  // whole light marches and slabs
    std::vector<float> mu, tau, S, sigma, droplet_d, sigma_slab, out;
    std::vector<glm::vec3> origin, dir;
    std::unique_ptr<cm_naive::phase_table<float>> mie_table;
    pass_inputs view;
};

// Unit vector in the upper hemisphere, at least about 6 degrees above the horizon.
glm::vec3 random_light_dir(splitmix64& rng) {
    for (;;) {
        const glm::vec3 v(rng.uniform(-1, 1), rng.uniform(0.1, 1), rng.uniform(-1, 1));
        const float len2 = glm::dot(v, v);
        if (len2 > 0.01f && len2 <= 1.0f) return v / std::sqrt(len2);
    }
}

std::unique_ptr<timing_inputs> make_timing_inputs() {
    auto in = std::make_unique<timing_inputs>();
    splitmix64 rng(0x5eed5eedull);
    for (std::size_t i = 0; i < timing_inputs::n; ++i) {
        in->mu.push_back(rng.uniform(-1, 1));
        // Half typical depths, half log-uniform over the whole documented range.
        in->tau.push_back(i % 2 == 0 ? rng.uniform(0, 10) : rng.log_uniform(1e-8, 1e4));
        in->S.push_back(rng.uniform(0.1, 1));
        in->sigma.push_back(rng.log_uniform(1e-9, 1e3));
        in->droplet_d.push_back(rng.uniform(5, 50));
    }
    in->out.assign(timing_inputs::n, 0.0f);
    for (std::size_t i = 0; i < timing_inputs::n_heavy; ++i) {
        in->origin.emplace_back(rng.uniform(0, 4000), rng.uniform(0, 4000), rng.uniform(0, 4000));
        in->dir.push_back(random_light_dir(rng));
        in->sigma_slab.push_back(rng.log_uniform(1e-11, 10));  // slab optical depth 1e-8 .. 1e4 over 1 km
    }
    pass_inputs& v = in->view;
    v.n = timing_inputs::n;
    v.mu = in->mu.data();
    v.tau = in->tau.data();
    v.S = in->S.data();
    v.sigma = in->sigma.data();
    v.droplet_d = in->droplet_d.data();
    v.out = in->out.data();
    v.g = 0.8f;       // a typical cloud eccentricity
    v.alpha = 22.0f;  // the Mie fit's Draine alpha near d = 10 um
    v.ds = 10.0f;     // m
    v.mie = cm::mie_approx_params(10.0f);
    const cm::mie_approx_parameters<float> p = v.mie;
    in->mie_table = std::make_unique<cm_naive::phase_table<float>>(mie_table_entries, [p](float mu) { return cm::phase_mie_approx(mu, p); });
    v.mie_table = in->mie_table.get();
    v.n_heavy = timing_inputs::n_heavy;
    v.origin = in->origin.data();
    v.dir = in->dir.data();
    v.sigma_slab = in->sigma_slab.data();
    return in;
}

// ---------------------------------------------------------------------------------------
// phase.hpp

void add_phase_variants(std::deque<variant>& rows, const pass_inputs* in) {
    const std::vector<float>& gs = phase_g_values;
    const std::vector<float> mus = mu_grid();
    const std::size_t nm = mus.size();
    std::vector<ld> ref_hg, ref_cs;
    for (float g : gs)
        for (float mu : mus) {
            ref_hg.push_back(hg_ref(mu, g));
            ref_cs.push_back(cornette_shanks_ref(mu, g));
        }
    auto where = [&](std::size_t gi, std::size_t mi) { return "g = " + fmt_input(gs[gi]) + ", mu = " + fmt_input(mus[mi]); };
    // Scalar function f(mu, g) and its timed kernel.
    auto setup = [&](variant& v, auto f, const std::vector<ld>& ref, void (*kernel)(const pass_inputs&)) {
        v.phase = true;
        for (std::size_t gi = 0; gi < gs.size(); ++gi)
            for (std::size_t mi = 0; mi < nm; ++mi)
                v.err.add(f(mus[mi], gs[gi]), ref[gi * nm + mi], [&] { return where(gi, mi); });
        v.scalar_pass = [in, kernel] { kernel(*in); };
        v.scalar_evals = static_cast<double>(in->n);
    };
    // Batch form batch(mu, n, g, out): one call per g over the mu grid.
    using batch_mu_g = void (*)(const float*, std::size_t, float, float*);
    auto setup_batch = [&](variant& v, batch_mu_g batch, const std::vector<ld>& ref) {
        std::vector<float> out(nm);
        for (std::size_t gi = 0; gi < gs.size(); ++gi) {
            batch(mus.data(), nm, gs[gi], out.data());
            for (std::size_t mi = 0; mi < nm; ++mi) v.batch_err.add(out[mi], ref[gi * nm + mi], [&] { return where(gi, mi); });
        }
        v.batch_pass = [in, batch] {
            batch(in->mu, in->n, in->g, in->out);
            kernels::sink_memory(in->out);
        };
        v.batch_evals = static_cast<double>(in->n);
    };

    {
        variant& v = add_variant(rows, "phase", "Henyey-Greenstein", "phase_hg (library)", "HG");
        v.glsl_function = "cm_phase_hg";
        setup(v, [](float m, float g) { return cm::phase_hg(m, g); }, ref_hg, kernels::hg_library);
        setup_batch(v, kernels::batch_hg_exact, ref_hg);
    }
    {
        variant& v = add_variant(rows, "phase", "Henyey-Greenstein", "HG textbook: pow(1 + g^2 - 2 g mu, 1.5)", "HG naive");
        setup(v, [](float m, float g) { return cm_naive::phase_hg(m, g); }, ref_hg, kernels::hg_naive);
    }
    {
        variant& v = add_variant(rows, "phase", "Henyey-Greenstein", "fast::phase_hg (bit-trick rsqrt)", "HG fast");
        setup(v, [](float m, float g) { return cm::fast::phase_hg(m, g); }, ref_hg, kernels::hg_fast);
        setup_batch(v, kernels::batch_hg_fast, ref_hg);
    }
    {
        variant& v = add_variant(rows, "phase", "Henyey-Greenstein", "phase_hg_schlick (Schlick, k(g))", "HG Schlick");
        v.glsl_function = "cm_phase_hg_schlick";
        v.error_note = "against HG";
        setup(v, [](float m, float g) { return cm::phase_hg_schlick(m, g); }, ref_hg, kernels::hg_schlick);
    }
    {
        variant& v = add_variant(rows, "phase", "Cornette-Shanks", "phase_cornette_shanks (library)", "CS");
        v.glsl_function = "cm_phase_cornette_shanks";
        setup(v, [](float m, float g) { return cm::phase_cornette_shanks(m, g); }, ref_cs, kernels::cornette_shanks_library);
        setup_batch(v, kernels::batch_cornette_shanks_exact, ref_cs);
    }
    {
        variant& v = add_variant(rows, "phase", "Cornette-Shanks", "Cornette-Shanks textbook (pow)", "CS naive");
        setup(v, [](float m, float g) { return cm_naive::phase_cornette_shanks(m, g); }, ref_cs, kernels::cornette_shanks_naive);
    }

    // Draine: g x alpha x mu.
    {
        std::vector<ld> ref;
        for (float g : gs)
            for (float a : draine_alphas)
                for (float mu : mus) ref.push_back(draine_ref(mu, g, a));
        auto setup_draine = [&](variant& v, auto f, void (*kernel)(const pass_inputs&)) {
            v.phase = true;
            std::size_t k = 0;
            for (float g : gs)
                for (float a : draine_alphas)
                    for (float mu : mus)
                        v.err.add(f(mu, g, a), ref[k++], [&] {
                            return "g = " + fmt_input(g) + ", alpha = " + fmt_input(a) + ", mu = " + fmt_input(mu);
                        });
            v.scalar_pass = [in, kernel] { kernel(*in); };
            v.scalar_evals = static_cast<double>(in->n);
        };
        variant& v = add_variant(rows, "phase", "Draine", "phase_draine (library)", "Draine");
        v.glsl_function = "cm_phase_draine";
        setup_draine(v, [](float m, float g, float a) { return cm::phase_draine(m, g, a); }, kernels::draine_library);
        variant& w = add_variant(rows, "phase", "Draine", "Draine textbook (pow)", "Draine naive");
        setup_draine(w, [](float m, float g, float a) { return cm_naive::phase_draine(m, g, a); }, kernels::draine_naive);
    }

    // Jendersie & d'Eon Mie fit: droplet diameter d x mu, every range of the fit.
    {
        std::vector<ld> ref;
        for (float d : mie_diameters) {
            const mie_ref_params p = mie_params_ref(d);
            for (float mu : mus) ref.push_back(mie_ref(mu, p));
        }
        auto where_d = [&](float d, float mu) { return "d = " + fmt_input(d) + " um, mu = " + fmt_input(mu); };

        variant& per_call = add_variant(rows, "phase", "Mie fit (Jendersie-d'Eon)", "phase_mie_approx(mu, d): parameters per call", "Mie per call");
        per_call.phase = true;
        per_call.glsl_function = "cm_phase_mie_approx";
        per_call.glsl_expression = "(a.x, a.y)";
        {
            std::size_t k = 0;
            for (float d : mie_diameters)
                for (float mu : mus) per_call.err.add(cm::phase_mie_approx(mu, d), ref[k++], [&] { return where_d(d, mu); });
        }
        per_call.scalar_pass = [in] { kernels::mie_per_call(*in); };
        per_call.scalar_evals = static_cast<double>(in->n);

        variant& pre = add_variant(rows, "phase", "Mie fit (Jendersie-d'Eon)", "phase_mie_approx(mu, params): precomputed parameters", "Mie params");
        pre.phase = true;
        pre.glsl_function = "cm_phase_mie_approx";
        pre.glsl_expression = "CmMieApproxParams";
        {
            std::size_t k = 0;
            std::vector<float> out(nm);
            for (float d : mie_diameters) {
                const cm::mie_approx_parameters<float> p = cm::mie_approx_params(d);
                for (float mu : mus) pre.err.add(cm::phase_mie_approx(mu, p), ref[k++], [&] { return where_d(d, mu); });
                kernels::batch_mie(mus.data(), nm, p, out.data());
                for (std::size_t mi = 0; mi < nm; ++mi)
                    pre.batch_err.add(out[mi], ref[k - nm + mi], [&] { return where_d(d, mus[mi]); });
            }
        }
        pre.scalar_pass = [in] { kernels::mie_precomputed(*in); };
        pre.scalar_evals = static_cast<double>(in->n);
        pre.batch_pass = [in] {
            kernels::batch_mie(in->mu, in->n, in->mie, in->out);
            kernels::sink_memory(in->out);
        };
        pre.batch_evals = static_cast<double>(in->n);

        // The table engines build from MiePlot data, here filled from the library's float Mie
        // fit; its error is the lookup's, against the analytic fit (the library in double).
        variant& table = add_variant(rows, "phase", "Mie fit (Jendersie-d'Eon)", "cm_naive::phase_table: 1800 entries, linear in angle", "Mie table");
        table.phase = true;
        table.error_note = "against the library's analytic fit in double";
        for (float d : mie_diameters) {
            const cm::mie_approx_parameters<float> pf = cm::mie_approx_params(d);
            const cm_naive::phase_table<float> lookup(mie_table_entries, [&](float mu) { return cm::phase_mie_approx(mu, pf); });
            const cm::mie_approx_parameters<double> pd = cm::mie_approx_params(static_cast<double>(d));
            for (float mu : mus)
                table.err.add(lookup(mu), cm::phase_mie_approx(static_cast<double>(mu), pd), [&] { return where_d(d, mu); });
        }
        table.scalar_pass = [in] { kernels::mie_table(*in); };
        table.scalar_evals = static_cast<double>(in->n);
    }
}

// ---------------------------------------------------------------------------------------
// transmittance.hpp (and fast_math.hpp's exponentials)

void add_transmittance_variants(std::deque<variant>& rows, const pass_inputs* in) {
    const std::vector<float> taus = tau_grid();
    auto where = [](float tau) { return "tau = " + fmt_input(tau); };
    auto setup = [&](variant& v, auto f, auto ref, void (*kernel)(const pass_inputs&)) {
        for (float tau : taus) v.err.add(f(tau), ref(static_cast<ld>(tau)), [&] { return where(tau); });
        v.scalar_pass = [in, kernel] { kernel(*in); };
        v.scalar_evals = static_cast<double>(in->n);
    };
    using batch_tau = void (*)(const float*, std::size_t, float*);
    auto setup_batch = [&](variant& v, batch_tau batch, auto ref) {
        std::vector<float> out(taus.size());
        batch(taus.data(), taus.size(), out.data());
        for (std::size_t i = 0; i < taus.size(); ++i) v.batch_err.add(out[i], ref(static_cast<ld>(taus[i])), [&] { return where(taus[i]); });
        v.batch_pass = [in, batch] {
            batch(in->tau, in->n, in->out);
            kernels::sink_memory(in->out);
        };
        v.batch_evals = static_cast<double>(in->n);
    };
    auto beer = [](ld tau) { return std::exp(-tau); };
    auto beer_powder = [](ld tau) { return 2 * std::exp(-tau) * -std::expm1(-2 * tau); };
    auto powder2 = [](ld tau) { return -std::expm1(-2 * tau); };
    // 0.7 exactly; float implementations multiply by 0.7f, 1.2e-8 relative off (rounding).
    auto nubis = [](ld tau) { return std::max(std::exp(-tau), 0.7L * std::exp(-0.25L * tau)); };

    {
        variant& v = add_variant(rows, "transmittance", "Beer-Lambert", "beer_lambert (library, std::exp)", "Beer");
        v.glsl_function = "cm_beer_lambert";
        v.glsl_expression = "(a.x)";
        setup(v, [](float x) { return cm::beer_lambert(x); }, beer, kernels::beer_library);
        setup_batch(v, kernels::batch_beer_exact, beer);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Beer-Lambert", "Beer textbook: std::exp(-tau)", "Beer naive");
        setup(v, [](float x) { return cm_naive::beer_lambert(x); }, beer, kernels::beer_naive);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Beer-Lambert", "fast::beer_lambert (degree-4 exp)", "Beer fast");
        setup(v, [](float x) { return cm::fast::beer_lambert(x); }, beer, kernels::beer_fast);
        setup_batch(v, kernels::batch_beer_fast, beer);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Beer-Lambert", "exp_vectorizable(-tau)", "exp_vectorizable");
        setup(v, [](float x) { return cm::exp_vectorizable(-x); }, beer, kernels::exp_vectorizable_scalar);
        // No batch function: the batch column times a plain loop over it.
        setup_batch(v, kernels::exp_vectorizable_loop, beer);
        v.batch_note = "plain loop";
    }
    {
        variant& v = add_variant(rows, "transmittance", "powder", "powder(tau, 2) (library, -expm1)", "powder");
        v.glsl_function = "cm_powder";
        v.glsl_expression = "(a.x, a.y)";
        setup(v, [](float x) { return cm::powder(x, 2.0f); }, powder2, kernels::powder_library);
    }
    {
        variant& v = add_variant(rows, "transmittance", "powder", "fast::powder(tau, 2)", "powder fast");
        setup(v, [](float x) { return cm::fast::powder(x, 2.0f); }, powder2, kernels::powder_fast);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Beer-Powder", "beer_powder (library)", "Beer-Powder");
        v.glsl_function = "cm_beer_powder";
        v.glsl_expression = "(a.x)";
        setup(v, [](float x) { return cm::beer_powder(x); }, beer_powder, kernels::beer_powder_library);
        setup_batch(v, kernels::batch_beer_powder_exact, beer_powder);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Beer-Powder", "Beer-Powder textbook: 2 e^-t (1 - e^-2t)", "BP naive");
        setup(v, [](float x) { return cm_naive::beer_powder(x); }, beer_powder, kernels::beer_powder_naive);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Beer-Powder", "fast::beer_powder (one fast exp)", "BP fast");
        setup(v, [](float x) { return cm::fast::beer_powder(x); }, beer_powder, kernels::beer_powder_fast);
        setup_batch(v, kernels::batch_beer_powder_fast, beer_powder);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Nubis attenuation", "nubis_attenuation (library)", "Nubis");
        v.glsl_function = "cm_nubis_attenuation";
        v.glsl_expression = "(a.x)";
        setup(v, [](float x) { return cm::nubis_attenuation(x); }, nubis, kernels::nubis_library);
        setup_batch(v, kernels::batch_nubis_exact, nubis);
    }
    {
        variant& v = add_variant(rows, "transmittance", "Nubis attenuation", "Nubis textbook: max of two std::exp", "Nubis naive");
        setup(v, [](float x) { return cm_naive::nubis_attenuation(x); }, nubis, kernels::nubis_naive);
    }
}

// ---------------------------------------------------------------------------------------
// integration.hpp: one step, and a homogeneous slab marched in N steps.

void add_integration_variants(std::deque<variant>& rows, const pass_inputs* in) {
    // Step: sigma_t x ds with sigma_t ds from 0 to 1e4 (1e-8 included), S = 0.37.
    std::vector<float> sigmas{0.0f, 1e-30f, 1e-20f};
    for (int i = -100; i <= 20; ++i) sigmas.push_back(static_cast<float>(std::pow(10.0L, i / 10.0L)));
    const std::vector<float> dss = {1.0f, 10.0f, 100.0f};
    const float S = 0.37f;
    auto where = [](float sigma, float ds) { return "sigma_t = " + fmt_input(sigma) + "/m, ds = " + fmt_input(ds) + " m"; };
    auto setup = [&](variant& v, auto f, void (*kernel)(const pass_inputs&)) {
        for (float ds : dss)
            for (float sigma : sigmas) v.err.add(f(S, sigma, ds), step_integral_ref(S, sigma, ds), [&] { return where(sigma, ds); });
        v.scalar_pass = [in, kernel] { kernel(*in); };
        v.scalar_evals = static_cast<double>(in->n);
    };
    {
        variant& v = add_variant(rows, "integration", "step integral", "integrate_scattering (library, expm1)", "step exact");
        v.glsl_function = "cm_integrate_scattering";
        v.glsl_expression = "(a.x, a.y, a.z)";
        setup(v, [](float s, float sig, float ds) { return cm::integrate_scattering(s, sig, ds); }, kernels::step_library);
        std::vector<float> out(sigmas.size()), Ss(sigmas.size(), S);
        for (float ds : dss) {
            kernels::batch_integrate(Ss.data(), sigmas.data(), sigmas.size(), ds, out.data());
            for (std::size_t i = 0; i < sigmas.size(); ++i)
                v.batch_err.add(out[i], step_integral_ref(S, sigmas[i], ds), [&] { return where(sigmas[i], ds); });
        }
        v.batch_pass = [in] {
            kernels::batch_integrate(in->S, in->sigma, in->n, in->ds, in->out);
            kernels::sink_memory(in->out);
        };
        v.batch_evals = static_cast<double>(in->n);
    }
    {
        variant& v = add_variant(rows, "integration", "step integral", "clamp constant: (S - S e^-x) / max(sigma_t, 1e-6)", "step clamp");
        setup(v, [](float s, float sig, float ds) { return cm_naive::integrate_scattering_clamped(s, sig, ds); }, kernels::step_clamped);
    }
    {
        variant& v = add_variant(rows, "integration", "step integral", "Riemann: S ds", "step Riemann");
        setup(v, [](float s, float sig, float ds) { return cm_naive::integrate_scattering_riemann(s, sig, ds); }, kernels::step_riemann);
    }

    // Homogeneous slab, 1 km thick, source S = 1/m: radiance leaving it after N steps, against
    // S (1 - exp(-tau)) / sigma_t. Slab optical depth tau from 0 to 1e4 (1e-8 included).
    std::vector<float> slab_sigmas{0.0f};
    for (int i = -110; i <= 10; ++i) slab_sigmas.push_back(static_cast<float>(std::pow(10.0L, i / 10.0L)));
    auto slab_setup = [&](variant& v, float (*value)(float, int), void (*kernel)(const pass_inputs&, int), int steps) {
        for (float sigma : slab_sigmas)
            v.err.add(value(sigma, steps), step_integral_ref(1, sigma, cm_report::light_path_length), [&] {
                return "slab tau = " + fmt_input(static_cast<double>(sigma) * cm_report::light_path_length);
            });
        v.scalar_pass = [in, kernel, steps] { kernel(*in, steps); };
        v.scalar_evals = static_cast<double>(in->n_heavy);
    };
    for (int steps : {16, 64}) {
        variant& v = add_variant(rows, "integration", "homogeneous slab", "slab, " + std::to_string(steps) + " steps: Riemann (S ds, then T *= e^-x)",
                                 "slab Riemann " + std::to_string(steps));
        slab_setup(v, kernels::slab_riemann_value, kernels::slab_riemann, steps);
    }
    for (int steps : {16, 64}) {
        variant& v = add_variant(rows, "integration", "homogeneous slab",
                                 "slab, " + std::to_string(steps) + " steps: march_accumulator (exact step integral)",
                                 "slab exact " + std::to_string(steps));
        v.glsl_function = "cm_march_add_segment";
        v.glsl_expression = "a.y, a.w)";
        v.cost_suffix = "/step";
        slab_setup(v, kernels::slab_exact_value, kernels::slab_exact, steps);
    }
}

// ---------------------------------------------------------------------------------------
// geometry.hpp: the first positive root at Earth radius.

void add_geometry_variants(std::deque<variant>& rows, const pass_inputs* in) {
    const float R = 6371e3f;
    struct scene {
        float h, H;
    };
    const std::vector<scene> scenes = {{1.8f, 1500.0f}, {1000.0f, 1500.0f}, {10000.0f, 4000.0f}};
    std::vector<float> mus;
    for (int i = -1000; i <= 1000; ++i) mus.push_back(static_cast<float>(i) / 1000.0f);
    for (int k = 2; k <= 7; ++k)
        for (int j = 1; j <= 9; ++j) {
            const float m = static_cast<float>(j * std::pow(10.0L, -k));
            mus.push_back(m);
            mus.push_back(-m);
        }
    struct point {
        float h, H, mu;
        ld t;
    };
    std::vector<point> points;
    for (const scene& s : scenes)
        for (float mu : mus) {
            const roots_ref r = altitude_roots_ref(s.h, mu, R, s.H);
            if (!r.hit) continue;
            const ld t_ref = r.t0 >= 0 ? r.t0 : r.t1;
            if (t_ref < 0) continue;
            // Grazing rays from above are ill-conditioned for any formula: the roots closer
            // than 1% of their distance are left out (as in tests/test_geometry.cpp).
            if (s.h > s.H && r.t1 - r.t0 < 0.01L * r.t0) continue;
            points.push_back({s.h, s.H, mu, t_ref});
        }
    auto setup = [&](variant& v, float (*f)(float, float, float, float), void (*kernel)(const pass_inputs&)) {
        for (const point& p : points)
            v.err.add(f(p.h, p.mu, R, p.H), p.t, [&] {
                return "camera " + fmt_input(p.h) + " m, sphere " + fmt_input(p.H) + " m, mu = " + fmt_input(p.mu);
            });
        v.scalar_pass = [in, kernel] { kernel(*in); };
        v.scalar_evals = static_cast<double>(in->n);
    };
    {
        variant& v = add_variant(rows, "geometry", "ray/sphere at Earth radius", "ray_sphere_intersect_altitude (library)", "ray/sphere altitude");
        v.glsl_function = "cm_ray_sphere_intersect_altitude";
        setup(v, kernels::ray_sphere_altitude_value, kernels::ray_sphere_altitude);
    }
    {
        variant& v = add_variant(rows, "geometry", "ray/sphere at Earth radius", "ray/sphere textbook (|o|^2 - r^2)", "ray/sphere naive");
        setup(v, cm_naive::ray_sphere_first_hit<float>, kernels::ray_sphere_naive);
    }
    {
        variant& v = add_variant(rows, "geometry", "ray/sphere at Earth radius", "ray_sphere_intersect (library, Haines; vec3 origin at R + h)",
                                 "ray/sphere Haines");
        v.glsl_function = "cm_ray_sphere_intersect";
        setup(v, kernels::ray_sphere_haines_value, kernels::ray_sphere_haines);
    }
}

// ---------------------------------------------------------------------------------------
// multiple_scattering.hpp: each octave count against the long double evaluation of the same
// N-octave formula, and the truncation change from N to N + 1 octaves.

struct truncation_row {
    int octaves;
    double median_change[2], rms_change[2], max_change[2];  // per parameter set
};

struct ms_parameters {
    float a, b, c;
    const char* name;
};
const ms_parameters ms_sets[2] = {{0.5f, 0.5f, 0.5f, "a = b = c = 0.5"}, {0.3f, 0.75f, 0.5f, "a = 0.3, b = 0.75, c = 0.5"}};
constexpr int ms_max_octaves = 8;

// diffusion_lighting.hpp: the fitted diffusion model in float against its own formula in
// long double (the same table), beside the octaves it replaces; its error against the path
// tracer is the physical-reference column.
void add_diffusion_variants(std::deque<variant>& rows, const pass_inputs* in) {
    variant& v = add_variant(rows, "diffusion_lighting", "3 inputs (diffusion)",
                             "diffusion_scattering, diffusion_models::fitted, albedo 0.99 (library)", "Diffusion");
    v.glsl_function = "cm_diffusion_scattering";
    v.glsl_expression = "CM_DIFFUSION_MODEL_FITTED)";
    const std::vector<float> taus = tau_grid(4, 0.5f);
    const std::vector<float> mus = mu_grid(21);
    for (float g : {0.0f, 0.5f, 0.8f, 0.9f, 0.99f})
        for (std::size_t i = 0; i < taus.size(); ++i)
            for (float mu : mus) {
                const float ts = taus[i], tb = taus[(i * 7 + 3) % taus.size()], tv = 0.25f * taus[(i * 13 + 5) % taus.size()];
                const float got = cm::diffusion_scattering(ts, tb, tv, mu, g, 0.99f, cm::diffusion_models::fitted);
                const ld ref = cm::diffusion_scattering<ld>(ts, tb, tv, mu, g, ld(0.99f), cm::diffusion_models::fitted);
                v.err.add(got, ref, [&] {
                    return "g = " + fmt_input(g) + ", tau_sun = " + fmt_input(ts) + ", tau_behind = " + fmt_input(tb) +
                           ", tau_view = " + fmt_input(tv) + ", mu = " + fmt_input(mu);
                });
            }
    v.scalar_pass = [in] { kernels::diffusion_library(*in); };
    v.scalar_evals = static_cast<double>(in->n);
}

std::vector<truncation_row> add_multiple_scattering_variants(std::deque<variant>& rows, const pass_inputs* in) {
    const std::vector<float> taus = tau_grid(4, 0.5f);
    const std::vector<float> mus = mu_grid(41);
    struct point {
        float tau, mu, g;
        int set;
        ld partial[ms_max_octaves + 1];  // sums of the first N octaves, N = 0..8
    };
    std::vector<point> points;
    for (int set = 0; set < 2; ++set)
        for (float g : ms_g_values)
            for (float tau : taus)
                for (float mu : mus) {
                    point p{tau, mu, g, set, {}};
                    // The powers of the float a, b, c, exactly (the code's running products
                    // round; that rounding is part of its error).
                    const ld a = ms_sets[set].a, b = ms_sets[set].b, c = ms_sets[set].c;
                    ld ai = 1, bi = 1, ci = 1;
                    p.partial[0] = 0;
                    for (int i = 0; i < ms_max_octaves; ++i) {
                        p.partial[i + 1] = p.partial[i] + bi * hg_ref(mu, ci * static_cast<ld>(g)) * std::exp(-ai * static_cast<ld>(tau));
                        ai *= a;
                        bi *= b;
                        ci *= c;
                    }
                    points.push_back(p);
                }
    auto where = [](const point& p) {
        return std::string(ms_sets[p.set].name) + ", g = " + fmt_input(p.g) + ", tau = " + fmt_input(p.tau) + ", mu = " + fmt_input(p.mu);
    };
    // Batch errors: one call per (parameter set, g) over that slice of (tau, mu) points.
    const std::size_t slice = taus.size() * mus.size();
    std::vector<float> slice_tau(slice), slice_mu(slice);
    for (std::size_t i = 0; i < slice; ++i) {
        slice_tau[i] = points[i].tau;
        slice_mu[i] = points[i].mu;
    }
    using batch_fn = void (*)(const float*, const float*, std::size_t, float, float, float, float, int, float*);
    auto setup = [&](variant& v, int octaves, auto f, void (*kernel)(const pass_inputs&, int)) {
        for (const point& p : points) {
            const ms_parameters& s = ms_sets[p.set];
            v.err.add(f(p.tau, p.mu, p.g, s.a, s.b, s.c, octaves), p.partial[octaves], [&] { return where(p); });
        }
        v.scalar_pass = [in, kernel, octaves] { kernel(*in, octaves); };
        v.scalar_evals = static_cast<double>(in->n);
    };
    auto setup_batch = [&](variant& v, int octaves, batch_fn batch) {
        std::vector<float> out(slice);
        for (std::size_t start = 0; start < points.size(); start += slice) {
            const point& first = points[start];
            const ms_parameters& s = ms_sets[first.set];
            batch(slice_tau.data(), slice_mu.data(), slice, first.g, s.a, s.b, s.c, octaves, out.data());
            for (std::size_t i = 0; i < slice; ++i) {
                const point& p = points[start + i];
                v.batch_err.add(out[i], p.partial[octaves], [&] { return where(p); });
            }
        }
        v.batch_pass = [in, batch, octaves] {
            batch(in->tau, in->mu, in->n, in->g, 0.5f, 0.5f, 0.5f, octaves, in->out);
            kernels::sink_memory(in->out);
        };
        v.batch_evals = static_cast<double>(in->n);
    };
    auto lib = [](float tau, float mu, float g, float a, float b, float c, int n) { return cm::multiple_scattering(tau, mu, g, a, b, c, n); };
    auto fast = [](float tau, float mu, float g, float a, float b, float c, int n) { return cm::fast::multiple_scattering(tau, mu, g, a, b, c, n); };
    auto naive = [](float tau, float mu, float g, float a, float b, float c, int n) { return cm_naive::multiple_scattering(tau, mu, g, a, b, c, n); };
    for (int n = 1; n <= ms_max_octaves; ++n) {
        const std::string family = std::to_string(n) + (n == 1 ? " octave" : " octaves");
        variant& v = add_variant(rows, "multiple_scattering", family, "multiple_scattering, " + family + " (library)", "MS" + std::to_string(n));
        v.glsl_function = "cm_multiple_scattering";
        v.glsl_expression = ", n)";
        setup(v, n, lib, kernels::multiple_scattering_library);
        setup_batch(v, n, kernels::batch_multiple_scattering_exact);
        variant& w = add_variant(rows, "multiple_scattering", family, "fast::multiple_scattering, " + family, "MS" + std::to_string(n) + " fast");
        setup(w, n, fast, kernels::multiple_scattering_fast);
        setup_batch(w, n, kernels::batch_multiple_scattering_fast);
        if (n == 3) {
            variant& x = add_variant(rows, "multiple_scattering", family, "octaves textbook (pow powers, pow HG), 3 octaves", "MS3 naive");
            setup(x, n, naive, kernels::multiple_scattering_naive);
        }
    }
    std::vector<truncation_row> truncation;
    for (int n = 1; n < ms_max_octaves; ++n) {
        truncation_row r{n, {0, 0}, {0, 0}, {0, 0}};
        std::vector<double> changes[2];
        for (const point& p : points) {
            const ld next = p.partial[n + 1];
            const ld change = std::fabs(next - p.partial[n]) / std::max(std::fabs(next), error_floor_ref);
            changes[p.set].push_back(static_cast<double>(change));
        }
        for (std::size_t s = 0; s < 2; ++s) {
            std::vector<double>& c = changes[s];
            std::sort(c.begin(), c.end());
            double sum_sq = 0;
            for (double x : c) sum_sq += x * x;
            r.median_change[s] = c[c.size() / 2];
            r.rms_change[s] = std::sqrt(sum_sq / static_cast<double>(c.size()));
            r.max_change[s] = c.back();
        }
        truncation.push_back(r);
    }
    return truncation;
}

// ---------------------------------------------------------------------------------------
// cone_sampling.hpp: optical depth toward the light over 1 km, against a 4096-step march of
// the same smooth density.

void add_light_variants(std::deque<variant>& rows, const pass_inputs* in) {
    splitmix64 rng(0xc0ffeeull);
    std::vector<glm::vec3> origins, dirs;
    std::vector<ld> refs;
    for (int i = 0; i < light_error_points; ++i) {
        origins.emplace_back(rng.uniform(0, 4000), rng.uniform(0, 4000), rng.uniform(0, 4000));
        dirs.push_back(random_light_dir(rng));
        refs.push_back(light_optical_depth_ref(origins.back(), dirs.back(), cm_report::light_path_length, light_reference_steps));
    }
    auto setup = [&](variant& v, auto f, std::function<void()> pass) {
        for (std::size_t i = 0; i < origins.size(); ++i)
            v.err.add(f(origins[i], dirs[i]), refs[i], [&] {
                return "ray " + std::to_string(i) + " of " + std::to_string(origins.size()) + ", tau = " + fmt_input(static_cast<double>(refs[i]));
            });
        v.scalar_pass = std::move(pass);
        v.scalar_evals = static_cast<double>(in->n_heavy);
    };
    for (float spread : {0.0f, 0.5f}) {
        variant& v = add_variant(rows, "cone_sampling", "optical depth to the light",
                                 "cone_optical_depth, 6 samples (5 near + far), spread " + fmt_input(spread), "cone 6, spread " + fmt_input(spread));
        v.glsl_function = "cm_cone_optical_depth";
        setup(v, [spread](const glm::vec3& o, const glm::vec3& d) { return kernels::cone_value(o, d, spread); },
              [in, spread] { kernels::cone(*in, spread); });
    }
    for (int steps : {8, 16, 32, 64}) {
        variant& v = add_variant(rows, "cone_sampling", "optical depth to the light", "full light march, " + std::to_string(steps) + " midpoint steps",
                                 "march " + std::to_string(steps));
        setup(v, [steps](const glm::vec3& o, const glm::vec3& d) { return kernels::light_march_value(o, d, steps); },
              [in, steps] { kernels::light_march(*in, steps); });
    }
}
// ---------------------------------------------------------------------------------------
// Timing: calibrate each pass to about target_seconds, then `rounds` interleaved rounds in a
// shuffled order; the result is the median ns per evaluation.

struct timing_job {
    std::function<void()>* pass;
    double evals;
    double* result;
    double* spread;
    std::size_t reps = 1;
    std::vector<double> samples;
};

double seconds_of(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

void run_timings(std::vector<timing_job>& jobs, int rounds, double target_seconds) {
    using clock = std::chrono::steady_clock;
    for (timing_job& j : jobs) {
        (*j.pass)();  // warm up caches and branch predictors
        std::size_t reps = 1;
        for (;;) {
            const auto t0 = clock::now();
            for (std::size_t r = 0; r < reps; ++r) (*j.pass)();
            const double dt = seconds_of(clock::now() - t0);
            if (dt >= target_seconds / 4 || reps >= (std::size_t(1) << 24)) {
                j.reps = std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(reps) * target_seconds / std::max(dt, 1e-9)));
                break;
            }
            reps *= 2;
        }
    }
    std::vector<std::size_t> order(jobs.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    splitmix64 rng(0x71e5ull);
    for (int round = 0; round < rounds; ++round) {
        for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.next() % i]);
        for (std::size_t k : order) {
            timing_job& j = jobs[k];
            const auto t0 = clock::now();
            for (std::size_t r = 0; r < j.reps; ++r) (*j.pass)();
            const double dt = seconds_of(clock::now() - t0);
            j.samples.push_back(dt * 1e9 / (static_cast<double>(j.reps) * j.evals));
        }
    }
    for (timing_job& j : jobs) {
        std::vector<double> s = j.samples;
        std::sort(s.begin(), s.end());
        auto quantile = [&s](double q) {
            const double x = q * static_cast<double>(s.size() - 1);
            const std::size_t i = static_cast<std::size_t>(x);
            const double f = x - static_cast<double>(i);
            return i + 1 < s.size() ? s[i] + f * (s[i + 1] - s[i]) : s[i];
        };
        *j.result = quantile(0.5);
        *j.spread = (quantile(0.75) - quantile(0.25)) / (2 * quantile(0.5));
    }
}

// ---------------------------------------------------------------------------------------
// GPU cost from docs/glsl_cost.md: rows "| cm_fn | `expression` | count |".

struct cost_entry {
    std::string function, expression, count;
};

std::string trim(const std::string& s) {
    const std::size_t b = s.find_first_not_of(" \t`");
    if (b == std::string::npos) return "";
    const std::size_t e = s.find_last_not_of(" \t`");
    return s.substr(b, e - b + 1);
}

std::vector<cost_entry> parse_glsl_cost(const std::string& path) {
    std::vector<cost_entry> entries;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("| cm_", 0) != 0) continue;
        // Function is the first cell, the count the last; the expression is what lies between.
        const std::size_t first = line.find('|', 1);
        const std::size_t last_bar = line.find_last_of('|');
        const std::size_t count_bar = line.find_last_of('|', last_bar - 1);
        if (first == std::string::npos || count_bar == std::string::npos || count_bar <= first) continue;
        entries.push_back({trim(line.substr(1, first - 1)), trim(line.substr(first + 1, count_bar - first - 1)),
                           trim(line.substr(count_bar + 1, last_bar - count_bar - 1))});
    }
    return entries;
}

// ---------------------------------------------------------------------------------------
// Pareto fronts: within each family, the variants that no other variant beats in both time
// and (floored) maximum error.

void mark_pareto_fronts(std::deque<variant>& rows) {
    for (variant& v : rows) {
        v.front = true;
        for (const variant& w : rows) {
            if (&w == &v || w.family != v.family || w.group != v.group) continue;
            const bool no_worse = w.plot_ns() <= v.plot_ns() && w.plot_error() <= v.plot_error();
            const bool better = w.plot_ns() < v.plot_ns() || w.plot_error() < v.plot_error();
            if (no_worse && better) v.front = false;
        }
    }
}

// ---------------------------------------------------------------------------------------
// Output.

const std::vector<std::string> group_order = {"phase", "transmittance", "integration", "geometry", "multiple_scattering",
                                              "diffusion_lighting", "cone_sampling"};
const std::map<std::string, std::string> group_colour = {
    {"phase", "#1f77b4"},    {"transmittance", "#ff7f0e"},       {"integration", "#2ca02c"},
    {"geometry", "#d62728"}, {"multiple_scattering", "#9467bd"}, {"cone_sampling", "#8c564b"},
    {"diffusion_lighting", "#e377c2"}};
const std::map<std::string, std::string> group_header = {
    {"phase", "phase.hpp"},       {"transmittance", "transmittance.hpp"},
    {"integration", "integration.hpp"}, {"geometry", "geometry.hpp"},
    {"multiple_scattering", "multiple_scattering.hpp"}, {"cone_sampling", "cone_sampling.hpp"},
    {"diffusion_lighting", "diffusion_lighting.hpp"}};
// ---------------------------------------------------------------------------------------
// The physical reference column: each model's error against ground truth no one here wrote
// the answer to, read from the reports of tools/reference: phase rows against the Lorenz-Mie
// phase function of Deirmendjian's C.1 droplets at 0.55 um (docs/phase_error.csv, the
// fraction of scattered light sent in wrong directions); multiple-scattering rows against
// the Monte Carlo path tracer (docs/lighting_error.csv, rms image error over optical
// thickness 1-100). Approximations of a model (textbook and fast:: forms) share the model's
// entry: their own error, in the other columns, is orders of magnitude smaller.
const char* physical_table = "mie_c1_0.55um";

std::string physical_key(const variant& v) {
    if (v.name.rfind("phase_hg_schlick", 0) == 0) return "phase:schlick_moment";
    if (v.family == "Henyey-Greenstein") return "phase:hg_moment";
    if (v.family == "Cornette-Shanks") return "phase:cs_moment";
    if (v.family == "Draine") return "phase:draine_fit";
    if (v.family == "Mie fit (Jendersie-d'Eon)") return "phase:mie_approx_d2reff";
    if (v.group == "diffusion_lighting") return "lighting:preset_diffusion_fitted";
    if (v.group == "multiple_scattering") {
        // The a = b = c = 0.5 rows: "default_beer" at 3 octaves, "default_beer_N" otherwise.
        const int n = std::atoi(v.family.c_str());
        if (n == 1) return "lighting:single";
        if (n == 3) return "lighting:default_beer";
        if (n > 1) return "lighting:default_beer_" + std::to_string(n);
    }
    return "";
}

std::vector<std::string> split_csv_line(const std::string& line) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    return f;
}

// Rows of a CSV (after its '#' lines) as column name -> value maps.
std::vector<std::map<std::string, std::string>> read_csv_table(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::map<std::string, std::string>> rows;
    std::vector<std::string> header;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        const std::vector<std::string> f = split_csv_line(line);
        if (header.empty()) {
            header = f;
            continue;
        }
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < f.size() && i < header.size(); ++i) row[header[i]] = f[i];
        rows.push_back(std::move(row));
    }
    return rows;
}

// Returns how many rows got a value; rows whose key is missing from the files say so.
int fill_physical_column(std::deque<variant>& rows, const std::string& phase_csv, const std::string& lighting_csv) {
    std::map<std::string, std::string> text;
    for (const auto& r : read_csv_table(phase_csv)) {
        const auto t = r.find("table"), id = r.find("variant"), e = r.find("misdirected_energy");
        if (t == r.end() || id == r.end() || e == r.end() || t->second != physical_table) continue;
        text["phase:" + id->second] = printf_string("%.2f of the light misdirected", std::stod(e->second));
    }
    for (const auto& r : read_csv_table(lighting_csv)) {
        const auto kind = r.find("kind"), id = r.find("id"), sub = r.find("subset"), rms = r.find("rms");
        if (kind == r.end() || id == r.end() || sub == r.end() || rms == r.end()) continue;
        if (kind->second != "variant" || sub->second != "all") continue;
        text["lighting:" + id->second] = printf_string("image rms %.0f%% vs Monte Carlo", 100.0 * std::stod(rms->second));
    }
    int filled = 0;
    for (variant& v : rows) {
        const std::string key = physical_key(v);
        if (key.empty()) continue;
        const auto it = text.find(key);
        if (it == text.end()) {
            v.physical = "n/a (" + key + " not in the tools/reference reports)";
            std::cerr << "speed-vs-error: no " << key << " in " << phase_csv << " or " << lighting_csv << '\n';
        } else {
            v.physical = it->second;
            ++filled;
        }
    }
    return filled;
}

std::string csv_quote(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string r = "\"";
    for (char c : s) {
        if (c == '"') r += '"';
        r += c;
    }
    return r + "\"";
}

std::string xml_escape(const std::string& s) {
    std::string r;
    for (char c : s) {
        if (c == '&') r += "&amp;";
        else if (c == '<') r += "&lt;";
        else if (c == '>') r += "&gt;";
        else if (c == '"') r += "&quot;";
        else r += c;
    }
    return r;
}

std::string md_escape(const std::string& s) {
    std::string r;
    for (char c : s) {
        if (c == '|') r += "\\|";
        else if (c == '*') r += "\\*";
        else r += c;
    }
    return r;
}

// Every report file is written atomically (tools/common/atomic_file.hpp: a temporary beside
// it, checked, renamed): a failed write throws, naming the path, and leaves the old file.
void save_report_file(const std::string& path, const std::string& text) {
    const std::string error = cloudmath::tools::write_file_atomically(path, text);
    if (!error.empty()) throw std::runtime_error(error);
}

void write_csv(const std::string& path, const std::deque<variant>& rows) {
    std::ostringstream out;
    out << "variant,group,family,float_ns_per_eval,batch_ns_per_eval,max_rel_error,rms_rel_error,"
           "batch_max_rel_error,batch_rms_rel_error,error_vs_physical_reference,gpu_spirv_instructions,pareto_front,"
           "error_points,max_error_at,error_reference_note,batch_note\n";
    for (const variant& v : rows) {
        auto num = [](double x, const char* f) { return std::isnan(x) ? std::string("-") : std::isinf(x) ? std::string("inf") : printf_string(f, x); };
        out << csv_quote(v.name) << ',' << v.group << ',' << csv_quote(v.family) << ',' << num(v.scalar_ns, "%.4g") << ','
            << num(v.batch_ns, "%.4g") << ',' << num(v.err.max(), "%.3e") << ',' << num(v.err.rms(), "%.3e") << ','
            << num(v.batch_err.max(), "%.3e") << ',' << num(v.batch_err.rms(), "%.3e") << ',' << csv_quote(v.physical) << ','
            << csv_quote(v.gpu_cost) << ',' << (v.front ? "yes" : "no") << ',' << v.err.count << ',' << csv_quote(v.err.where_text()) << ','
            << csv_quote(v.error_note) << ',' << csv_quote(v.batch_note) << '\n';
    }
    save_report_file(path, out.str());
}

std::string batch_cell(const variant& v) {
    std::string s = fmt_ns(v.batch_ns);
    if (!v.batch_note.empty() && !std::isnan(v.batch_ns)) s += " (" + v.batch_note + ")";
    return s;
}

const variant* find_variant(const std::deque<variant>& rows, const std::string& label) {
    for (const variant& v : rows)
        if (v.label == label) return &v;
    return nullptr;
}

struct machine_info {
    std::string cpu, compiler, flags, date, command;
    unsigned cores;
};

void write_markdown(const std::string& path, const std::deque<variant>& rows, const std::vector<truncation_row>& truncation,
                    const machine_info& m, int rounds, double target_seconds, const std::string& cost_source, bool cost_found) {
    std::ostringstream out;
    std::string g_list;
    for (float g : phase_g_values) g_list += (g_list.empty() ? "" : ", ") + fmt_input(g);
    // Timing spread across all rows: the median and the largest half-IQR relative to the median.
    std::vector<double> spreads;
    for (const variant& v : rows) {
        if (!std::isnan(v.scalar_spread)) spreads.push_back(v.scalar_spread);
        if (!std::isnan(v.batch_spread)) spreads.push_back(v.batch_spread);
    }
    std::sort(spreads.begin(), spreads.end());
    const double spread_median = spreads.empty() ? nan_value : spreads[spreads.size() / 2];
    const double spread_max = spreads.empty() ? nan_value : spreads.back();

    out << "# Speed against error of every lighting variant\n\n"
        << "Generated by `" << m.command << "` (rerun it after changing a header; do not edit by hand).\n"
        << "Source: [bench/report/speed_vs_error.cpp](../bench/report/speed_vs_error.cpp) (timed loops in\n"
        << "[bench/report/kernels.cpp](../bench/report/kernels.cpp)); the same data as\n"
        << "[speed_vs_error.csv](speed_vs_error.csv), plotted in [speed_vs_error.svg](speed_vs_error.svg).\n\n"
        << "Machine: " << m.cpu << ", " << m.cores << " hardware threads. Compiler: " << m.compiler << ", flags `" << m.flags
        << "`" << (m.flags.find("-march") == std::string::npos ? " (no `-march`: SSE2 code on x86-64)" : "")
        << "; the batch forms ran their " << cloudmath::batch::isa_name(cloudmath::batch::active_isa())
        << " copy (batch.hpp picks it at run time). Date: " << m.date << ".\n\n"
        << "![speed against error](speed_vs_error.svg)\n\n"
        << "## How it is measured\n\n"
        << "- **Time**: float, nanoseconds per evaluation, median of " << rounds << " rounds. Each round times every\n"
        << "  variant once, in a shuffled order, as one timed block of about " << printf_string("%.0f", target_seconds * 1e3)
        << " ms (`std::chrono::steady_clock`) of repeated\n"
        << "  passes over " << timing_inputs::n << " inputs (" << timing_inputs::n_heavy << " for whole marches and slabs)"
        << " in random order. **Float ns/eval** calls the scalar function once per\n"
        << "  input and keeps each result in a register (an empty `asm volatile` sink), so calls are not\n"
        << "  vectorised across inputs; **batch ns/eval** is the `cloudmath::batch` function over the same array\n"
        << "  (exact_math policy on library rows, fast_math on `fast::` rows), which the compiler vectorises.\n"
        << "  The timed loops are compiled in a small file of their own, so every call inlines as in a user's\n"
        << "  file. The tau inputs reach 1e4: beyond tau = 87 float transmittances are denormal or clamped,\n"
        << "  and products with them can hit the CPU's slow denormal path, which is part of what is timed.\n"
        << "  Inputs: mu uniform on [-1, 1] with g = 0.8 (Draine alpha = 22, Mie fit at d = 10 um, or d\n"
        << "  uniform on [5, 50] um per element for the per-call form); tau half uniform on [0, 10] and half\n"
        << "  log-uniform on [1e-8, 1e4]; sigma_t log-uniform on [1e-9, 1e3] 1/m with ds = 10 m; ray/sphere\n"
        << "  from a camera at 1.8 m to the 1500 m sphere with mu uniform; multiple scattering with\n"
        << "  a = b = c = 0.5. On this shared machine the half inter-quartile range of the rounds was "
        << printf_string("%.1f", 100 * spread_median) << "% of the median for the typical row and "
        << printf_string("%.0f", 100 * spread_max) << "% for the noisiest.\n"
        << "- **Error**: relative error |got - ref| / max(|ref|, 1e-20), maximum and RMS over every point of\n"
        << "  the domain below. Results below 1e-20 (a transmittance of exp(-46)) are judged by their absolute\n"
        << "  error: they are invisible in any image, and float has no relative precision left near its\n"
        << "  denormals (1.2e-38), where `std::exp` returns denormals or 0 and `exp_vectorizable` clamps at\n"
        << "  1.2e-38. A result that is Inf or NaN makes the maximum `inf`; the RMS is then over the finite\n"
        << "  results, and \"Max error at\" counts the others. References are long double, with the HG-type base 1 + g^2 - 2 g mu and the\n"
        << "  ray/sphere roots in quad precision (`__float128`), evaluated at the exact float inputs, so the\n"
        << "  error is the algorithm's, not the rounding of its inputs. \"Max error at\" names the worst input.\n"
        << "  Float rounding alone gives about 6e-8 (half an ulp); the plot draws errors below 1e-9 at 1e-9.\n"
        << "- **Domains** (documented domain plus its hard cases):\n"
        << "  - phase: mu at 401 uniform points on [-1, 1] (+-1 included) and +-(1 - 10^-k), k = 1..7;\n"
        << "    g in {" << g_list << "}; Draine\n"
        << "    alpha in {0, 0.5, 1, 5, 22, 250}; Mie fit d in {0.05, 0.5, 1, 2, 3, 5, 10, 20, 35, 50} um.\n"
        << "    Schlick is measured against HG, which it stands in for. The Mie table is filled from the\n"
        << "    library's float fit and measured against the library's analytic fit in double: its error is\n"
        << "    the lookup's. The per-call and precomputed Mie forms are measured against the fit's formulas\n"
        << "    evaluated in long double (so their error includes the float rounding of the parameters).\n"
        << "  - transmittance: tau = 0, 10^-8 .. 10^4 (10 points a decade) and 0.05 .. 10 in steps of 0.05;\n"
        << "    powder with k = 2.\n"
        << "  - integration (step): S = 0.37, ds in {1, 10, 100} m, sigma_t in {0, 1e-30, 1e-20} and\n"
        << "    10^-10 .. 10^2 1/m (10 a decade), against the exact step integral S (1 - e^-x)/sigma_t.\n"
        << "    Homogeneous slab: 1 km, S = 1/m, slab optical depth 0 and 10^-8 .. 10^4, radiance leaving\n"
        << "    the slab after N steps against S (1 - e^-tau)/sigma_t.\n"
        << "  - geometry: R = 6371 km; camera 1.8 m and 1000 m below the 1500 m sphere, 10 km above the\n"
        << "    4000 m sphere; mu at 2001 uniform points and +-j 10^-k (j = 1..9, k = 2..7) near the horizon;\n"
        << "    first root at t >= 0 against quad roots; grazing rays from above whose two roots lie within\n"
        << "    1% of each other are left out (ill-conditioned for any formula).\n"
        << "  - multiple_scattering: each octave count N against the long double evaluation of the same\n"
        << "    N-octave formula (not against more octaves: that is truncation, tabulated separately below);\n"
        << "    g in {-0.5, 0, 0.5, 0.8, 0.9, 0.99, 0.999}, (a, b, c) = (0.5, 0.5, 0.5) and (0.3, 0.75, 0.5),\n"
        << "    tau = 0, 10^-8 .. 10^4 (4 a decade) and 0.5 .. 10, mu at 41 uniform points and +-(1 - 10^-k).\n"
        << "  - cone_sampling: optical depth over 1 km toward the light through the smooth field\n"
        << "    sigma_t = 0.01 (1.2 + sin(0.004 x + 0.3) sin(0.005 y + 1.1) cos(0.003 z - 0.7)) 1/m, from 512\n"
        << "    random points of a 4 km box toward random directions at least 6 degrees above the horizon,\n"
        << "    against a 4096-step midpoint march of the same field in long double. The cone has 5 near\n"
        << "    samples every 100 m and the far sample at 750 m standing for 500 m; with spread 0.5 the\n"
        << "    samples leave the ray on purpose (a soft shadow), so its error includes that blur.\n"
        << "- **GPU cost**: SPIR-V instructions of the GLSL twin after `spirv-opt -O`, read from\n"
        << "  [" << cost_source << "](glsl_cost.md)" << (cost_found ? "" : " (not found when this ran)")
        << "; a static count, loops counted once (so every octave count shows the\n"
        << "  same number), \"-\" where there is no GLSL twin (textbook and `fast::` forms). Counts are net of\n"
        << "  a baseline shader, so a call that folds into very little can show 0 or less (`beer_lambert`).\n"
        << "- **Pareto front**: within each family of interchangeable variants (same quantity, same group),\n"
        << "  the variants that no other one beats in both scalar time and maximum error are in **bold**, and\n"
        << "  outlined and connected in the plot. Ties within the timing noise can fall either way (the\n"
        << "  library's `beer_lambert` and `std::exp(-tau)` are the same call).\n"
        << "- **Error vs physical reference**: the model's error against ground truth, from the reports of\n"
        << "  tools/reference. Phase rows: the fraction of the scattered light the model sends in wrong\n"
        << "  directions against the Lorenz-Mie phase function of Deirmendjian's C.1 droplets at 0.55 um, with\n"
        << "  g = the table's mean cosine (HG, Schlick), its Cornette-Shanks equivalent, Draine fitted, or the\n"
        << "  Jendersie-d'Eon fit at d = 2 r_eff ([phase_error.md](phase_error.md)). Multiple-scattering rows\n"
        << "  (a = b = c = 0.5, as timed): rms error of the radiance against a Monte Carlo path tracer over spheres and\n"
        << "  slabs of optical thickness 1-100, relative to each image's mean ([lighting_error.md](lighting_error.md)).\n"
        << "  Textbook and `fast::` forms compute the same model and share its entry.\n\n";

    out << "## All variants\n\n"
        << "| Variant | Group | Float ns/eval | Batch ns/eval | Max rel error | RMS rel error | Batch max rel error | Max error at | Error vs physical reference | GPU cost (SPIR-V) |\n"
        << "|---|---|---:|---:|---:|---:|---:|---|---|---:|\n";
    for (const std::string& group : group_order)
        for (const variant& v : rows) {
            if (v.group != group) continue;
            std::string name = md_escape(v.name);
            if (v.front) name = "**" + name + "**";
            std::string at = md_escape(v.err.where_text());
            if (!v.error_note.empty()) at += " (" + md_escape(v.error_note) + ")";
            out << "| " << name << " | " << v.group << " | " << fmt_ns(v.scalar_ns) << " | " << batch_cell(v) << " | "
                << fmt_error(v.err.max()) << " | " << fmt_error(v.err.rms()) << " | " << fmt_error(v.batch_err.max()) << " | " << at
                << " | " << md_escape(v.physical) << " | " << v.gpu_cost << " |\n";
        }

    out << "\n## Multiple scattering: truncation change from N to N + 1 octaves\n\n"
        << "How much the (N+1)-th octave changes the sum, |S(N+1) - S(N)| / S(N+1), evaluated in long double\n"
        << "over the multiple-scattering domain above: the physical error of stopping at N octaves is not\n"
        << "measured here (that needs the Monte Carlo reference), only how far the octave sum still moves.\n"
        << "The maximum is near 1 for every N: at large tau the new octave, attenuated by exp(-a^N tau)\n"
        << "instead of exp(-tau), outweighs all the earlier ones.\n\n"
        << "| N -> N + 1 | median, " << ms_sets[0].name << " | RMS | max | median, " << ms_sets[1].name << " | RMS | max |\n"
        << "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const truncation_row& r : truncation)
        out << "| " << r.octaves << " -> " << r.octaves + 1 << " | " << fmt_error(r.median_change[0]) << " | " << fmt_error(r.rms_change[0])
            << " | " << fmt_error(r.max_change[0]) << " | " << fmt_error(r.median_change[1]) << " | " << fmt_error(r.rms_change[1]) << " | "
            << fmt_error(r.max_change[1]) << " |\n";

    // The condensed table the README quotes (copied verbatim from here).
    out << "\n## Headline rows\n\n"
        << "| Variant | Float ns/eval | Batch ns/eval | Max rel error |\n|---|---:|---:|---:|\n";
    for (const char* label : {"HG", "HG naive", "HG fast", "HG Schlick", "Beer", "Beer naive", "Beer fast", "exp_vectorizable",
                              "Beer-Powder", "BP naive", "BP fast", "step exact", "step clamp", "ray/sphere altitude",
                              "ray/sphere naive", "MS3", "MS3 fast", "cone 6, spread 0", "march 64"}) {
        const variant* v = find_variant(rows, label);
        if (!v) continue;
        out << "| " << md_escape(v->name) << " | " << fmt_ns(v->scalar_ns) << " | " << batch_cell(*v) << " | " << fmt_error(v->err.max())
            << " |\n";
    }
    out << "\nMachine: " << m.cpu << ", " << m.cores << " hardware threads; " << m.compiler << " `" << m.flags << "`, batch forms "
        << cloudmath::batch::isa_name(cloudmath::batch::active_isa()) << " (run-time dispatch); " << m.date << ".\n";
    save_report_file(path, out.str());
}

// Log-log scatter plot: x = float ns/eval, y = max relative error (floored), colour per
// group, Pareto fronts per family outlined and connected, one label per point. Batch forms
// are hollow diamonds joined to their scalar point by a dotted line. Results that are Inf or
// NaN sit in a band above the log axis.
void write_svg(const std::string& path, const std::deque<variant>& rows, const machine_info& m) {
    struct point {
        const variant* v;
        double x, y;
        bool batch;
    };
    std::vector<point> points;
    for (const variant& v : rows) {
        if (!std::isnan(v.scalar_ns)) points.push_back({&v, v.scalar_ns, std::max(v.err.max(), plot_error_floor), false});
        if (!std::isnan(v.batch_ns) && !v.batch_err.empty())
            points.push_back({&v, v.batch_ns, std::max(v.batch_err.max(), plot_error_floor), true});
    }
    double min_x = 1e300, max_x = 0, max_y = plot_error_floor;
    bool any_inf = false;
    for (const point& p : points) {
        min_x = std::min(min_x, p.x);
        max_x = std::max(max_x, p.x);
        if (std::isfinite(p.y)) max_y = std::max(max_y, p.y);
        else any_inf = true;
    }
    const double W = 1200, H = 840, left = 96, right = 250, top = 64, bottom = 70;
    const double band = any_inf ? 40 : 0;  // the Inf/NaN band above the log axis
    const double pw = W - left - right, ph = H - top - bottom - band;
    const double y0 = top + band;  // top of the log area
    const int lx0 = static_cast<int>(std::floor(std::log10(min_x)));
    const int lx1 = std::max(lx0 + 1, static_cast<int>(std::ceil(std::log10(max_x))));
    const int ly0 = static_cast<int>(std::floor(std::log10(plot_error_floor)));
    const int ly1 = std::max(0, static_cast<int>(std::ceil(std::log10(max_y))));
    auto X = [&](double x) { return left + (std::log10(x) - lx0) / (lx1 - lx0) * pw; };
    auto Y = [&](double y) {
        if (!std::isfinite(y)) return top + band / 2;
        return y0 + ph - (std::log10(y) - ly0) / (ly1 - ly0) * ph;
    };
    auto num = [](double v) { return printf_string("%.1f", v); };
    std::ostringstream s;
    s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W << ' ' << H
      << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << left << "\" y=\"26\" font-size=\"17\" font-weight=\"bold\">cloudmath: speed against error of every lighting variant (float)</text>\n"
      << "<text x=\"" << left << "\" y=\"46\" font-size=\"11\" fill=\"#444\">" << xml_escape(m.cpu) << ", " << m.cores << " threads; "
      << xml_escape(m.compiler) << ' ' << xml_escape(m.flags) << "; " << xml_escape(m.date) << ". Lower left is better.</text>\n";

    // Grid, decade ticks and their labels.
    s << "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
    for (int k = lx0; k <= lx1; ++k) {
        const double x = X(std::pow(10.0, k));
        s << "<line x1=\"" << num(x) << "\" y1=\"" << top << "\" x2=\"" << num(x) << "\" y2=\"" << y0 + ph << "\"/>\n";
    }
    for (int k = ly0; k <= ly1; ++k) {
        const double y = Y(std::pow(10.0, k));
        s << "<line x1=\"" << left << "\" y1=\"" << num(y) << "\" x2=\"" << left + pw << "\" y2=\"" << num(y) << "\"/>\n";
    }
    s << "</g>\n<g stroke=\"#888\" stroke-width=\"1\">\n";
    for (int k = lx0; k < lx1; ++k)
        for (int j = 2; j <= 9; ++j) {
            const double x = X(j * std::pow(10.0, k));
            s << "<line x1=\"" << num(x) << "\" y1=\"" << y0 + ph << "\" x2=\"" << num(x) << "\" y2=\"" << y0 + ph - 4 << "\"/>\n";
        }
    for (int k = ly0; k < ly1; ++k)
        for (int j = 2; j <= 9; ++j) {
            const double y = Y(j * std::pow(10.0, k));
            s << "<line x1=\"" << left << "\" y1=\"" << num(y) << "\" x2=\"" << left + 4 << "\" y2=\"" << num(y) << "\"/>\n";
        }
    s << "</g>\n<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph + band
      << "\" fill=\"none\" stroke=\"#333\"/>\n";
    if (any_inf)
        s << "<line x1=\"" << left << "\" y1=\"" << y0 << "\" x2=\"" << left + pw << "\" y2=\"" << y0
          << "\" stroke=\"#333\" stroke-dasharray=\"4,3\"/>\n"
          << "<text x=\"" << left - 8 << "\" y=\"" << num(top + band / 2 + 4) << "\" text-anchor=\"end\" font-size=\"12\">Inf/NaN</text>\n";
    auto time_label = [](int k) {  // 10^k ns
        static const char* units[] = {"ps", "ns", "\u00b5s", "ms", "s"};
        const int unit = k + 3 >= 0 ? (k + 3) / 3 : -1;
        if (unit < 0 || unit > 4) return "1e" + std::to_string(k) + " ns";
        const int power = k - (unit - 1) * 3;
        return std::string(power == 0 ? "1" : power == 1 ? "10" : "100") + ' ' + units[unit];
    };
    s << "<g font-size=\"12\" fill=\"#222\">\n";
    for (int k = lx0; k <= lx1; ++k)
        s << "<text x=\"" << num(X(std::pow(10.0, k))) << "\" y=\"" << y0 + ph + 18 << "\" text-anchor=\"middle\">" << time_label(k) << "</text>\n";
    for (int k = ly0; k <= ly1; ++k)
        s << "<text x=\"" << left - 8 << "\" y=\"" << num(Y(std::pow(10.0, k)) + 4) << "\" text-anchor=\"end\">"
          << (k == ly0 ? "\u2264 " : "") << "10<tspan dy=\"-6\" font-size=\"9\">" << k << "</tspan></text>\n";
    s << "<text x=\"" << num(left + pw / 2) << "\" y=\"" << H - 22
      << "\" text-anchor=\"middle\" font-size=\"13\">time per evaluation, float (median; log scale)</text>\n"
      << "<text transform=\"translate(22," << num(y0 + ph / 2) << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">"
      << "maximum relative error over the domain and its hard cases (log scale)</text>\n</g>\n";

    // Batch forms: dotted line from the scalar point to a hollow diamond.
    s << "<g stroke-width=\"1.2\">\n";
    for (const point& p : points) {
        if (!p.batch) continue;
        const std::string colour = group_colour.at(p.v->group);
        const double x = X(p.x), y = Y(p.y);
        if (!std::isnan(p.v->scalar_ns))
            s << "<line x1=\"" << num(X(p.v->scalar_ns)) << "\" y1=\"" << num(Y(std::max(p.v->err.max(), plot_error_floor))) << "\" x2=\""
              << num(x) << "\" y2=\"" << num(y) << "\" stroke=\"" << colour << "\" stroke-dasharray=\"2,2\" stroke-opacity=\"0.8\"/>\n";
        s << "<path d=\"M" << num(x) << ',' << num(y - 5) << " L" << num(x + 5) << ',' << num(y) << " L" << num(x) << ',' << num(y + 5)
          << " L" << num(x - 5) << ',' << num(y) << " Z\" fill=\"white\" stroke=\"" << colour << "\"><title>"
          << xml_escape(p.v->name + ", batch form: " + fmt_ns(p.x) + " ns, max rel error " + fmt_error(p.v->batch_err.max()))
          << "</title></path>\n";
    }
    s << "</g>\n";

    // Pareto fronts (scalar points): one polyline per family through its front points.
    std::map<std::string, std::vector<const variant*>> fronts;
    for (const variant& v : rows)
        if (v.front && !std::isnan(v.plot_ns())) fronts[v.group + "/" + v.family].push_back(&v);
    s << "<g fill=\"none\" stroke-width=\"1.6\" stroke-opacity=\"0.75\">\n";
    for (auto& [key, members] : fronts) {
        if (members.size() < 2) continue;
        std::sort(members.begin(), members.end(), [](const variant* a, const variant* b) { return a->plot_ns() < b->plot_ns(); });
        s << "<polyline stroke=\"" << group_colour.at(members.front()->group) << "\" points=\"";
        for (const variant* v : members) s << num(X(v->plot_ns())) << ',' << num(Y(v->plot_error())) << ' ';
        s << "\"/>\n";
    }
    s << "</g>\n";

    // Scalar points, then their labels, placed greedily where they overlap the least.
    struct box {
        double x0, y0, x1, y1;
    };
    auto overlap = [](const box& a, const box& b) {
        const double w = std::min(a.x1, b.x1) - std::max(a.x0, b.x0), h = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
        return w > 0 && h > 0 ? w * h : 0.0;
    };
    std::vector<box> occupied;
    std::vector<const point*> labelled;
    for (const point& p : points) {
        const double x = X(p.x), y = Y(p.y);
        occupied.push_back({x - 5, y - 5, x + 5, y + 5});
        if (p.batch) continue;
        labelled.push_back(&p);
        s << "<circle cx=\"" << num(x) << "\" cy=\"" << num(y) << "\" r=\"" << (p.v->front ? 5.5 : 3.8) << "\" fill=\""
          << group_colour.at(p.v->group) << "\"" << (p.v->front ? " stroke=\"black\" stroke-width=\"1.3\"" : " fill-opacity=\"0.85\"")
          << "><title>" << xml_escape(p.v->name + ": " + fmt_ns(p.x) + " ns, max rel error " + fmt_error(p.v->err.max()))
          << "</title></circle>\n";
    }
    s << "<g font-size=\"10\" fill=\"#222\">\n";
    std::stable_sort(labelled.begin(), labelled.end(), [](const point* a, const point* b) { return a->v->front && !b->v->front; });
    struct candidate {
        double dx, dy;
        int anchor;  // -1 end, 0 middle, 1 start
    };
    const candidate candidates[] = {{8, 3.5, 1},  {-8, 3.5, -1}, {6, -7, 1},    {6, 14, 1},    {-6, -7, -1},
                                    {-6, 14, -1}, {0, -10, 0},   {0, 18, 0},    {12, -16, 1},  {12, 24, 1},
                                    {-12, -16, -1}, {-12, 24, -1}, {0, -22, 0}, {0, 30, 0}};
    static const char* anchors[] = {"end", "middle", "start"};
    for (const point* p : labelled) {
        const double x = X(p->x), y = Y(p->y);
        const double width = 5.8 * static_cast<double>(p->v->label.size()), height = 11;
        double best_score = 1e300;
        box best_box{};
        const candidate* best = &candidates[0];
        for (const candidate& c : candidates) {
            const double tx = x + c.dx, ty = y + c.dy;
            const double x0 = c.anchor > 0 ? tx : c.anchor < 0 ? tx - width : tx - width / 2;
            const box b{x0, ty - height + 2, x0 + width, ty + 2};
            double score = 0;
            for (const box& o : occupied) score += overlap(b, o);
            if (b.x0 < left || b.x1 > left + pw || b.y0 < top || b.y1 > y0 + ph) score += 1e4;
            score += 0.01 * (std::abs(c.dx) + std::abs(c.dy));  // the nearest position wins ties
            if (score < best_score) {
                best_score = score;
                best = &c;
                best_box = b;
            }
        }
        occupied.push_back(best_box);
        s << "<text x=\"" << num(x + best->dx) << "\" y=\"" << num(y + best->dy) << "\" text-anchor=\"" << anchors[best->anchor + 1] << "\">"
          << xml_escape(p->v->label) << "</text>\n";
    }
    s << "</g>\n";

    // Legend.
    const double lx = left + pw + 20;
    double ly = top + 10;
    s << "<g font-size=\"12\">\n<text x=\"" << lx << "\" y=\"" << ly << "\" font-weight=\"bold\">Group (header)</text>\n";
    for (const std::string& g : group_order) {
        ly += 20;
        s << "<circle cx=\"" << lx + 6 << "\" cy=\"" << ly - 4 << "\" r=\"5\" fill=\"" << group_colour.at(g) << "\"/>"
          << "<text x=\"" << lx + 18 << "\" y=\"" << ly << "\">" << group_header.at(g) << "</text>\n";
    }
    ly += 34;
    s << "<circle cx=\"" << lx + 6 << "\" cy=\"" << ly - 4 << "\" r=\"5.5\" fill=\"#bbb\" stroke=\"black\" stroke-width=\"1.3\"/>"
      << "<text x=\"" << lx + 18 << "\" y=\"" << ly << "\">Pareto front within</text>\n"
      << "<text x=\"" << lx + 18 << "\" y=\"" << ly + 15 << "\">a family of variants that</text>\n"
      << "<text x=\"" << lx + 18 << "\" y=\"" << ly + 30 << "\">compute the same thing</text>\n"
      << "<text x=\"" << lx + 18 << "\" y=\"" << ly + 45 << "\">(scalar calls; connected)</text>\n";
    ly += 72;
    s << "<path d=\"M" << lx + 6 << ',' << ly - 9 << " L" << lx + 11 << ',' << ly - 4 << " L" << lx + 6 << ',' << ly + 1 << " L" << lx + 1 << ','
      << ly - 4 << " Z\" fill=\"white\" stroke=\"#555\" stroke-width=\"1.2\"/>"
      << "<text x=\"" << lx + 18 << "\" y=\"" << ly << "\">batch form (batch.hpp),</text>\n"
      << "<text x=\"" << lx + 18 << "\" y=\"" << ly + 15 << "\">dotted to its scalar call</text>\n";
    ly += 45;
    s << "<text x=\"" << lx << "\" y=\"" << ly << "\" fill=\"#444\">Errors below 1e-9 are</text>\n"
      << "<text x=\"" << lx << "\" y=\"" << ly + 15 << "\" fill=\"#444\">drawn at the floor; float</text>\n"
      << "<text x=\"" << lx << "\" y=\"" << ly + 30 << "\" fill=\"#444\">rounding alone is ~6e-8.</text>\n"
      << "<text x=\"" << lx << "\" y=\"" << ly + 55 << "\" fill=\"#444\">Table and method:</text>\n"
      << "<text x=\"" << lx << "\" y=\"" << ly + 70 << "\" fill=\"#444\">docs/speed_vs_error.md</text>\n"
      << "</g>\n</svg>\n";
    save_report_file(path, s.str());
}

std::string read_cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos) return trim(line.substr(colon + 1));
        }
    return "unknown CPU";
}

std::string utc_date() {
    const std::time_t now = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    return buf;
}

}  // namespace

int main(int argc, char** argv) {
    std::string out_dir = std::string(CLOUDMATH_REPORT_SOURCE_DIR) + "/docs";
    std::string cost_path = std::string(CLOUDMATH_REPORT_SOURCE_DIR) + "/docs/glsl_cost.md";
    std::string phase_error_path = std::string(CLOUDMATH_REPORT_SOURCE_DIR) + "/docs/phase_error.csv";
    std::string lighting_error_path = std::string(CLOUDMATH_REPORT_SOURCE_DIR) + "/docs/lighting_error.csv";
    std::string command = "build/bench/bench/report/cloudmath_speed_vs_error";
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--out-dir" && i + 1 < argc) out_dir = argv[++i];
        else if (a == "--glsl-cost" && i + 1 < argc) cost_path = argv[++i];
        else if (a == "--phase-error" && i + 1 < argc) phase_error_path = argv[++i];
        else if (a == "--lighting-error" && i + 1 < argc) lighting_error_path = argv[++i];
        else if (a == "--command" && i + 1 < argc) command = argv[++i];
        else if (a == "--quick") quick = true;
        else {
            std::cerr << "usage: " << argv[0] << " [--out-dir DIR] [--glsl-cost FILE] [--phase-error FILE] [--lighting-error FILE] [--command TEXT] [--quick]\n";
            return 2;
        }
    }

    const auto start = std::chrono::steady_clock::now();
    const std::unique_ptr<timing_inputs> inputs = make_timing_inputs();
    const pass_inputs* view = &inputs->view;
    std::deque<variant> rows;
    std::cout << "speed-vs-error: measuring errors" << std::endl;
    add_phase_variants(rows, view);
    add_transmittance_variants(rows, view);
    add_integration_variants(rows, view);
    add_geometry_variants(rows, view);
    const std::vector<truncation_row> truncation = add_multiple_scattering_variants(rows, view);
    add_diffusion_variants(rows, view);
    add_light_variants(rows, view);
    std::cout << "speed-vs-error: errors of " << rows.size() << " variants done in "
              << printf_string("%.1f", seconds_of(std::chrono::steady_clock::now() - start)) << " s; timing" << std::endl;

    std::vector<timing_job> jobs;
    for (variant& v : rows) {
        if (v.scalar_pass) jobs.push_back({&v.scalar_pass, v.scalar_evals, &v.scalar_ns, &v.scalar_spread, 1, {}});
        if (v.batch_pass) jobs.push_back({&v.batch_pass, v.batch_evals, &v.batch_ns, &v.batch_spread, 1, {}});
    }
    const int rounds = quick ? 5 : 41;
    const double target_seconds = quick ? 0.001 : 0.005;
    run_timings(jobs, rounds, target_seconds);

    const std::vector<cost_entry> costs = parse_glsl_cost(cost_path);
    for (variant& v : rows) {
        if (v.glsl_function.empty()) continue;
        for (const cost_entry& c : costs)
            if (c.function == v.glsl_function && c.expression.find(v.glsl_expression) != std::string::npos) {
                v.gpu_cost = c.count + v.cost_suffix;
                break;
            }
        if (v.gpu_cost == "-") std::cerr << "speed-vs-error: no SPIR-V count for " << v.glsl_function << " in " << cost_path << '\n';
    }
    mark_pareto_fronts(rows);
    fill_physical_column(rows, phase_error_path, lighting_error_path);

    machine_info m;
    m.cpu = read_cpu_model();
    m.cores = std::thread::hardware_concurrency();
    m.compiler = CLOUDMATH_REPORT_COMPILER;
    m.flags = CLOUDMATH_REPORT_FLAGS;
    m.date = utc_date();
    m.command = command;

    try {
        write_csv(out_dir + "/speed_vs_error.csv", rows);
        write_markdown(out_dir + "/speed_vs_error.md", rows, truncation, m, rounds, target_seconds, "docs/glsl_cost.md", !costs.empty());
        write_svg(out_dir + "/speed_vs_error.svg", rows, m);
    } catch (const std::runtime_error& e) {
        std::cerr << "speed-vs-error: " << e.what() << '\n';
        return 1;
    }

    auto pad = [](std::string text, std::size_t width, bool right_align) {
        const std::size_t fill = text.size() < width ? width - text.size() : 0;
        return right_align ? std::string(fill, ' ') + text : text + std::string(fill, ' ');
    };
    for (const variant& v : rows)
        std::cout << pad(v.name, 72, false) << pad(fmt_ns(v.scalar_ns), 8, true) << " ns" << pad(fmt_ns(v.batch_ns), 8, true)
                  << " ns  max " << pad(fmt_error(v.err.max()), 7, true) << "  rms " << pad(fmt_error(v.err.rms()), 7, true)
                  << (v.front ? "  front" : "") << '\n';
    std::cout << "speed-vs-error: wrote " << out_dir << "/speed_vs_error.{md,csv,svg} in "
              << printf_string("%.1f", seconds_of(std::chrono::steady_clock::now() - start)) << " s" << std::endl;
    return 0;
}
