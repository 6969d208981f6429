// sun_depth_check.cpp (research, not built): the depth volume's far transmittance against 25 m marches
// from the same points. g++ -std=c++17 -O2 -I examples/cloud_renderer -I include
// examples/cloud_renderer/sun_depth_check.cpp BUILD/examples/cloud_renderer/libcloud_renderer_core.a -lpthread;
// ./a.out PRESET SPACING NEAR slice U0 (lit samples u in [U0, U0 + 40 km], read NEAR metres toward the sun).
#include "sun_depth_volume.hpp"
#include "cloud_density.hpp"
#include "scene.hpp"
#include "textures.hpp"
#include <cloudmath/cloudmath.hpp>
#include <cstdio>
#include <cmath>
#include <random>
using namespace cloud_renderer;
int main(int argc, char** argv) {
    cloud_textures t; std::string why;
    if (!load_or_bake_textures(default_texture_cache_dir(), true, t, why)) { std::puts(why.c_str()); return 1; }
    scene s = *find_preset(argc > 1 ? argv[1] : "low_sun_ahead");
    frame_constants k = make_frame_constants(s);
    float sp = argc > 2 ? std::stof(argv[2]) : 500.0f;
    const sun_depth_volume& v = sun_depth(s, k.sun_dir, t, sp, 1000.0f, true);
    cloud_density field(s, t);
    std::mt19937 rng(1); std::uniform_real_distribution<float> U(0, 1);
    double sumd = 0, sumv = 0, sumabs = 0; int n = 0, lit = 0; double sa = 0;
    const float R = s.planet_radius, r0 = R + s.camera_altitude;
    for (int i = 0; i < 3000; ++i) {
        const float uu = (argc > 5 ? std::stof(argv[5]) : 0.0f) + U(rng) * 40000.0f, ww = (U(rng) - 0.5f) * 80000.0f;
        glm::vec3 p(v.eu.x * uu + v.ew.x * ww, 0.0f, v.eu.y * uu + v.ew.y * ww);
        float alt = v.alt_lo + (v.alt_hi - v.alt_lo) * U(rng);
        p.y = std::sqrt((R + alt) * (R + alt) - p.x * p.x - p.z * p.z) - r0;
        if (field.density(p) <= 0.0f) continue;  // a lit sample: inside cloud
        p += k.sun_dir * (argc > 3 ? std::stof(argv[3]) : 1000.0f); if (field.altitude(p) > v.alt_hi) continue;
        float tau = 0; float ds = 25.0f;
        for (int m = 0; m < 20000; ++m) { glm::vec3 q = p + k.sun_dir * ((float(m) + 0.5f) * ds); float a = field.altitude(q); if (a > v.alt_hi || a < v.alt_lo) break; tau += s.extinction * field.density(q) * ds; if (tau > 30) break; }
        float tau100 = 0; for (int m = 0; m < 5000; ++m) { glm::vec3 q = p + k.sun_dir * ((float(m) + 0.5f) * 100.0f); float a = field.altitude(q); if (a > v.alt_hi || a < v.alt_lo) break; tau100 += s.extinction * field.density(q) * 100.0f; }
        float Tv = sun_depth_lookup(v, p, field.altitude(p));
        if (argc > 4) {
            const glm::vec2 ns = sun_depth_next_slice(v, p, field.altitude(p), k.sun_dir, R, r0);
            float seg = 0; const int nn = std::max(1, int(std::ceil(ns.x / 10.0f))); const float dd = ns.x / float(nn);
            for (int m = 0; m < nn; ++m) seg += s.extinction * field.density(p + k.sun_dir * ((float(m) + 0.5f) * dd)) * dd;
            Tv = std::exp(-seg) * (ns.y >= 0.0f ? sun_depth_on_slice(v, int(ns.y), p + k.sun_dir * ns.x) : 1.0f);
        }
        float Td = std::exp(-tau);
        sumd += Td; sumv += Tv; sumabs += std::fabs(Td - Tv); ++n;
        if (Td > 0.05f) { ++lit; sa += std::fabs(Td - Tv) / Td; }
        if (Td > 0.05f && Td < 0.95f && lit < 25) std::printf("Td %.4f T100 %.4f Tv %.4f tau %.3f\n", Td, std::exp(-tau100), Tv, tau);
    }
    std::printf("n %d mean Td %.4f Tv %.4f mean|d| %.4f; lit %d mean rel %.3f\n", n, sumd / n, sumv / n, sumabs / n, lit, sa / lit);
}
