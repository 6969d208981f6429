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
#include <string>

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
