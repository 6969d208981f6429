// tools/reference/optics/size_distribution.cpp: see size_distribution.hpp (Deirmendjian 1969;
// Hansen & Travis 1974).
#include "size_distribution.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "mie.hpp"

namespace cloudmath::reference {

namespace {

constexpr double pi = 3.14159265358979323846;

// Radii per chunk of work: fixed, so that the summation order never depends on the threads.
constexpr std::size_t chunk_radii = 32;

double cos_deg(double theta) {
    if (theta == 90.0) return 0.0;  // as phase_table: exact 0 and -1 at 90 and 180 deg
    if (theta == 180.0) return -1.0;
    return std::cos(theta * (pi / 180.0));
}

// ln of the cross-section weight r^2 n(r), up to a constant.
double log_cross_section_weight(const modified_gamma& d, double r) {
    return (d.alpha + 2.0) * std::log(r) - d.b * std::pow(r, d.gamma);
}

// The radius above the mode where r^2 n(r) has fallen to cutoff times its maximum (bisection
// on the log, which decreases monotonically there).
double upper_radius(const modified_gamma& d, double cutoff) {
    const double mode = d.cross_section_mode_um();
    const double target = log_cross_section_weight(d, mode) + std::log(cutoff);
    double lo = mode, hi = 2.0 * mode;
    while (log_cross_section_weight(d, hi) > target) {
        lo = hi;
        hi *= 2.0;
    }
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (log_cross_section_weight(d, mid) > target ? lo : hi) = mid;
    }
    return hi;
}

// The integrand per unit size parameter at x = k r: n(r) dr/dx times
//   [ |S1|^2 + |S2|^2 at every angle ..., 1, C_ext, C_sca, C_sca g, r^2, r^3 ].
// The last six components give the droplet count, the mean cross sections, g and r_eff.
class integrand {
public:
    static constexpr std::size_t scalar_count = 6;

    integrand(const modified_gamma& d, std::complex<double> m, double k,
              const std::vector<double>& mu)
        : distribution_(d), m_(m), k_(k), mu_(mu) {}

    [[nodiscard]] std::size_t size() const { return mu_.size() + scalar_count; }

    void evaluate(double x, std::vector<double>& out) const {
        out.assign(size(), 0.0);
        const double r = x / k_;
        const double w = distribution_.density(r) / k_;
        if (!(w > 0.0)) return;
        const mie_coefficients coef = compute_mie_coefficients(m_, x);
        const mie_efficiencies e = compute_efficiencies(coef);
        accumulate_intensity(coef, mu_, w, out);
        const double area = pi * r * r;
        double* s = out.data() + mu_.size();
        s[0] = w;
        s[1] = w * area * e.q_ext;
        s[2] = w * area * e.q_sca;
        s[3] = w * area * e.q_sca * e.g;
        s[4] = w * r * r;
        s[5] = w * r * r * r;
    }

private:
    const modified_gamma& distribution_;
    std::complex<double> m_;
    double k_;
    const std::vector<double>& mu_;
};

// Adaptive midpoint rule on one cell (why: see size_distribution.hpp). The cell [center - width/2,
// center + width/2] is split in three; the middle third reuses the centre value, so each refinement
// costs two evaluations. A cell is refined while the three-point and one-point estimates differ by
// more than width * tolerance_density in any component; the accepted error of all cells together
// stays below the sum of tolerance_density over the whole range. max_depth bounds the refinement
// (3^-depth).
struct adaptive_cell_integrator {
    const integrand& f;
    const std::vector<double>& tolerance_density;
    int max_depth;

    // Adds the integral over the cell to sum; returns the number of evaluations made.
    std::size_t integrate(double center, double width, const std::vector<double>& f_center,
                          int depth, std::vector<double>& sum) const {
        const std::size_t n = f.size();
        if (depth >= max_depth) {
            for (std::size_t j = 0; j < n; ++j) sum[j] += width * f_center[j];
            return 0;
        }
        const double third = width / 3.0;
        std::vector<double> f_left, f_right;
        f.evaluate(center - third, f_left);
        f.evaluate(center + third, f_right);
        std::size_t evaluations = 2;
        bool converged = true;
        for (std::size_t j = 0; j < n && converged; ++j)
            converged =
                std::abs(f_left[j] + f_right[j] - 2.0 * f_center[j]) <= 3.0 * tolerance_density[j];
        if (converged) {
            for (std::size_t j = 0; j < n; ++j)
                sum[j] += third * (f_left[j] + f_center[j] + f_right[j]);
            return evaluations;
        }
        evaluations += integrate(center - third, third, f_left, depth + 1, sum);
        evaluations += integrate(center, third, f_center, depth + 1, sum);
        evaluations += integrate(center + third, third, f_right, depth + 1, sum);
        return evaluations;
    }
};

// Runs task(chunk, sums) for every chunk on thread_count threads; every chunk has its own
// sums vector, so the caller can add them in chunk order. Reports progress on the calling
// thread as progress_offset + progress_scale * (done cost / total cost).
template <class Task>
std::vector<std::vector<double>> run_chunks(std::size_t chunk_count, unsigned thread_count,
                                            const std::vector<double>& chunk_cost, Task&& task,
                                            const std::function<void(double)>& progress,
                                            double progress_offset, double progress_scale) {
    std::vector<std::vector<double>> sums(chunk_count);
    double total_cost = 0.0;
    for (double c : chunk_cost) total_cost += c;
    std::atomic<std::size_t> next_chunk{0};
    std::mutex mutex;
    std::condition_variable finished;
    double done_cost = 0.0;
    unsigned running = thread_count;
    const auto worker = [&]() {
        for (;;) {
            const std::size_t c = next_chunk.fetch_add(1);
            if (c >= chunk_count) break;
            task(c, sums[c]);
            std::lock_guard<std::mutex> lock(mutex);
            done_cost += chunk_cost[c];
        }
        std::lock_guard<std::mutex> lock(mutex);
        --running;
        finished.notify_all();
    };
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < thread_count; ++t) threads.emplace_back(worker);
    {
        std::unique_lock<std::mutex> lock(mutex);
        while (running > 0) {
            finished.wait_for(lock, std::chrono::milliseconds(250));
            if (progress && running > 0) {
                const double fraction = total_cost > 0.0 ? done_cost / total_cost : 1.0;
                lock.unlock();
                progress(progress_offset + progress_scale * fraction);
                lock.lock();
            }
        }
    }
    for (auto& t : threads) t.join();
    return sums;
}

// Adds the chunk sums in chunk order (the order never depends on the threads).
std::vector<double> add_in_order(const std::vector<std::vector<double>>& sums, std::size_t size) {
    std::vector<double> total(size, 0.0);
    for (const auto& s : sums)
        for (std::size_t j = 0; j < s.size(); ++j) total[j] += s[j];
    return total;
}

}  // namespace

double modified_gamma::density(double r_um) const {
    if (!(r_um > 0.0)) return 0.0;
    return scale * std::pow(r_um, alpha) * std::exp(-b * std::pow(r_um, gamma));
}

double modified_gamma::effective_radius_um() const {
    return std::exp(std::lgamma((alpha + 4.0) / gamma) - std::lgamma((alpha + 3.0) / gamma)) *
           std::pow(b, -1.0 / gamma);
}

double modified_gamma::total_number() const {
    const double s = (alpha + 1.0) / gamma;
    return scale * std::exp(std::lgamma(s)) / (gamma * std::pow(b, s));
}

double modified_gamma::cross_section_mode_um() const {
    return std::pow((alpha + 2.0) / (b * gamma), 1.0 / gamma);
}

void modified_gamma::validate() const {
    const bool finite =
        std::isfinite(scale) && std::isfinite(alpha) && std::isfinite(b) && std::isfinite(gamma);
    if (!finite || !(scale > 0.0) || !(alpha > -1.0) || !(b > 0.0) || !(gamma > 0.0))
        throw std::invalid_argument(
            "modified gamma distribution needs scale > 0, alpha > -1, b > 0, gamma > 0");
}

modified_gamma deirmendjian_c1() { return {2.373, 6.0, 1.5, 1.0}; }

modified_gamma modified_gamma_from_effective_radius(double r_eff_um, double alpha, double gamma) {
    if (!(r_eff_um > 0.0) || !std::isfinite(r_eff_um))
        throw std::invalid_argument("effective radius must be finite and > 0");
    modified_gamma d{1.0, alpha, 1.0, gamma};
    d.validate();
    // r_eff = ratio * b^(-1/gamma)  =>  b = (ratio / r_eff)^gamma.
    const double ratio =
        std::exp(std::lgamma((alpha + 4.0) / gamma) - std::lgamma((alpha + 3.0) / gamma));
    d.b = std::pow(ratio / r_eff_um, gamma);
    // One droplet in total.
    const double s = (alpha + 1.0) / gamma;
    d.scale = gamma * std::pow(d.b, s) / std::exp(std::lgamma(s));
    d.validate();
    return d;
}

std::optional<std::complex<double>> default_water_index(double wavelength_um) {
    if (std::abs(wavelength_um - 0.55) < 1e-9) return std::complex<double>(1.333, -1.96e-9);
    if (std::abs(wavelength_um - 0.70) < 1e-9) return std::complex<double>(1.33, 0.0);
    return std::nullopt;
}

mean_phase_result compute_mean_phase(const modified_gamma& distribution,
                                     const mean_phase_settings& settings) {
    distribution.validate();
    const double lambda = settings.wavelength_um;
    const double step = settings.size_parameter_step;
    if (!(lambda > 0.0) || !std::isfinite(lambda))
        throw std::invalid_argument("wavelength must be > 0");
    if (!(step > 0.0) || !std::isfinite(step))
        throw std::invalid_argument("size parameter step must be > 0");
    if (!(settings.relative_tolerance > 0.0) || settings.max_refinement_depth < 0 ||
        settings.max_refinement_depth > 30)
        throw std::invalid_argument("relative tolerance must be > 0, refinement depth 0 .. 30");
    if (!(settings.weight_cutoff > 0.0 && settings.weight_cutoff < 1.0))
        throw std::invalid_argument("weight cutoff must lie in (0, 1)");
    if (!(settings.refractive_index.real() > 0.0) ||
        !std::isfinite(settings.refractive_index.real()) ||
        !std::isfinite(settings.refractive_index.imag()))
        throw std::invalid_argument("refractive index needs a finite real part > 0");

    const std::vector<double> angles =
        settings.angles_deg.empty() ? default_angles_deg() : settings.angles_deg;
    std::vector<double> mu(angles.size());
    std::transform(angles.begin(), angles.end(), mu.begin(), cos_deg);

    // Cells of width step in x centred on x_i = (i + 1/2) step, r_i = x_i / k.
    const double k = 2.0 * pi / lambda;
    const double x_max = k * upper_radius(distribution, settings.weight_cutoff);
    const auto cell_count = static_cast<std::size_t>(std::ceil(x_max / step));
    if (cell_count > 50'000'000) throw std::invalid_argument("size parameter step too small");
    const double x_range = static_cast<double>(cell_count) * step;
    const integrand f(distribution, settings.refractive_index, k, mu);
    const std::size_t n = f.size();

    unsigned thread_count =
        settings.threads != 0 ? settings.threads : std::thread::hardware_concurrency();
    thread_count = std::max(1u, thread_count);

    // Pass 1: plain midpoint rule with 4 times the step, for the size of every component's
    // integral, which sets the tolerances of pass 2.
    const double coarse_step = 4.0 * step;
    const auto coarse_count = static_cast<std::size_t>(std::ceil(x_max / coarse_step));
    const std::size_t coarse_chunks = (coarse_count + chunk_radii - 1) / chunk_radii;
    std::vector<double> coarse_cost(coarse_chunks, 0.0);
    for (std::size_t i = 0; i < coarse_count; ++i)
        coarse_cost[i / chunk_radii] +=
            static_cast<double>(mie_term_count((static_cast<double>(i) + 0.5) * coarse_step) + 4);
    const auto coarse_task = [&](std::size_t c, std::vector<double>& sums) {
        sums.assign(n, 0.0);
        std::vector<double> value;
        const std::size_t end = std::min(coarse_count, (c + 1) * chunk_radii);
        for (std::size_t i = c * chunk_radii; i < end; ++i) {
            f.evaluate((static_cast<double>(i) + 0.5) * coarse_step, value);
            for (std::size_t j = 0; j < n; ++j) sums[j] += coarse_step * value[j];
        }
    };
    const std::vector<double> estimate =
        add_in_order(run_chunks(coarse_chunks, thread_count, coarse_cost, coarse_task,
                                settings.progress, 0.0, 0.2),
                     n);

    // Pass 2: adaptive cells. A component may err by relative_tolerance of its integral over
    // the whole range, spread uniformly in x.
    std::vector<double> tolerance_density(n);
    for (std::size_t j = 0; j < n; ++j)
        tolerance_density[j] = settings.relative_tolerance * std::abs(estimate[j]) / x_range;
    const adaptive_cell_integrator integrator{f, tolerance_density, settings.max_refinement_depth};
    const std::size_t chunk_count = (cell_count + chunk_radii - 1) / chunk_radii;
    std::vector<double> chunk_cost(chunk_count, 0.0);
    for (std::size_t i = 0; i < cell_count; ++i)
        chunk_cost[i / chunk_radii] +=
            static_cast<double>(mie_term_count((static_cast<double>(i) + 0.5) * step) + 4);
    std::vector<std::size_t> chunk_evaluations(chunk_count, 0);
    const auto fine_task = [&](std::size_t c, std::vector<double>& sums) {
        sums.assign(n, 0.0);
        std::vector<double> value;
        std::size_t evaluations = 0;
        const std::size_t end = std::min(cell_count, (c + 1) * chunk_radii);
        for (std::size_t i = c * chunk_radii; i < end; ++i) {
            const double x = (static_cast<double>(i) + 0.5) * step;
            f.evaluate(x, value);
            evaluations += 1 + integrator.integrate(x, step, value, 0, sums);
        }
        chunk_evaluations[c] = evaluations;
    };
    const std::vector<double> total = add_in_order(
        run_chunks(chunk_count, thread_count, chunk_cost, fine_task, settings.progress, 0.2, 0.8),
        n);
    if (settings.progress) settings.progress(1.0);
    const double* scalars = total.data() + mu.size();
    const double number = scalars[0], c_ext = scalars[1], c_sca = scalars[2], c_sca_g = scalars[3];
    if (!(c_sca > 0.0)) throw std::invalid_argument("the distribution scatters nothing");

    mean_phase_result result;
    result.table.theta_deg = angles;
    result.table.phase.resize(angles.size());
    const double norm = 1.0 / (2.0 * k * k * c_sca);
    for (std::size_t j = 0; j < angles.size(); ++j) result.table.phase[j] = total[j] * norm;
    result.table.finalize();
    result.integral_before_normalisation = result.table.integral();
    if (settings.normalize) result.table.normalize();

    result.asymmetry_g = c_sca_g / c_sca;
    result.mean_c_ext_um2 = c_ext / number;
    result.mean_c_sca_um2 = c_sca / number;
    result.single_scattering_albedo = c_sca / c_ext;
    result.number_integral = number;
    result.effective_radius_um = scalars[5] / scalars[4];
    result.r_min_um = 0.5 * step / k;
    result.r_max_um = (x_range - 0.5 * step) / k;
    result.cell_count = cell_count;
    result.evaluation_count = coarse_count;
    for (std::size_t e : chunk_evaluations) result.evaluation_count += e;
    result.size_parameter_step = step;
    return result;
}

}  // namespace cloudmath::reference
