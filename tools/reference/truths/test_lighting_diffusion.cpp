// Tests of the diffusion model's fitting tool (lighting_diffusion.hpp) and of the held-out
// split: the quadrature's new inputs against closed forms, the fit's features against the
// library function, the fit recovering a model from its own radiances, a held-out split that
// shares nothing with the fitted one, and the generated model headers reproduced from the
// stored Monte Carlo data (so the documented errors are what the data gives).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "lighting_diffusion.hpp"
#include "lighting_error.hpp"
#include "lighting_models.hpp"

namespace lm = cloudmath::reference::lighting;

TEST_CASE("quadrature inputs: tau_behind and tau_view against closed forms") {
    // Slab, looking straight down, sun at mu0: a node at optical path t from the top has
    // t / mu0 toward the sun and (tau - t) / mu0 behind it.
    const double tau = 3.0, mu0 = 0.5;
    const lm::ray_quadrature s = lm::slab_quadrature(tau, mu0, 1.0, {0.0, 0.0, -1.0});
    REQUIRE(s.weight.size() == s.tau_behind.size());
    REQUIRE(s.weight.size() == s.tau_view.size());
    for (std::size_t k = 0; k < s.weight.size(); ++k) {
        CHECK(s.tau_light[k] == doctest::Approx(s.tau_view[k] / mu0).epsilon(1e-12));
        CHECK(s.tau_light[k] + s.tau_behind[k] == doctest::Approx(tau / mu0).epsilon(1e-12));
    }
    // Sphere, sun along +z, a ray along the x axis through the centre: at x the chord along
    // the sun is 2 sqrt(1 - x^2), split evenly between front and back.
    const double tau_d = 4.0, sigma = tau_d / 2.0;
    const lm::ray_quadrature q = lm::sphere_quadrature(tau_d, 1.0, {0.0, 0.0, 1.0},
                                                       {-2.0, 0.0, 0.0}, {1.0, 0.0, 0.0});
    REQUIRE(!q.weight.empty());
    for (std::size_t k = 0; k < q.weight.size(); ++k) {
        const double x = -1.0 + q.tau_view[k] / sigma;
        const double half = sigma * std::sqrt(std::max(0.0, 1.0 - x * x));
        CHECK(q.tau_light[k] == doctest::Approx(half).epsilon(1e-9).scale(1e-9));
        CHECK(q.tau_behind[k] == doctest::Approx(half).epsilon(1e-9).scale(1e-9));
    }
}

namespace {
// A small reference set (sphere and slab rays, g = 0.8) whose radiances are those of model m.
lm::reference_set synthetic_set(const cloudmath::diffusion_model& m) {
    lm::reference_set set;
    set.phase_spec = "hg:0.8";
    set.albedo = 1.0;
    for (double tau : {1.0, 3.0, 8.0, 20.0, 60.0})
        for (double mu0 : {1.0, 0.6, 0.25}) {
            for (double vx : {-0.6, 0.0, 0.6})
                for (double vz : {-1.0, 1.0}) {
                    lm::reference_row r;
                    r.geometry = vz < 0 ? "slab_reflected" : "slab_transmitted";
                    r.tau = tau;
                    r.sun_deg = std::acos(mu0) * 180.0 / 3.14159265358979;
                    r.sun = lm::slab_sun_direction(mu0);
                    r.dir = glm::normalize(glm::dvec3(vx, 0.2, vz));
                    set.rows.push_back(r);
                }
            for (double u : {-0.6, 0.0, 0.6}) {
                lm::reference_row r;
                r.geometry = "sphere";
                r.tau = tau;
                r.sun_deg = std::acos(mu0) * 180.0 / 3.14159265358979 + 40.0;
                r.sun = {0.0, 0.0, 1.0};
                const double a = r.sun_deg * 3.14159265358979 / 180.0;
                r.dir = {std::sin(a), 0.0, std::cos(a)};
                r.origin = -2.0 * r.dir + glm::dvec3(0.0, u, 0.0);
                set.rows.push_back(r);
            }
        }
    const lm::diffusion_evaluator ev(set);
    const std::vector<double> L = ev.radiance(m);
    for (std::size_t i = 0; i < L.size(); ++i) set.rows[i].radiance = L[i];
    return set;
}

cloudmath::diffusion_model smooth_positive_model() {
    cloudmath::diffusion_model m{};
    m.name = "test";
    for (int i = 0; i < cloudmath::diffusion_layout::table_size; ++i)
        m.table[i] = 0.4f + 0.05f * static_cast<float>(i % 7);
    const float peak[cloudmath::diffusion_layout::peak_size] = {0.1f, 0.2f, 0.3f, 0.05f, 0.0f, 0.15f};
    std::copy(std::begin(peak), std::end(peak), std::begin(m.peak));
    return m;
}
}  // namespace

TEST_CASE("the fit's features give the library function's radiance") {
    const cloudmath::diffusion_model m = smooth_positive_model();
    const lm::reference_set set = synthetic_set(m);
    const lm::diffusion_evaluator ev(set);
    CHECK(ev.g() == 0.8);
    std::vector<double> single;
    const std::vector<std::vector<double>> F = ev.row_features(single);
    const std::vector<double> L = ev.radiance(m);
    for (std::size_t i = 0; i < L.size(); ++i) {
        double sum = single[i];
        for (std::size_t j = 0; j < lm::diffusion_unknowns; ++j) {
            const double c = j < static_cast<std::size_t>(cloudmath::diffusion_layout::table_size)
                                 ? double(m.table[j])
                                 : double(m.peak[j - static_cast<std::size_t>(cloudmath::diffusion_layout::table_size)]);
            sum += c * F[i][j];
        }
        CHECK(sum == doctest::Approx(L[i]).epsilon(1e-11));
        CHECK(L[i] > 0.0);
    }
}

TEST_CASE("fit_diffusion_model recovers a model from its own radiances") {
    const cloudmath::diffusion_model m = smooth_positive_model();
    const lm::reference_set set = synthetic_set(m);
    lm::diffusion_fit_options o;
    o.smoothing = 1e-12;
    o.ridge = 1e-12;
    const lm::diffusion_fit_result fit = lm::fit_diffusion_model({set}, o);
    CHECK(fit.residual < 1e-5);
    const lm::diffusion_evaluator ev(set);
    const lm::error_summary e = lm::measure(set, ev.radiance(fit.model), lm::select_all());
    CHECK(e.rms < 1e-5);
    CHECK_THROWS_AS((void)lm::fit_diffusion_model(std::vector<lm::reference_set>{}, o), std::invalid_argument);
    CHECK_THROWS_AS((void)lm::fit_diffusion_model(std::vector<const lm::diffusion_fit_rows*>{}, o),
                    std::invalid_argument);
    // From prepared rows, the same fit.
    const lm::diffusion_fit_rows rows = lm::prepare_diffusion_fit(set, o.panel);
    const lm::diffusion_fit_result again = lm::fit_diffusion_model({&rows}, o);
    CHECK(again.coefficients == fit.coefficients);
}

TEST_CASE("phase_spec_mean_cosine") {
    CHECK(lm::phase_spec_mean_cosine("hg:0.85") == 0.85);
    CHECK(lm::phase_spec_mean_cosine("isotropic") == 0.0);
    CHECK(lm::phase_spec_mean_cosine("dual_hg:0.8,-0.2,0.25") == doctest::Approx(0.55));
    CHECK_THROWS_AS((void)lm::phase_spec_mean_cosine("cs:0.8"), std::invalid_argument);
    CHECK_THROWS_AS((void)lm::phase_spec_mean_cosine("hg:x"), std::invalid_argument);
    // The phase callback: HG, the dual lobe with both eccentricities scaled, isotropic.
    constexpr double pi = 3.14159265358979323846;
    const auto hg = [&](double mu, double g) { return (1 - g * g) / (4 * pi * std::pow(1 + g * g - 2 * g * mu, 1.5)); };
    CHECK(lm::parse_hg_mixture("hg:0.85").phase(0.3, 0.5) == doctest::Approx(hg(0.3, 0.425)).epsilon(1e-12));
    CHECK(lm::parse_hg_mixture("dual_hg:0.8,-0.2,0.25").phase(-0.4, 0.5) ==
          doctest::Approx(0.75 * hg(-0.4, 0.4) + 0.25 * hg(-0.4, -0.1)).epsilon(1e-12));
    CHECK(lm::parse_hg_mixture("isotropic").phase(0.9, 0.8) == doctest::Approx(1 / (4 * pi)).epsilon(1e-12));
}

TEST_CASE("the held-out split shares no thickness, angle or view with the fitted split") {
    const lm::reference_options fitted, held = lm::holdout_reference_options();
    for (double t : held.taus)
        CHECK(std::find(fitted.taus.begin(), fitted.taus.end(), t) == fitted.taus.end());
    for (double a : held.sphere_view_angles_deg)
        CHECK(std::find(fitted.sphere_view_angles_deg.begin(), fitted.sphere_view_angles_deg.end(), a) ==
              fitted.sphere_view_angles_deg.end());
    for (double z : held.slab_sun_zenith_deg)
        CHECK(std::find(fitted.slab_sun_zenith_deg.begin(), fitted.slab_sun_zenith_deg.end(), z) ==
              fitted.slab_sun_zenith_deg.end());
    std::set<std::pair<bool, std::pair<double, double>>> views;
    for (const auto& v : cloudmath::reference::mc::parse_slab_views(fitted.slab_views))
        views.insert({v.transmitted, {v.mu, v.phi_deg}});
    for (const auto& v : cloudmath::reference::mc::parse_slab_views(held.slab_views))
        CHECK(views.count({v.transmitted, {v.mu, v.phi_deg}}) == 0);
    CHECK(held.seed != fitted.seed);
    // The stored sets: the held-out ones have none of the training sets' g but 0.85.
    std::set<std::string> train_g;
    for (const std::string& p : lm::diffusion_training_paths(CLOUDMATH_SOURCE_DIR "/docs/data"))
        train_g.insert(lm::read_reference(p).phase_spec);
    for (const std::string& p : lm::diffusion_holdout_paths(CLOUDMATH_SOURCE_DIR "/docs/data")) {
        const std::string spec = lm::read_reference(p).phase_spec;
        CHECK((spec == "hg:0.85" || train_g.count(spec) == 0));
    }
}

namespace {
std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE_MESSAGE(in.good(), "cannot read " << path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("the generated model headers are reproduced from the stored Monte Carlo data") {
    const std::string dir = CLOUDMATH_SOURCE_DIR "/docs/data";
    const lm::diffusion_run run = lm::run_diffusion_fit(lm::diffusion_training_paths(dir),
                                                        lm::diffusion_holdout_paths(dir), {},
                                                        lm::diffusion_clouds_path(dir));
    MESSAGE(run.report);
    CHECK(lm::diffusion_models_cpp(run.models, run.provenance, run.homogeneous) ==
          read_file(CLOUDMATH_SOURCE_DIR "/include/cloudmath/diffusion_lighting_models.hpp"));
    CHECK(lm::diffusion_models_glsl(run.models, run.provenance) ==
          read_file(CLOUDMATH_SOURCE_DIR "/include/cloudmath/glsl/diffusion_lighting_models.glsl"));
    // What the library ships equals what was measured.
    CHECK(std::string(cloudmath::diffusion_models::fitted.name) == "fitted");
    CHECK(cloudmath::diffusion_models::fitted.rms_error == run.models[0].rms_error);
    CHECK(cloudmath::diffusion_models::fitted.holdout_rms_error == run.models[0].holdout_rms_error);
}

TEST_CASE("the whole-cloud fit's file: the shipped clouds model, and malformed files are refused") {
    const std::string dir = CLOUDMATH_SOURCE_DIR "/docs/data";
    const cloudmath::diffusion_model m = lm::read_clouds_model(lm::diffusion_clouds_path(dir));
    CHECK(std::string(m.name) == "clouds");
    for (int i = 0; i < cloudmath::diffusion_layout::table_size; ++i) CHECK(m.table[i] == cloudmath::diffusion_models::clouds.table[i]);
    for (int i = 0; i < cloudmath::diffusion_layout::peak_size; ++i) CHECK(m.peak[i] == cloudmath::diffusion_models::clouds.peak[i]);
    // Malformed: each must throw, naming the file.
    std::string good;
    for (int i = 0; i < cloudmath::diffusion_layout::table_size; ++i) good += "table," + std::to_string(i) + ",1\n";
    for (int i = 0; i < cloudmath::diffusion_layout::peak_size; ++i) good += "peak," + std::to_string(i) + ",0\n";
    const std::string path = "diffusion_clouds_test.txt";
    const auto write = [&](const std::string& text) {
        std::ofstream out(path, std::ios::binary);
        out << "# test\nkind,index,value\n" << text;
    };
    write(good);
    CHECK(lm::read_clouds_model(path).table[7] == 1.0f);
    for (const std::string& bad : {good + "table,3,2\n", good + "table,135,1\n", good + "peak,6,1\n", good + "beam,0,1\n",
                                   good + "table,1,nan\n", good + "table,1,0.5x\n", good + "table,-1,1\n", good + "table,1\n",
                                   good.substr(good.find('\n') + 1)}) {
        write(bad);
        std::string message;
        try {
            (void)lm::read_clouds_model(path);
        } catch (const std::runtime_error& e) {
            message = e.what();
        }
        CAPTURE(bad.substr(bad.size() - 16));
        CHECK(message.find(path) != std::string::npos);
    }
    CHECK_THROWS_AS((void)lm::read_clouds_model("no_such_dir/none.txt"), std::runtime_error);
    std::remove(path.c_str());
}
