// tools/reference/truths/lighting_diffusion.cpp: see lighting_diffusion.hpp.
#include "lighting_diffusion.hpp"

#include <cloudmath/multiple_scattering.hpp>

#include "lighting_report.hpp"
#include "strict_number.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace cloudmath::reference::lighting {

namespace L = cloudmath::diffusion_layout;

hg_mixture parse_hg_mixture(const std::string& spec) {
    auto numbers = [&](const std::string& list) {
        std::vector<double> out;
        std::stringstream ss(list);
        for (std::string cell; std::getline(ss, cell, ',');) {
            const std::optional<double> v = cloudmath::tools::parse_finite(cell);
            if (!v)
                throw std::invalid_argument("phase spec '" + spec + "': '" + cell +
                                            "' is not a number");
            out.push_back(*v);
        }
        return out;
    };
    if (spec == "isotropic") return {};
    if (spec.rfind("hg:", 0) == 0) {
        const std::vector<double> v = numbers(spec.substr(3));
        if (v.size() == 1) return {v[0], 0.0, 0.0};
    }
    if (spec.rfind("dual_hg:", 0) == 0) {
        const std::vector<double> v = numbers(spec.substr(8));
        if (v.size() == 3) return {v[0], v[1], v[2]};
    }
    throw std::invalid_argument("phase spec '" + spec +
                                "': the diffusion model needs isotropic, hg:G or dual_hg");
}

double hg_mixture::mean_cosine() const { return (1.0 - w) * g0 + w * g1; }

double hg_mixture::phase(double mu, double scale) const {
    return cloudmath::phase_hg_dual(mu, scale * g0, scale * g1, w);
}

double phase_spec_mean_cosine(const std::string& spec) { return parse_hg_mixture(spec).mean_cosine(); }

std::vector<double> diffusion_features(double tau_sun, double tau_behind, double tau_view,
                                       double mu, double g, double albedo, double& single) {
    // The terms of cloudmath::diffusion_scattering_with, one feature per fitted number.
    const cloudmath::detail::diffusion_sample<double> t =
        cloudmath::detail::diffusion_sample_terms(tau_sun, tau_behind, tau_view, mu, g, albedo);
    std::vector<double> f(diffusion_unknowns, 0.0);
    for (int ia = 0; ia < L::peak_a_count; ++ia)
        for (int ic = 0; ic < L::peak_c_count; ++ic)
            f[static_cast<std::size_t>(L::table_size + ia * L::peak_c_count + ic)] =
                cloudmath::phase_hg(t.mu, L::peak_c[ic] * g) * t.beams[ia];
    cloudmath::detail::diffusion_table_corners(t.u, [&](int index, double weight) {
        f[static_cast<std::size_t>(index)] += t.diffuse * weight;
    });
    single = cloudmath::phase_hg(t.mu, g) * t.direct;
    return f;
}

diffusion_evaluator::diffusion_evaluator(const reference_set& set, double panel)
    : phase_(parse_hg_mixture(set.phase_spec)), g_(phase_.mean_cosine()), albedo_(set.albedo) {
    begin_.push_back(0);
    for (const reference_row& r : set.rows) {
        const ray_quadrature q = row_quadrature(r, set.albedo, panel);
        mu_.push_back(q.mu);
        weight_.insert(weight_.end(), q.weight.begin(), q.weight.end());
        tau_light_.insert(tau_light_.end(), q.tau_light.begin(), q.tau_light.end());
        tau_behind_.insert(tau_behind_.end(), q.tau_behind.begin(), q.tau_behind.end());
        tau_view_.insert(tau_view_.end(), q.tau_view.begin(), q.tau_view.end());
        begin_.push_back(weight_.size());
    }
}

std::vector<double> diffusion_evaluator::radiance(const diffusion_model& m) const {
    std::vector<double> out(mu_.size(), 0.0);
    for (std::size_t row = 0; row < mu_.size(); ++row) {
        // The phase functions depend on the row only: evaluate them once per row.
        const double mu = mu_[row];
        const double p1 = phase_.phase(mu, 1.0);
        const double pc[L::peak_c_count] = {phase_.phase(mu, L::peak_c[0]), phase_.phase(mu, L::peak_c[1])};
        auto phase = [&](double, double scale) {
            return scale == 1.0 ? p1 : (scale == L::peak_c[0] ? pc[0] : pc[1]);
        };
        double sum = 0.0;
        for (std::size_t k = begin_[row]; k < begin_[row + 1]; ++k)
            sum += weight_[k] * cloudmath::diffusion_scattering_with(tau_light_[k], tau_behind_[k],
                                                                     tau_view_[k], mu, g_, albedo_, m,
                                                                     phase);
        out[row] = sum;
    }
    return out;
}

std::vector<std::vector<double>> diffusion_evaluator::row_features(std::vector<double>& single) const {
    std::vector<std::vector<double>> out(mu_.size(), std::vector<double>(diffusion_unknowns, 0.0));
    single.assign(mu_.size(), 0.0);
    for (std::size_t row = 0; row < mu_.size(); ++row)
        for (std::size_t k = begin_[row]; k < begin_[row + 1]; ++k) {
            double s = 0.0;
            const std::vector<double> f =
                diffusion_features(tau_light_[k], tau_behind_[k], tau_view_[k], mu_[row], g_, albedo_, s);
            for (std::size_t j = 0; j < diffusion_unknowns; ++j) out[row][j] += weight_[k] * f[j];
            single[row] += weight_[k] * s;
        }
    return out;
}

namespace {

// Solves A x = b (n x n, row-major) by Gaussian elimination with partial pivoting.
std::vector<double> solve_linear(std::vector<double> A, std::vector<double> b) {
    const std::size_t n = b.size();
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t p = c;
        for (std::size_t r = c + 1; r < n; ++r)
            if (std::abs(A[r * n + c]) > std::abs(A[p * n + c])) p = r;
        if (!(std::abs(A[p * n + c]) > 0.0))
            throw std::runtime_error("fit_diffusion_model: singular normal equations");
        for (std::size_t j = 0; j < n; ++j) std::swap(A[c * n + j], A[p * n + j]);
        std::swap(b[c], b[p]);
        for (std::size_t r = c + 1; r < n; ++r) {
            const double f = A[r * n + c] / A[c * n + c];
            for (std::size_t j = c; j < n; ++j) A[r * n + j] -= f * A[c * n + j];
            b[r] -= f * b[c];
        }
    }
    std::vector<double> x(n);
    for (std::size_t c = n; c-- > 0;) {
        double s = b[c];
        for (std::size_t j = c + 1; j < n; ++j) s -= A[c * n + j] * x[j];
        x[c] = s / A[c * n + c];
    }
    return x;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

std::string upper(std::string s) {
    for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

diffusion_fit_rows prepare_diffusion_fit(const reference_set& set, double panel) {
    const diffusion_evaluator ev(set, panel);
    std::vector<double> single;
    const std::vector<std::vector<double>> F = ev.row_features(single);
    const std::vector<double> mean = image_means(set);
    // measure()'s weights: each geometry class (sphere, slab) counts half.
    std::size_t sphere = 0, slab = 0;
    for (const reference_row& r : set.rows)
        if (r.radiance > 0.0) (r.is_sphere() ? sphere : slab) += 1;
    const double classes = (sphere > 0 ? 1.0 : 0.0) + (slab > 0 ? 1.0 : 0.0);
    diffusion_fit_rows p;
    for (std::size_t i = 0; i < set.rows.size(); ++i) {
        const reference_row& r = set.rows[i];
        const double w = r.radiance > 0.0
                             ? 1.0 / (static_cast<double>(r.is_sphere() ? sphere : slab) * classes)
                             : 0.0;
        std::vector<double> a(diffusion_unknowns);
        for (std::size_t j = 0; j < diffusion_unknowns; ++j) a[j] = F[i][j] / mean[i];
        p.features.push_back(std::move(a));
        p.target.push_back((r.radiance - single[i]) / mean[i]);
        p.weight.push_back(w);
    }
    return p;
}

diffusion_fit_result fit_diffusion_model(const std::vector<const diffusion_fit_rows*>& sets,
                                         const diffusion_fit_options& o) {
    if (sets.empty()) throw std::invalid_argument("fit_diffusion_model: no reference set");
    const std::size_t n = diffusion_unknowns;
    std::vector<double> AtA(n * n, 0.0), Atb(n, 0.0);
    for (const diffusion_fit_rows* p : sets)
        for (std::size_t i = 0; i < p->features.size(); ++i) {
            const std::vector<double>& a = p->features[i];
            const double w = p->weight[i];
            for (std::size_t j = 0; j < n; ++j) {
                Atb[j] += w * a[j] * p->target[i];
                for (std::size_t k = 0; k < n; ++k) AtA[j * n + k] += w * a[j] * a[k];
            }
        }
    double scale = 0.0;
    for (std::size_t j = 0; j < n; ++j) scale += AtA[j * n + j];
    scale /= static_cast<double>(n);
    // Second differences of the table along every axis with 3 or more nodes.
    const int dims[4] = {L::size_x, L::size_y, L::size_mu, L::size_d};
    for (int ix = 0; ix < L::size_x; ++ix)
        for (int iy = 0; iy < L::size_y; ++iy)
            for (int im = 0; im < L::size_mu; ++im)
                for (int id = 0; id < L::size_d; ++id) {
                    const int at[4] = {ix, iy, im, id};
                    for (int axis = 0; axis < 4; ++axis) {
                        if (at[axis] + 2 >= dims[axis]) continue;
                        std::size_t v[3];
                        for (int step = 0; step < 3; ++step) {
                            int q[4] = {ix, iy, im, id};
                            q[axis] += step;
                            v[step] = static_cast<std::size_t>(L::table_index(q[0], q[1], q[2], q[3]));
                        }
                        const double c[3] = {1.0, -2.0, 1.0};
                        for (int a = 0; a < 3; ++a)
                            for (int b = 0; b < 3; ++b)
                                AtA[v[a] * n + v[b]] += o.smoothing * scale * c[a] * c[b];
                    }
                }
    // Ridge: the table toward 1 (plain diffusion), the peak weights toward 0.
    for (std::size_t j = 0; j < n; ++j) {
        AtA[j * n + j] += o.ridge * scale;
        if (j < static_cast<std::size_t>(L::table_size)) Atb[j] += o.ridge * scale;
    }
    diffusion_fit_result r;
    r.coefficients = solve_linear(AtA, Atb);
    double sum = 0.0;
    for (const diffusion_fit_rows* p : sets) {
        double s2 = 0.0, wsum = 0.0;
        for (std::size_t i = 0; i < p->features.size(); ++i) {
            double e = -p->target[i];
            for (std::size_t j = 0; j < n; ++j) e += p->features[i][j] * r.coefficients[j];
            s2 += p->weight[i] * e * e;
            wsum += p->weight[i];
        }
        sum += wsum > 0.0 ? std::sqrt(s2 / wsum) : 0.0;
    }
    r.residual = sum / static_cast<double>(sets.size());
    r.model.name = "fitted";
    for (std::size_t j = 0; j < static_cast<std::size_t>(L::table_size); ++j)
        r.model.table[j] = static_cast<float>(r.coefficients[j]);
    for (std::size_t j = 0; j < static_cast<std::size_t>(L::peak_size); ++j)
        r.model.peak[j] = static_cast<float>(r.coefficients[static_cast<std::size_t>(L::table_size) + j]);
    return r;
}

diffusion_fit_result fit_diffusion_model(const std::vector<reference_set>& sets,
                                         const diffusion_fit_options& o) {
    std::vector<diffusion_fit_rows> rows;
    for (const reference_set& set : sets) rows.push_back(prepare_diffusion_fit(set, o.panel));
    std::vector<const diffusion_fit_rows*> pointers;
    for (const diffusion_fit_rows& r : rows) pointers.push_back(&r);
    return fit_diffusion_model(pointers, o);
}

diffusion_model physical_diffusion_model() {
    diffusion_model m{};
    m.name = "physical";
    for (float& v : m.table) v = 1.0f;
    // e^(-x) (a = 1) with c = 4/5: the similarity-scaled beam minus the unscattered one.
    m.peak[1 * L::peak_c_count + 1] = 1.0f;
    return m;
}

namespace {

std::string base_name(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string fixed4(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f", v);
    return buf;
}

}  // namespace

std::string diffusion_cross_validation(const std::vector<std::string>& train_paths) {
    if (train_paths.size() < 2)
        throw std::invalid_argument("diffusion_cross_validation: needs two training sets or more");
    std::vector<reference_set> sets;
    for (const std::string& p : train_paths) sets.push_back(read_reference(p));
    std::vector<diffusion_evaluator> evs;
    for (const reference_set& s : sets) evs.emplace_back(s);
    // The fit's rows do not depend on the options: build them once for every fold.
    std::vector<diffusion_fit_rows> rows;
    for (const reference_set& s : sets) rows.push_back(prepare_diffusion_fit(s, diffusion_fit_options{}.panel));
    std::ostringstream out;
    out << "leave-one-set-out rms (fit on the other sets, measured on the one left out):\n"
        << "smoothing   ridge  ";
    for (const std::string& p : train_paths) out << ' ' << base_name(p);
    out << "  mean\n";
    for (double smoothing : {0.01, 0.1, 1.0, 10.0})
        for (double ridge : {1e-6, 1e-5, 1e-4, 1e-3}) {
            diffusion_fit_options o;
            o.smoothing = smoothing;
            o.ridge = ridge;
            char buf[64];
            std::snprintf(buf, sizeof buf, "%9g %7g ", smoothing, ridge);
            out << buf;
            double sum = 0.0;
            for (std::size_t k = 0; k < sets.size(); ++k) {
                std::vector<const diffusion_fit_rows*> others;
                for (std::size_t j = 0; j < sets.size(); ++j)
                    if (j != k) others.push_back(&rows[j]);
                const diffusion_fit_result fit = fit_diffusion_model(others, o);
                const double rms = measure(sets[k], evs[k].radiance(fit.model), select_all()).rms;
                sum += rms;
                std::snprintf(buf, sizeof buf, " %6.1f%%", 100 * rms);
                out << buf;
            }
            std::snprintf(buf, sizeof buf, "  %6.1f%%\n", 100 * sum / static_cast<double>(sets.size()));
            out << buf;
        }
    return out.str();
}

std::vector<std::string> diffusion_training_paths(const std::string& dir) {
    return {dir + "/lighting_reference.csv", dir + "/lighting_train_g0.8.csv",
            dir + "/lighting_train_g0.93.csv"};
}

std::vector<std::string> diffusion_holdout_paths(const std::string& dir) {
    return {dir + "/lighting_holdout_g0.75.csv", dir + "/lighting_holdout_g0.85.csv",
            dir + "/lighting_holdout_g0.9.csv", dir + "/lighting_holdout_g0.85_albedo0.99.csv",
            dir + "/lighting_holdout_renderer_phase.csv"};
}

std::string diffusion_clouds_path(const std::string& dir) { return dir + "/diffusion_clouds.txt"; }

diffusion_model read_clouds_model(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read the whole-cloud fit " + path + " (bash scripts/truth.sh --fit)");
    diffusion_model m{};
    m.name = "clouds";
    std::vector<bool> seen(diffusion_unknowns, false);
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#' || line == "kind,index,value") continue;
        const auto fail = [&] { throw std::runtime_error(path + ":" + std::to_string(line_no) + ": malformed row '" + line + "'"); };
        const std::size_t c1 = line.find(','), c2 = line.find(',', c1 == std::string::npos ? c1 : c1 + 1);
        if (c1 == std::string::npos || c2 == std::string::npos) fail();
        const std::string kind = line.substr(0, c1);
        const std::optional<std::uint64_t> index = cloudmath::tools::parse_count(line.substr(c1 + 1, c2 - c1 - 1));
        const std::optional<double> value = cloudmath::tools::parse_finite(line.substr(c2 + 1));
        if (!index || !value || (kind != "table" && kind != "peak")) fail();
        const std::size_t limit = kind == "table" ? std::size_t(L::table_size) : std::size_t(L::peak_size);
        if (*index >= limit) fail();
        const std::size_t slot = (kind == "table" ? 0 : std::size_t(L::table_size)) + std::size_t(*index);
        if (seen[slot]) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": " + kind + " " + std::to_string(*index) + " repeated");
        seen[slot] = true;
        (kind == "table" ? m.table[*index] : m.peak[*index]) = static_cast<float>(*value);
    }
    if (std::find(seen.begin(), seen.end(), false) != seen.end())
        throw std::runtime_error(path + ": not every table entry and peak weight is given");
    return m;
}

diffusion_run run_diffusion_fit(const std::vector<std::string>& train_paths,
                                const std::vector<std::string>& holdout_paths,
                                const diffusion_fit_options& o, const std::string& clouds_path) {
    std::vector<reference_set> train, holdout;
    for (const std::string& p : train_paths) train.push_back(read_reference(p));
    for (const std::string& p : holdout_paths) holdout.push_back(read_reference(p));
    diffusion_fit_result fit = fit_diffusion_model(train, o);
    diffusion_model m = fit.model;
    diffusion_model physical = physical_diffusion_model();
    m.tau_min = m.g_min = 1e30f;
    m.tau_max = m.g_max = -1e30f;
    for (const reference_set& set : train) {
        const float g = static_cast<float>(phase_spec_mean_cosine(set.phase_spec));
        m.g_min = std::min(m.g_min, g);
        m.g_max = std::max(m.g_max, g);
        for (const reference_row& r : set.rows) {
            m.tau_min = std::min(m.tau_min, static_cast<float>(r.tau));
            m.tau_max = std::max(m.tau_max, static_cast<float>(r.tau));
        }
    }
    physical.tau_min = m.tau_min;
    physical.tau_max = m.tau_max;
    physical.g_min = m.g_min;
    physical.g_max = m.g_max;
    const bool with_clouds = !clouds_path.empty();
    diffusion_model clouds{};
    if (with_clouds) {
        clouds = read_clouds_model(clouds_path);
        clouds.tau_min = m.tau_min;
        clouds.tau_max = m.tau_max;
        clouds.g_min = m.g_min;
        clouds.g_max = m.g_max;
    }

    std::ostringstream out;
    out << "diffusion model fitted on " << train.size() << " set(s) (smoothing " << o.smoothing
        << ", ridge " << o.ridge << "): rms of the linear fit "
        << fixed4(fit.residual) << "\n"
        << "rms / bias / max of (L - L_MC) / image mean; the library function with float tables\n";
    auto report = [&](const reference_set& set, const std::string& label, bool subsets) {
        const diffusion_evaluator ev(set);
        const evaluator octaves(set);
        out << label << " (g = " << ev.g() << ")\n";
        auto line = [&](const std::string& name, const std::vector<double>& L, bool all) {
            for (const row_subset& sub : report_subsets()) {
                if (!all && sub.id != "all") continue;
                const error_summary e = measure(set, L, sub.select);
                if (e.rows == 0) continue;
                char buf[160];
                std::snprintf(buf, sizeof buf, "  %-24s %-44s %6.1f%% %+7.1f%% %7.1f%%\n", name.c_str(),
                              sub.label.c_str(), 100 * e.rms, 100 * e.bias, 100 * e.max);
                out << buf;
            }
        };
        const std::vector<double> Lf = ev.radiance(m), Lp = ev.radiance(physical);
        line("diffusion fitted", Lf, subsets);
        line("diffusion physical", Lp, false);
        error_summary ec{};
        if (with_clouds) {
            const std::vector<double> Lc = ev.radiance(clouds);
            line("diffusion clouds", Lc, false);
            ec = measure(set, Lc, select_all());
        }
        for (const cloudmath::multiple_scattering_preset& p : cloudmath::ms_preset::all) {
            const model_spec spec{attenuation::beer, ev.g(), p.a, p.b, p.c, p.octaves};
            line(std::string("ms_preset::") + p.name, octaves.radiance(spec), false);
        }
        return std::make_tuple(measure(set, Lf, select_all()), measure(set, Lp, select_all()), ec);
    };
    for (std::size_t i = 0; i < train.size(); ++i) {
        const auto e = report(train[i], "fitted on " + base_name(train_paths[i]), i == 0);
        if (i > 0) continue;
        m.rms_error = static_cast<float>(std::get<0>(e).rms);
        m.max_error = static_cast<float>(std::get<0>(e).max);
        physical.rms_error = static_cast<float>(std::get<1>(e).rms);
        physical.max_error = static_cast<float>(std::get<1>(e).max);
        clouds.rms_error = static_cast<float>(std::get<2>(e).rms);
        clouds.max_error = static_cast<float>(std::get<2>(e).max);
    }
    for (std::size_t i = 0; i < holdout.size(); ++i) {
        const auto e = report(holdout[i], "held out " + base_name(holdout_paths[i]), true);
        m.holdout_rms_error = std::max(m.holdout_rms_error, static_cast<float>(std::get<0>(e).rms));
        physical.holdout_rms_error = std::max(physical.holdout_rms_error, static_cast<float>(std::get<1>(e).rms));
        clouds.holdout_rms_error = std::max(clouds.holdout_rms_error, static_cast<float>(std::get<2>(e).rms));
    }

    diffusion_run run;
    run.models = {m, physical};
    if (with_clouds) run.models.push_back(clouds);
    run.report = out.str();
    std::string names;
    for (const std::string& p : train_paths) names += (names.empty() ? "" : ", ") + base_name(p);
    run.provenance = "cloudmath_lighting_error fit-diffusion (scripts/reference.sh)\n// fitted on " + names;
    names.clear();
    for (const std::string& p : holdout_paths) names += (names.empty() ? "" : ", ") + base_name(p);
    if (!names.empty()) run.provenance += "\n// held out: " + names;
    char opts[96];
    std::snprintf(opts, sizeof opts, "\n// options: smoothing %g, ridge %g", o.smoothing, o.ridge);
    run.provenance += opts;
    if (with_clouds)
        run.provenance += "\n// clouds: " + base_name(clouds_path) + " (cloudmath_volume_truth fit-clouds, scripts/truth.sh --fit)";
    return run;
}

namespace {

// "v0, v1, ..." with a line break every 6 numbers; `suffix` after each ("f" in C++).
std::string list_of(const float* v, int n, const char* indent, const char* suffix) {
    std::string s;
    for (int i = 0; i < n; ++i)
        s += (i % 6 == 0 ? std::string("\n") + indent : std::string(" ")) +
             num(static_cast<double>(v[i])) + suffix + (i + 1 < n ? "," : "");
    return s;
}

}  // namespace

std::string diffusion_models_cpp(const std::vector<diffusion_model>& models,
                                 const std::string& provenance, std::size_t in_all) {
    std::ostringstream o;
    o << "// cloudmath/diffusion_lighting_models.hpp: the fitted models of diffusion_lighting.hpp.\n"
      << "// Generated by " << provenance << "; do not edit.\n"
      << "#ifndef CLOUDMATH_DIFFUSION_LIGHTING_MODELS_HPP\n#define CLOUDMATH_DIFFUSION_LIGHTING_MODELS_HPP\n\n"
      << "#include \"diffusion_lighting.hpp\"\n\nnamespace cloudmath::diffusion_models {\n\n";
    auto f = [](double v) { return num(v) + "f"; };
    for (const diffusion_model& m : models) {
        o << "inline constexpr diffusion_model " << m.name << "{\n    \"" << m.name << "\",\n    {"
          << list_of(m.table, L::table_size, "     ", "f") << "},\n    {"
          << list_of(m.peak, L::peak_size, "     ", "f") << "},\n    " << f(m.tau_min) << ", "
          << f(m.tau_max) << ", " << f(m.g_min) << ", " << f(m.g_max) << ", " << f(m.rms_error)
          << ", " << f(m.max_error) << ", " << f(m.holdout_rms_error) << "};\n\n";
    }
    const std::size_t listed = std::min(in_all, models.size());
    o << "// Every model of homogeneous media, the default (most accurate) first"
      << (listed < models.size() ? " (clouds, fitted to whole-cloud images, is not one)" : "")
      << ".\ninline constexpr diffusion_model all[] = {";
    for (std::size_t i = 0; i < listed; ++i) o << models[i].name << (i + 1 < listed ? ", " : "");
    o << "};\n\n}  // namespace cloudmath::diffusion_models\n\n#endif  // CLOUDMATH_DIFFUSION_LIGHTING_MODELS_HPP\n";
    return o.str();
}

std::string diffusion_models_glsl(const std::vector<diffusion_model>& models,
                                  const std::string& provenance) {
    std::ostringstream o;
    o << "// cloudmath/glsl/diffusion_lighting_models.glsl: the table layout, CmDiffusionModel (the C++\n"
      << "// diffusion_model without its name) and the fitted models of diffusion_lighting.glsl.\n"
      << "// Generated by " << provenance << ";\n// do not edit.\n"
      << "#ifndef CM_DIFFUSION_LIGHTING_MODELS_GLSL\n#define CM_DIFFUSION_LIGHTING_MODELS_GLSL\n\n"
      << "#include \"core.glsl\"\n\n"
      << "// diffusion_layout of the C++ header.\n"
      << "#define CM_DIFFUSION_SIZE_X " << L::size_x << "\n#define CM_DIFFUSION_SIZE_Y " << L::size_y
      << "\n#define CM_DIFFUSION_SIZE_MU " << L::size_mu << "\n#define CM_DIFFUSION_SIZE_D " << L::size_d
      << "\n#define CM_DIFFUSION_TABLE_SIZE " << L::table_size << "\n#define CM_DIFFUSION_PEAK_SIZE "
      << L::peak_size << "\n#define CM_DIFFUSION_EXTRAPOLATION " << num(L::extrapolation) << "\n\n"
      << "struct CmDiffusionModel {\n    float table[CM_DIFFUSION_TABLE_SIZE];\n"
      << "    float peak[CM_DIFFUSION_PEAK_SIZE];\n    float tau_min;\n    float tau_max;\n"
      << "    float g_min;\n    float g_max;\n    float rms_error;\n    float max_error;\n"
      << "    float holdout_rms_error;\n};\n\n";
    for (const diffusion_model& m : models) {
        o << "const CmDiffusionModel CM_DIFFUSION_MODEL_" << upper(m.name) << " = CmDiffusionModel(\n    float["
          << L::table_size << "](" << list_of(m.table, L::table_size, "        ", "") << "),\n    float[" << L::peak_size
          << "](" << list_of(m.peak, L::peak_size, "        ", "") << "),\n    " << num(m.tau_min) << ", " << num(m.tau_max)
          << ", " << num(m.g_min) << ", " << num(m.g_max) << ", " << num(m.rms_error) << ", "
          << num(m.max_error) << ", " << num(m.holdout_rms_error) << ");\n";
    }
    o << "\n#endif  // CM_DIFFUSION_LIGHTING_MODELS_GLSL\n";
    return o.str();
}

}  // namespace cloudmath::reference::lighting
