// Validation of the heterogeneous-media path tracer (volume_tracer.hpp): on homogeneous
// spheres and slabs it must reproduce montecarlo.hpp's exact-free-path tracer within 3
// combined standard errors, also with a majorant well above the extinction (delta tracking
// is unbiased for any majorant >= sigma_t); results must not depend on the thread count;
// and the cloud medium's majorants must bound the renderer's density everywhere.
#include "cloud_medium.hpp"
#include "montecarlo_detail.hpp"
#include "volume_tracer.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace mc = cloudmath::reference::mc;
namespace vt = cloudmath::reference::volume;
namespace cr = cloud_renderer;

namespace {

// |a - b| in units of the combined standard error.
double combined_se(const mc::estimate& a, const mc::estimate& b) {
    return std::abs(a.mean - b.mean) / std::sqrt(a.std_error * a.std_error + b.std_error * b.std_error);
}

vt::lighting sun_only(const mc::vec3& sun) {
    vt::lighting l;
    l.sun_direction = sun;
    l.sun_irradiance = {1.0, 1.0, 1.0};
    return l;
}

mc::run_options options(unsigned threads = 2) {
    mc::run_options o;
    o.seed = 11;
    o.threads = threads;
    return o;
}

// Checks every ray's red channel (grey medium, white sun: r = g = b) against mc.
void check_against(const std::vector<vt::rgb_estimate>& got, const std::vector<mc::estimate>& want,
                   const char* what) {
    REQUIRE(got.size() == want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        const double z = combined_se(got[i].r, want[i]);
        MESSAGE(std::string(what) << " ray " << i << ": tracer " << got[i].r.mean << " +- " << got[i].r.std_error << ", montecarlo "
                     << want[i].mean << " +- " << want[i].std_error << ": " << z << " SE");
        CHECK(z < 3.0);
        CHECK(got[i].g.mean == got[i].r.mean);
    }
}

// The sphere of mc::sphere_radiance (radius 1, optical diameter 4) seen along a line of 3
// rays at 70 degrees from the sun.
void sphere_case(double albedo, double majorant_scale) {
    const mc::phase_model phase = mc::make_phase("hg:0.85");
    const mc::sphere_camera cam = mc::make_sphere_camera_line(70.0, 3);
    mc::sphere_parameters sp;
    sp.optical_diameter = 4.0;
    sp.albedo = albedo;
    sp.sun_direction = cam.sun_direction;
    const auto want = mc::sphere_radiance(sp, phase, cam.rays, 100000, options());

    const vt::homogeneous_sphere sphere(2.0, majorant_scale);
    const vt::lighting light = sun_only(cam.sun_direction);
    const vt::path_tracer tracer(sphere, phase, albedo, light);
    std::vector<vt::camera_ray> rays;
    for (const mc::ray& r : cam.rays) {
        vt::camera_ray c;
        c.origin = r.origin;
        c.direction = r.direction;
        rays.push_back(c);
    }
    check_against(vt::estimate_radiance(tracer, rays, 100000, options()), want, "sphere");
}

}  // namespace

TEST_CASE("sphere: the volume tracer reproduces mc::sphere_radiance (albedo 1 and 0.99)") {
    sphere_case(1.0, 1.0);
    sphere_case(0.99, 1.0);
}

TEST_CASE("sphere: a majorant 3x the extinction gives the same radiance (delta tracking)") {
    sphere_case(0.99, 3.0);
}

TEST_CASE("slab: the volume tracer reproduces mc::slab_radiance, also with a majorant 2.5x") {
    const mc::phase_model phase = mc::make_phase("hg:0.85");
    for (double albedo : {1.0, 0.99}) {
        mc::slab_parameters sp;
        sp.tau = 2.0;
        sp.mu0 = 0.6;
        sp.albedo = albedo;
        const std::vector<mc::slab_view> views = mc::parse_slab_views("r:0.8,180;r:0.5,0;t:0.7,0;t:0.9,90");
        const auto want = mc::slab_radiance(sp, phase, views, 100000, options());
        const mc::vec3 sun{std::sqrt((1.0 - sp.mu0) * (1.0 + sp.mu0)), 0.0, sp.mu0};
        const vt::lighting light = sun_only(sun);
        std::vector<vt::camera_ray> rays;
        for (const mc::slab_view& v : views) {
            // montecarlo.hpp's view direction (away from the camera) and start on the surface.
            const double s = std::sqrt((1.0 - v.mu) * (1.0 + v.mu)), phi = v.phi_deg * (mc::detail::pi / 180.0);
            vt::camera_ray c;
            c.origin = {0.0, 0.0, v.transmitted ? 0.0 : sp.tau};
            c.direction = {s * std::cos(phi), s * std::sin(phi), v.transmitted ? v.mu : -v.mu};
            rays.push_back(c);
        }
        for (double scale : {1.0, 2.5}) {
            CAPTURE(albedo);
            CAPTURE(scale);
            const vt::homogeneous_slab slab(sp.tau, scale);
            const vt::path_tracer tracer(slab, phase, albedo, light);
            check_against(vt::estimate_radiance(tracer, rays, 100000, options()), want, "slab");
        }
    }
}

TEST_CASE("results are bit-identical for a seed whatever the thread count") {
    const mc::phase_model phase = mc::make_phase("dual_hg:0.8,-0.25,0.2");
    const vt::homogeneous_sphere sphere(3.0, 2.0);
    const vt::lighting light = sun_only({0.3, 0.2, 0.9});
    const vt::path_tracer tracer(sphere, phase, 0.99, light);
    const mc::sphere_camera cam = mc::make_sphere_camera_line(120.0, 4);
    std::vector<vt::camera_ray> rays;
    for (const mc::ray& r : cam.rays) rays.push_back({r.origin, r.direction, 0.0, vt::camera_ray{}.t_end, {}});
    const auto one = vt::estimate_radiance(tracer, rays, 5000, options(1));
    const auto three = vt::estimate_radiance(tracer, rays, 5000, options(3));
    for (std::size_t i = 0; i < rays.size(); ++i) {
        CHECK(one[i].r.mean == three[i].r.mean);
        CHECK(one[i].r.std_error == three[i].r.std_error);
    }
    CHECK(one[1].r.mean > 0.0);
}

TEST_CASE("allocate_paths: Neyman allocation with costs, the target met at the least cost") {
    // Closed form without the clamps: n_i = lambda sqrt(v_i / c_i) with lambda =
    // sum sqrt(v_i c_i) / V, and the cost sum n_i c_i = (sum sqrt(v_i c_i))^2 / V.
    const std::vector<double> v{4.0, 1.0, 0.25, 9.0}, c{1.0, 4.0, 1.0, 9.0};
    const double target = 0.0123;
    const vt::path_allocation a = vt::allocate_paths(v, c, target, 2, 1u << 30);
    double root_sum = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) root_sum += std::sqrt(v[i] * c[i]);
    const double lambda = root_sum / target;
    for (std::size_t i = 0; i < v.size(); ++i) {
        CAPTURE(i);
        const double want = lambda * std::sqrt(v[i] / c[i]);
        CHECK(std::abs(double(a.paths[i]) - want) <= 0.01 * want + 1.0);  // up to the rounding up
    }
    CHECK(a.predicted_variance_sum <= target);
    CHECK(a.predicted_variance_sum > target * 0.999);
    CHECK(a.predicted_cost == doctest::Approx(root_sum * root_sum / target).epsilon(2e-3));
    // Any other allocation that meets the target costs at least as much: shift paths between
    // two rays and restore the target with the fewest paths on the second.
    const double moved = 0.9 * double(a.paths[0]);
    const double rest = target - v[0] / moved - v[2] / double(a.paths[2]) - v[3] / double(a.paths[3]);
    REQUIRE(rest > 0.0);
    CHECK(moved * c[0] + v[1] / rest * c[1] > double(a.paths[0]) * c[0] + double(a.paths[1]) * c[1]);
}

TEST_CASE("allocate_paths: bounds, zero variance, an unreachable target and bad input") {
    const std::vector<double> v{0.0, 1.0, 100.0}, c{1.0, 1.0, 1.0};
    const vt::path_allocation a = vt::allocate_paths(v, c, 0.5, 16, 1000);
    CHECK(a.paths[0] == 16);  // no variance: the floor
    CHECK(a.paths[2] > a.paths[1]);
    CHECK(a.predicted_variance_sum <= 0.5);
    // Already met by the floor: the floor everywhere.
    const vt::path_allocation floor = vt::allocate_paths(v, c, 1e6, 16, 1000);
    for (const auto n : floor.paths) CHECK(n == 16);
    // Unreachable: max_paths everywhere but for zero variance... every ray at the cap, and the
    // shortfall reported.
    const vt::path_allocation capped = vt::allocate_paths(v, c, 1e-9, 16, 1000);
    CHECK(capped.paths[1] == 1000);
    CHECK(capped.paths[2] == 1000);
    CHECK(capped.predicted_variance_sum == doctest::Approx(101.0 / 1000.0));
    CHECK_THROWS_AS((void)vt::allocate_paths({1.0}, {1.0, 2.0}, 1.0, 2, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({-1.0}, {1.0}, 1.0, 2, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({NAN}, {1.0}, 1.0, 2, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({1.0}, {0.0}, 1.0, 2, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({1.0}, {INFINITY}, 1.0, 2, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({1.0}, {1.0}, 0.0, 2, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({1.0}, {1.0}, NAN, 2, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({1.0}, {1.0}, 1.0, 1, 10), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::allocate_paths({1.0}, {1.0}, 1.0, 11, 10), std::invalid_argument);
}

TEST_CASE("per-ray path counts: equal counts reproduce the uniform run; adaptive runs stay unbiased") {
    const mc::phase_model phase = mc::make_phase("hg:0.85");
    const mc::sphere_camera cam = mc::make_sphere_camera_line(70.0, 3);
    std::vector<vt::camera_ray> rays;
    for (const mc::ray& r : cam.rays) rays.push_back({r.origin, r.direction, 0.0, vt::camera_ray{}.t_end, {}});
    const vt::homogeneous_sphere sphere(2.0);
    const vt::lighting light = sun_only(cam.sun_direction);
    const vt::path_tracer tracer(sphere, phase, 0.99, light);
    // The same streams: bit-identical, whatever the thread count.
    const auto uniform = vt::estimate_radiance(tracer, rays, 6000, options(1));
    const auto counted = vt::estimate_radiance(tracer, rays, std::vector<std::uint64_t>(rays.size(), 6000), options(3));
    for (std::size_t i = 0; i < rays.size(); ++i) {
        CHECK(counted[i].r.mean == uniform[i].r.mean);
        CHECK(counted[i].r.std_error == uniform[i].r.std_error);
    }
    CHECK_THROWS_AS((void)vt::estimate_radiance(tracer, rays, std::vector<std::uint64_t>{5}, options()), std::invalid_argument);

    // The pilot: its own streams (not the estimate's), a cost of at least 1 per path.
    const vt::pilot_estimate pilot = vt::estimate_radiance_pilot(tracer, rays, 6000, options());
    REQUIRE(pilot.cost_per_path.size() == rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        CHECK(pilot.radiance[i].r.mean != uniform[i].r.mean);
        CHECK(pilot.cost_per_path[i] >= 1.0);
        CHECK(combined_se(pilot.radiance[i].r, uniform[i].r) < 4.0);
    }
    CHECK(pilot.cost_per_path[1] > 2.0);  // the middle ray crosses the sphere: lookups counted
    CHECK_THROWS_AS((void)vt::estimate_radiance_pilot(tracer, rays, 1, options()), std::invalid_argument);

    // Counts from the pilot, then the estimate against montecarlo.hpp's exact free paths.
    mc::sphere_parameters sp;
    sp.optical_diameter = 4.0;
    sp.albedo = 0.99;
    sp.sun_direction = cam.sun_direction;
    const auto want = mc::sphere_radiance(sp, phase, cam.rays, 100000, options());
    std::vector<double> variance;
    for (const vt::rgb_estimate& e : pilot.radiance) variance.push_back(6000.0 * e.r.std_error * e.r.std_error);
    double target = 0.0;
    for (const mc::estimate& w : want) target += 4.0 * w.std_error * w.std_error;  // half the reference's precision
    const vt::path_allocation plan = vt::allocate_paths(variance, pilot.cost_per_path, target, 64, 1u << 22);
    const auto got = vt::estimate_radiance(tracer, rays, plan.paths, options());
    check_against(got, want, "adaptive sphere");
    double achieved = 0.0;
    for (const vt::rgb_estimate& e : got) achieved += e.r.std_error * e.r.std_error;
    CHECK(achieved < 1.3 * target);  // the plan's variance, up to the pilot's own error
}

namespace {

const cr::cloud_textures& textures() {
    static const cr::cloud_textures t = [] {
        cr::cloud_textures x;
        std::string why;
        REQUIRE_MESSAGE(cr::load_or_bake_textures(CLOUDMATH_TRUTH_TEST_CACHE, true, x, why), why);
        return x;
    }();
    return t;
}

}  // namespace

TEST_CASE("cloud medium: the majorants bound the renderer's density along random rays") {
    for (const char* name : {"ground", "inside", "stratus"}) {
        CAPTURE(std::string(name));
        const vt::cloud_medium medium(*cr::find_preset(name), textures());
        const cr::scene& s = medium.scene_data();
        mc::detail::random_stream rng(5, 0, 0);
        int inside = 0, cloudy = 0, violations = 0;
        double tightness = 0.0;
        for (int n = 0; n < 20000; ++n) {
            // Origins spread over 200 km and the whole layer, directions uniform.
            const mc::vec3 o{(rng.uniform() - 0.5) * 2e5, s.layer_bottom - s.camera_altitude - 200.0 + rng.uniform() * 2900.0,
                             (rng.uniform() - 0.5) * 2e5};
            const double cz = 2.0 * rng.uniform() - 1.0, phi = 2.0 * mc::detail::pi * rng.uniform();
            const double sz = std::sqrt(1.0 - cz * cz);
            const mc::vec3 d{sz * std::cos(phi), cz, sz * std::sin(phi)};
            const double len = 3000.0 * rng.uniform();
            for (int k = 0; k < 8; ++k) {
                const double t = len * rng.uniform();
                const double sigma = medium.extinction(o + t * d);
                double bound = 0.0;
                medium.majorants(o, d, 0.0, len, [&](double a, double b, double m) {
                    if (t >= a && t < b) bound = m;
                    return b <= t;
                });
                ++inside;
                if (sigma > 0.0) {
                    ++cloudy;
                    tightness += sigma / bound;
                }
                if (sigma > bound) ++violations;
            }
        }
        MESSAGE(std::string(name) << ": " << cloudy << " of " << inside << " points in cloud, mean sigma / majorant there "
                     << tightness / std::max(cloudy, 1));
        CHECK(violations == 0);
        CHECK(cloudy > 100);
    }
}

TEST_CASE("cloud scene: pixels that miss the clouds see the renderer's background exactly") {
    const cr::scene& s = *cr::find_preset("horizon");  // its lower rows see the ground
    const vt::cloud_medium medium(s, textures());
    const vt::lighting light = vt::make_cloud_lighting(s);
    const mc::phase_model phase = mc::make_phase(vt::renderer_phase_spec(s));
    CHECK(phase.spec() == "dual_hg:0.8,-0.25,0.2");
    const vt::path_tracer tracer(medium, phase, s.albedo, light);
    const std::vector<vt::camera_ray> rays = vt::make_camera_rays(s, 12, 6);
    const auto L = vt::estimate_radiance(tracer, rays, 4, options());
    int clear = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        CHECK(std::isfinite(L[i].r.mean));
        CHECK(L[i].b.mean >= 0.0);
        if (rays[i].t_end <= rays[i].t_begin) {
            ++clear;
            CHECK(L[i].b.mean == rays[i].background.b);
            CHECK(L[i].b.std_error == 0.0);
        }
    }
    MESSAGE(clear << " of " << rays.size() << " pixels without a view stretch");
    CHECK(clear >= 12);
}
