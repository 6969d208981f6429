#include "cpu_renderer.hpp"

#include "far_shadow.hpp"
#include "physical_sky.hpp"

#include "cloud_density.hpp"

#include <cloudmath/cloudmath.hpp>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

namespace cloud_renderer {
namespace {

namespace cm = cloudmath;
using glm::vec2;
using glm::vec3;
using glm::vec4;

// GL_LINEAR's four taps on a width x height grid for footprint fp = (x0, y0, fx, fy)
// (texel_bilinear), clamped to the grid: tap(index, weight) for each, in the shaders' order.
template <class Tap>
void bilinear_taps(vec4 fp, int width, int height, Tap tap) {
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            const int tx = std::clamp(int(fp.x) + dx, 0, width - 1), ty = std::clamp(int(fp.y) + dy, 0, height - 1);
            tap(static_cast<std::size_t>(ty) * static_cast<std::size_t>(width) + static_cast<std::size_t>(tx),
                (dx ? fp.z : 1.0f - fp.z) * (dy ? fp.w : 1.0f - fp.w));
        }
}

// Catmull-Rom's value of `values` (a width x height grid) around footprint fp, clamped to
// the grid, then to the range of the four bilinear taps: no ringing. A sharper
// reconstruction than GL_LINEAR, which, repeated every frame on a moving history, blurs it.
// temporal_resolve.frag's cr_catmull_rom reads it in five GL_LINEAR reads (the middle pair of
// taps along each axis is one linear read); those are the 16 taps less the four corners
// (each weight at most 0.0055), renormalised, which is what this sums texel by texel.
vec4 catmull_rom_clamped(vec4 fp, int width, int height, const std::vector<vec4>& values) {
    const auto weights = [](float f, float* w) {
        w[0] = f * (-0.5f + f * (1.0f - 0.5f * f));
        w[1] = 1.0f + f * f * (-2.5f + 1.5f * f);
        w[2] = f * (0.5f + f * (2.0f - 1.5f * f));
        w[3] = f * f * (-0.5f + 0.5f * f);
    };
    float wx[4], wy[4];
    weights(fp.z, wx);
    weights(fp.w, wy);
    vec4 sum(0.0f), lo(INFINITY), hi(-INFINITY);
    float total = 0.0f;
    for (int dy = -1; dy < 3; ++dy)
        for (int dx = -1; dx < 3; ++dx) {
            const bool corner = (dx == -1 || dx == 2) && (dy == -1 || dy == 2);
            if (corner) continue;
            const int tx = std::clamp(int(fp.x) + dx, 0, width - 1), ty = std::clamp(int(fp.y) + dy, 0, height - 1);
            const vec4 texel = values[static_cast<std::size_t>(ty) * static_cast<std::size_t>(width) + static_cast<std::size_t>(tx)];
            const float weight = wx[dx + 1] * wy[dy + 1];
            sum += texel * weight;
            total += weight;
        }
    bilinear_taps(fp, width, height, [&](std::size_t i, float) {
        lo = glm::min(lo, values[i]);
        hi = glm::max(hi, values[i]);
    });
    return glm::clamp(sum / total, lo, hi);
}

// A view sample in cloud, recorded by the march for the light pass (clouds.frag's CrLitSample).
struct lit_sample {
    float t;              // distance along the view ray
    float sigma_t;        // extinction
    float ds;             // length of its step
    float tau_view;       // optical depth from the camera to the step's middle
    float transmittance;  // the view's transmittance in front of the step
};

// The shader's functions (cr_*), with the uniforms as members.
struct pixel_program {
    const scene& s;
    const variant& v;
    // Samples the march records before the light pass runs (1..lit_samples): the shader's
    // CR_LIT_SAMPLES; render_cpu_lit_capacity sets others, which must give the same image.
    int lit_capacity = lit_samples;
    frame_constants k;
    cloud_density field;
    cm::mie_approx_parameters<float> mie;
    float phase_g_mean;  // the diffusion model's g
    vec2 band;           // altitudes of the cloud type's band (height_range_for_type): no density outside
    const cm::diffusion_model* model;  // the diffusion model's fitted numbers
    std::shared_ptr<const haze_table> haze;  // the physical sky's aerial perspective (physical_sky.hpp)
    std::shared_ptr<const far_shadow_table> far_field;  // ... and its clouds' shadow beyond the light march (far_shadow.hpp)
    std::vector<vec3> shadow_map;  // the Beer shadow map (needs_shadow_map), row j = 0 first
    long shadow_map_reads = 0;     // texture reads of building it (once per frame)

    // `kept_map`: the shadow map of the temporal scheme's previous frames, of which only rows
    // `rows` are redrawn (temporal_shadow_rows); null: the whole map is drawn. `tables`: where
    // the physical sky's tables are kept (the process's, or a cpu_temporal_renderer's own).
    pixel_program(const scene& sc, const variant& va, const cloud_textures& t, const cm::diffusion_model* m = nullptr,
                  const std::vector<vec3>* kept_map = nullptr, glm::ivec2 rows = glm::ivec2(0, shadow_map_size),
                  cpu_sky_tables& tables = shared_cpu_sky_tables())
        : s(sc), v(va), k(make_frame_constants(sc, tables)), field(sc, t), mie(cm::mie_approx_params(k.droplet_diameter)),
          phase_g_mean(phase_mean_cosine(k, va.phase)),
          band(k.band),
          model(m != nullptr ? m : va.table == diffusion_table::clouds ? &cm::diffusion_models::clouds : &cm::diffusion_models::fitted),
          haze(sc.sky == sky_model::physical ? physical_haze(sc.camera_altitude, k.sun_dir, tables) : nullptr),
          far_field(sc.sky == sky_model::physical ? far_shadow(sc, k.sun_dir, t, light_reach(va, k), tables) : nullptr) {
        if (needs_shadow_map(v, s)) {
            shadow_map.resize(static_cast<std::size_t>(shadow_map_size) * static_cast<std::size_t>(shadow_map_size));
            if (kept_map != nullptr && kept_map->size() == shadow_map.size()) shadow_map = *kept_map;
            else rows = glm::ivec2(0, shadow_map_size);
            for (int j = rows.x; j < rows.y; ++j)
                for (int i = 0; i < shadow_map_size; ++i)
                    shadow_map[static_cast<std::size_t>(j * shadow_map_size + i)] = shadow_texel(i, j, &shadow_map_reads);
        }
    }

    // Texel (i, j) of the Beer shadow map (the shader's pass 2, cr_shadow_texel): midpoint
    // steps along the sunlight through the cloud type's band, depths from the map's plane.
    vec3 shadow_texel(int i, int j, long* counter = nullptr) const {
        const vec2 ab = (vec2(float(i) + 0.5f, float(j) + 0.5f) / float(shadow_map_size) * 2.0f - 1.0f) * k.shadow_half_extent;
        const vec3 p0 = k.shadow_origin + k.shadow_right * ab.x + k.shadow_up * ab.y;
        const vec2 seg = cm::cloud_layer_segment(altitude(p0), -glm::dot(k.sun_dir, up_at(p0)), s.planet_radius, band.x, band.y);
        cm::beer_shadow_accumulator<float> acc;
        if (seg.y > seg.x) {
            const float ds = (seg.y - seg.x) / float(shadow_map_steps);
            for (int m = 0; m < shadow_map_steps; ++m) {
                const float t = seg.x + float(m) * ds;
                const vec3 q = p0 - k.sun_dir * (t + 0.5f * ds);
                acc.add_step(t, ds, s.extinction * density(q, altitude(q), counter));
            }
        }
        return acc.texel();
    }

    // What the shadow map leaves of the ground's light where the ray in direction dir meets
    // the ground: the sky's share plus the sun's times the clouds' transmittance (1 where the
    // ray meets sky, or ground outside the map). Bilinear texels (texel_bilinear), clamped.
    float ground_shadow(vec3 dir) const {
        const vec2 g = cm::ray_sphere_intersect_altitude(s.camera_altitude, dir.y, s.planet_radius, 0.0f);
        if (!(g.x >= 0.0f && g.y > g.x)) return 1.0f;
        const vec3 uvd = cm::shadow_map_project(dir * g.x, k.shadow_origin, k.shadow_right, k.shadow_up, k.sun_dir,
                                                k.shadow_half_extent);
        if (!on_map(uvd)) return 1.0f;
        return glm::mix(ground_sky_share, 1.0f, cm::beer_shadow_transmittance(shadow_lookup(vec2(uvd)), uvd.z));
    }

    static bool on_map(vec3 uvd) { return uvd.x >= 0.0f && uvd.x <= 1.0f && uvd.y >= 0.0f && uvd.y <= 1.0f; }

    // The map's texel at uv: bilinear (texel_bilinear), taps clamped to the map (4 reads).
    vec3 shadow_lookup(vec2 uv, long* counter = nullptr) const {
        if (counter) *counter += 4;
        vec3 texel(0.0f);
        bilinear_taps(cm::texel_bilinear(uv, vec2(float(shadow_map_size))), shadow_map_size, shadow_map_size,
                      [&](std::size_t i, float weight) { texel += shadow_map[i] * weight; });
        return texel;
    }

    // Texture reads of one pixel (count_texture_reads); null when not counting.
    struct reads {
        long view = 0, light = 0;
        bool in_layer = false;  // the view ray enters the cloud layer
    };

    float altitude(vec3 p) const { return field.altitude(p); }
    // The unit vertical at the camera-relative point p (clouds.frag's cr_up).
    vec3 up_at(vec3 p) const { return glm::normalize(vec3(p.x, p.y + (s.planet_radius + s.camera_altitude), p.z)); }
    float density(vec3 p, float alt, long* counter = nullptr) const { return field.density(p, alt, counter); }

    float cone_extinction(vec3 p, long* counter = nullptr) const { return s.extinction * density(p, altitude(p), counter); }

    float phase(float mu, float scale) const {
        switch (v.phase) {
        case phase_model::hg: return cm::phase_hg(mu, scale * k.phase_g);
        case phase_model::dual_hg: return cm::phase_hg_dual(mu, scale * k.phase_g, scale * k.phase_g_back, k.phase_w);
        case phase_model::cornette_shanks: return cm::phase_cornette_shanks(mu, scale * k.phase_g);
        case phase_model::mie: break;
        }
        cm::mie_approx_parameters<float> m = mie;
        m.g_hg *= scale;
        m.g_draine *= scale;
        return cm::phase_mie_approx(mu, m);
    }

    // Optical depth from p along the unit vector `toward` (the sun, or away from it for the
    // diffusion model's tau_behind) by the cone or by a march to where the cloud type's
    // altitude band ends (height_range_for_type: no density beyond it, so the band's steps
    // lose nothing and a 225 m stratus sheet gets all of them instead of 1 in 11), its steps
    // quadratic (light_march_distance: short near the sample, where the light is decided),
    // sampled at light_offset within each. near (if given): the depth without the far field
    // (reach=far's steps), which the physical sky's occluded sky light uses
    // (sky_depth_toward_sun); the whole in map and cone modes.
    float light_optical_depth(vec3 p, float alt, vec3 toward, light_mode mode, long* counter = nullptr,
                              float light_offset = 0.5f, float* near = nullptr) const {
        const auto whole = [near](float tau) {
            if (near != nullptr) *near = tau;
            return tau;
        };
        if (mode == light_mode::map) {
            // Toward the sun: the map's optical depth at p's depth; away from it: the rest of
            // the column. Off the map: the cone.
            const vec3 uvd = cm::shadow_map_project(p, k.shadow_origin, k.shadow_right, k.shadow_up, k.sun_dir,
                                                    k.shadow_half_extent);
            if (on_map(uvd)) {
                const vec3 texel = shadow_lookup(vec2(uvd), counter);
                const float before = cm::beer_shadow_optical_depth(texel, uvd.z);
                return whole(glm::dot(toward, k.sun_dir) > 0.0f ? before : std::max(texel.z - before, 0.0f));
            }
            mode = light_mode::cone;
        }
        if (mode == light_mode::cone) {
            const cm::cone_light_config<float> cone{cone_samples, k.cone_step, k.cone_spread, k.cone_far_distance,
                                                    k.cone_far_length};
            return whole(cm::cone_optical_depth(p, toward, cone, [this, counter](const vec3& q, int) { return cone_extinction(q, counter); }));
        }
        const vec2 seg = cm::cloud_layer_segment(alt, glm::dot(toward, up_at(p)), s.planet_radius, band.x, band.y);
        const float reach = v.reach == reach_mode::band ? light_long_reach : k.light_march_max;
        const float length_to_exit = seg.y > seg.x ? std::min(seg.y, reach) : 0.0f;
        float tau = 0.0f;
        // Step i spans [at(i / n), at((i + 1) / n)], its sample at at((i + offset) / n).
        const float nl = float(v.light_steps);
        const auto at = [&](float u) { return cm::light_march_distance(u, length_to_exit); };
        for (int i = 0; i < v.light_steps; ++i) {
            const float ds = at((float(i) + 1.0f) / nl) - at(float(i) / nl);
            tau += cone_extinction(p + toward * at((float(i) + light_offset) / nl), counter) * ds;
        }
        if (near != nullptr) *near = tau;
        // reach=far: toward the sun, the rest of the band beyond the capped march in
        // far_step_count uniform steps on the full density.
        if (v.reach == reach_mode::far && seg.y > length_to_exit && glm::dot(toward, k.sun_dir) > 0.0f) {
            const int nf = far_step_count(v.light_steps);
            const float span = (std::min(seg.y, light_long_reach) - length_to_exit) / float(nf);
            for (int j = 0; j < nf; ++j) {
                const vec3 q = p + toward * (length_to_exit + (float(j) + light_offset) * span);
                tau += cone_extinction(q, counter) * span;
            }
        }
        return tau;
    }

    // tau_behind and tau_view are used by the diffusion model only; far: the far shadow's
    // transmittance (far_shadow_at), on the sun's light only; tau_sky: the depth toward the sun
    // the occluded sky light uses (sky_depth_toward_sun).
    vec3 in_scattering(float tau_light, float tau_behind, float tau_view, float mu, float h, float far_light,
                       float tau_sky) const {
        const auto phase_fn = [this](float m, float scale) { return phase(m, scale); };
        float sun = v.lighting == lighting_model::diffusion
                        ? cm::diffusion_scattering_with(tau_light, tau_behind, tau_view, mu, phase_g_mean, s.albedo,
                                                        *model, phase_fn)
                        : cm::multiple_scattering_with(tau_light, mu, k.ms_a, k.ms_b, k.ms_c, v.octaves, phase_fn);
        if (v.powder) sun *= glm::mix(2.0f * cm::powder(tau_light, 2.0f), 1.0f, 0.5f + 0.5f * mu);
        const vec3 sun_light = sun_at_height(k, haze != nullptr, h) * far_light;  // the physical sky's sun by height
        if (!v.occluded_ambient) return sun_light * sun + glm::mix(k.ambient_bottom, k.ambient_top, h);
        const vec2 o = sky_occlusion(tau_sky, tau_behind);
        return sun_light * sun + glm::mix(k.ambient_bottom * o.y, k.ambient_top * o.x, h);
    }

    // The physical sky's far shadow at p (altitude alt): the table by the sun's zenith cosine
    // at p (clouds.frag's cr_far_shadow); 1 with the artistic sky.
    float far_shadow_at(vec3 p, float alt) const {
        if (far_field == nullptr) return 1.0f;
        return far_shadow_lookup(*far_field, alt, glm::dot(k.sun_dir, up_at(p)));
    }

    // variant::occluded_ambient: what reaches the sample of the sky light from above (x) and
    // below (y), diffuse_transmittance of the vertical optical depths estimated from the
    // slanted light estimates times the sine of the sun's elevation. With the sun below the
    // horizon the estimate toward the sun looks down and the one away from it looks up, so they
    // swap (before, the sine was clamped to 0 there: no occlusion at all, and the sunset's sky
    // light 18% too bright; docs/lighting_research.md, "The sun below the horizon").
    vec2 sky_occlusion(float tau_light, float tau_behind) const {
        const float sine = k.sun_dir.y;
        const vec2 depths = sine >= 0.0f ? vec2(tau_light, tau_behind) : vec2(tau_behind, tau_light);
        const float up = std::fabs(sine);
        return {cm::diffuse_transmittance(depths.x * up, phase_g_mean), cm::diffuse_transmittance(depths.y * up, phase_g_mean)};
    }

    // The depth toward the sun that the occluded sky light reads (sky_occlusion), from the
    // light estimate `whole` and its part without the far field `near`. With the physical sky,
    // near: the far steps toward a low sun cross clouds kilometres away, which shade the sun
    // (they stay in the sun's depth) but not the sky above the sample; low_sun_behind 42.7 ->
    // 39.2% excess error, horizon 75.0 -> 74.5%, sunrise 60.5 -> 59.6%, nothing at a high sun,
    // where the band ends within the march's cap (docs/lighting_research.md, "The sky light's
    // depth without the far field"). With the artistic sky, whole: its table
    // (diffusion_clouds.txt) was fitted with it, and refitted with near it loses 2.3 points at
    // low_sun_behind.
    float sky_depth_toward_sun(float whole, float near) const { return haze != nullptr ? near : whole; }

    // One sample's share of the pixel's gradient (shade_linear's grad): its source is
    // weight * sun_radiance * (diffusion model), linear in the table and peak weights.
    void add_gradient(float* grad, float weight, float tau_light, float tau_behind, float tau_view, float mu) const {
        namespace L = cm::diffusion_layout;
        const cm::detail::diffusion_sample<float> t =
            cm::detail::diffusion_sample_terms(tau_light, tau_behind, tau_view, mu, phase_g_mean, s.albedo);
        cm::detail::diffusion_table_corners(t.u, [&](int index, float w) { grad[index] += weight * t.diffuse * w; });
        for (int ia = 0; ia < L::peak_a_count; ++ia)
            for (int ic = 0; ic < L::peak_c_count; ++ic)
                grad[L::table_size + ia * L::peak_c_count + ic] += weight * t.beams[ia] * phase(t.mu, float(L::peak_c[ic]));
    }

    // main() of the shader for the pixel whose centre is (x + 0.5, y + 0.5), before the
    // tonemap: rgb linear radiance, a opacity. depth (optional): the cloud's
    // transmittance-weighted distance, 0 where the ray meets no cloud (out_depth).
    // grad (optional, diffusion model): adds d(radiance) / d(fitted number) over sun_radiance
    // for the model's table then peak weights (diffusion_feature_count), the max(0, ...)
    // clamps ignored, and to sky (given with grad) the sky light's weights from above and
    // below (render_cpu_diffusion_features). layer_only: rgb is the cloud layer's own light
    // (haze included), without what lies behind it (clouds.frag's passes 0 and 1: the
    // composite, composite_display, lays it over behind() at full resolution every frame).
    vec4 shade_linear(int x, int y, int width, int height, reads* counted = nullptr, float* depth = nullptr,
                      float* grad = nullptr, float* sky = nullptr, bool layer_only = false) const {
        long* view_reads = counted ? &counted->view : nullptr;
        long* light_reads = counted ? &counted->light : nullptr;
        const vec3 dir = pixel_direction(k, x, y, width, height);
        if (depth != nullptr) *depth = 0.0f;

        cm::march_accumulator<vec3, vec3> acc;
        // The view stretch: from where the ray enters the layer, at most max_distance. The
        // march covers the part of it inside the cloud type's altitude band (no density outside).
        const vec2 seg = view_stretch(dir);
        if (counted) {
            const vec2 layer = cm::cloud_layer_segment(s.camera_altitude, dir.y, s.planet_radius, s.layer_bottom, s.layer_top);
            counted->in_layer = layer.y > layer.x;
        }
        if (seg.y > seg.x) {
            const float t1 = seg.y;
            const std::uint32_t pixel_hash = cm::noise_hash(static_cast<std::uint32_t>(x) + static_cast<std::uint32_t>(y) * 8192u);
            const float offset = cm::frame_jitter(pixel_hash, s.frame);
            const float mu = glm::dot(dir, k.sun_dir);
            const float n = float(v.view_steps);
            const auto at = [&](float u) {
                return v.schedule == step_schedule::growing ? cm::march_schedule_distance(u, seg.x, t1, k.march_near_distance)
                                                            : seg.x + u * (t1 - seg.x);
            };
            float tau_view = 0.0f;    // optical depth from the camera to the start of the step
            float depth_sum = 0.0f;   // sum of each step's opacity times its distance
            float step_begin = seg.x; // = at(0), for both schedules
            float step_end = seg.x;   // the end of view step i, once its sample is taken
            bool after_empty = true;  // no cloud since the last empty sample (or the start)
            float last_empty = -1.0f; // the last view sample with no cloud
            std::uint32_t light_index = 0; // light estimates so far (their jitter's index)
            // The light pass (cr_light_samples): each recorded sample's light estimates and
            // source, added with its transmittance in the march's order.
            const auto light_samples = [&](const lit_sample* samples, int count) {
                for (int q = 0; q < count; ++q) {
                    const lit_sample& e = samples[q];
                    const float alts = cm::altitude_along_ray(s.camera_altitude, dir.y, s.planet_radius, e.t);
                    // The light march's offset: new for each light estimate and frame.
                    const float lo = cm::sample_jitter(pixel_hash, s.frame, light_index++);
                    float tau_near = 0.0f;
                    const float tau_light = light_optical_depth(dir * e.t, alts, k.sun_dir, v.light, light_reads, lo, &tau_near);
                    const float tau_sky = sky_depth_toward_sun(tau_light, tau_near);
                    const float tau_behind = v.lighting == lighting_model::diffusion
                                                 ? light_optical_depth(dir * e.t, alts, -k.sun_dir, v.behind, light_reads, lo)
                                                 : 0.0f;
                    const float h = cm::height_fraction(alts, s.layer_bottom, s.layer_top);
                    const float far_light = far_shadow_at(dir * e.t, alts);
                    const vec3 S = (s.albedo * e.sigma_t) * in_scattering(tau_light, tau_behind, e.tau_view, mu, h, far_light, tau_sky);
                    if (grad != nullptr) {
                        // This step's weight in the pixel per unit source (add_segment's), times
                        // the sun here over sun_radiance: with the physical sky the sun changes
                        // with height and the far shadow dims it; the features are per unit of
                        // one colour, so that ratio is the sun's projection on sun_radiance
                        // (exactly 1 with the artistic sky).
                        const vec3 sun_here = sun_at_height(k, haze != nullptr, h) * far_light;
                        const float sun_sq = glm::dot(k.sun_radiance, k.sun_radiance);
                        const float ratio = haze == nullptr ? 1.0f : sun_sq > 0.0f ? glm::dot(sun_here, k.sun_radiance) / sun_sq : 0.0f;
                        const float w = e.transmittance * s.albedo * e.sigma_t * cm::integrate_scattering(1.0f, e.sigma_t, e.ds);
                        add_gradient(grad, w * ratio, tau_light, tau_behind, e.tau_view, mu);
                        const vec2 o = v.occluded_ambient ? sky_occlusion(tau_sky, tau_behind) : vec2(1.0f);
                        sky[0] += w * h * o.x;
                        sky[1] += w * (1.0f - h) * o.y;
                    }
                    // Energy-conserving (add_segment's source term), or the textbook Riemann
                    // sum: the source at full strength over the whole step.
                    acc.luminance += v.integration == integration_mode::analytic
                                         ? vec3(e.transmittance) * cm::integrate_scattering(S, e.sigma_t, e.ds)
                                         : vec3(e.transmittance) * S * e.ds;
                }
            };
            // The march: one flat loop with one density sample per turn (clouds.frag's main):
            // view step i's sample or sub-step m of the refined step i (variant::refine: a step
            // thicker than optical depth 1 is marched again in `sub` sub-steps of sub_ds from
            // sub_from, the last empty sample when it is the first step in cloud). It records
            // the samples in cloud, and the light pass lights them whenever lit_capacity are
            // recorded and at the end.
            std::array<lit_sample, lit_samples> recorded{};
            const int capacity = std::clamp(lit_capacity, 1, lit_samples);
            int i = 0, m = 0, sub = 0;
            float sub_from = 0.0f, sub_ds = 0.0f;
            bool opaque = false;
            for (;;) {
                int count = 0;
                while (!opaque && count < capacity && (m < sub || i < v.view_steps)) {
                    const bool refining = m < sub;
                    const float t = refining ? sub_from + (float(m) + offset) * sub_ds : at((float(i) + offset) / n);
                    const float alt = cm::altitude_along_ray(s.camera_altitude, dir.y, s.planet_radius, t);
                    const float d = field.density(dir * t, alt, view_reads);
                    float ds = 0.0f;
                    if (refining) {
                        ds = sub_ds;
                        if (++m == sub) {
                            step_begin = step_end;
                            ++i;
                        }
                        if (d <= 0.0f) continue;
                    } else {
                        step_end = at((float(i) + 1.0f) / n);
                        if (d <= 0.0f) {
                            last_empty = t;
                            step_begin = step_end;
                            after_empty = true;
                            ++i;
                            continue;
                        }
                        const float r0 = after_empty && last_empty >= 0.0f ? last_empty : step_begin;
                        const int n_sub = cm::refine_substeps(s.extinction * d * (step_end - r0), v.refine);
                        after_empty = false;
                        if (n_sub > 1) {  // march the step again in sub-steps, from the next turn
                            sub = n_sub;
                            m = 0;
                            sub_from = r0;
                            sub_ds = (step_end - r0) / float(n_sub);
                            continue;
                        }
                        ds = step_end - step_begin;
                        step_begin = step_end;
                        ++i;
                    }
                    // A sample in cloud: record it for the light pass, and take its transmittance.
                    const float sigma_t = s.extinction * d;
                    const float before = acc.transmittance.r;  // grey extinction: every channel alike
                    recorded[static_cast<std::size_t>(count++)] = {t, sigma_t, ds, tau_view + 0.5f * sigma_t * ds, before};
                    tau_view += sigma_t * ds;
                    acc.transmittance *= cm::beer_lambert(sigma_t * ds);
                    depth_sum += (before - acc.transmittance.r) * t;
                    opaque = acc.is_opaque(k.min_transmittance);
                }
                light_samples(recorded.data(), count);
                if (opaque || count < capacity) break;
            }
            // Aerial perspective: the air between the camera and the cloud's
            // transmittance-weighted depth dims its light and adds the horizon's haze in
            // proportion to its opacity (the sky behind already holds its air). The physical
            // sky's haze is the atmosphere's in-scattering along this direction to that depth.
            const float opacity = 1.0f - acc.transmittance.r;
            if (depth != nullptr && opacity > 0.0f) *depth = depth_sum / opacity;
            if (s.haze && opacity > 0.0f) {
                const vec3 tau_air = cm::air_optical_depth(s.camera_altitude, dir.y, depth_sum / opacity);
                if (haze != nullptr) {
                    acc.luminance = acc.luminance * glm::exp(-tau_air) + haze_lookup(*haze, dir, k.sun_dir, depth_sum / opacity) * opacity;
                } else {
                    acc.luminance = cm::aerial_perspective(acc.luminance, k.sky_horizon * opacity, tau_air);
                }
            }
        }
        const vec3 t = acc.transmittance;
        const float alpha = 1.0f - (t.r + t.g + t.b) / 3.0f;
        if (layer_only) return vec4(acc.luminance, alpha);
        const vec3 color = behind(dir) * acc.transmittance + acc.luminance;
        return vec4(color, alpha);
    }

    // The view stretch: from where the ray enters the layer, at most max_distance, the part
    // of it inside the cloud type's altitude band (no density outside); empty (y <= x) where
    // the ray meets no cloud at all.
    vec2 view_stretch(vec3 dir) const {
        const vec2 layer = cm::cloud_layer_segment(s.camera_altitude, dir.y, s.planet_radius, s.layer_bottom, s.layer_top);
        const vec2 in_band = cm::cloud_layer_segment(s.camera_altitude, dir.y, s.planet_radius, band.x, band.y);
        vec2 seg(std::max(layer.x, in_band.x), std::min(std::min(layer.y, layer.x + s.max_distance), in_band.y));
        const float scene_t = terrain_distance(s, dir, nullptr);
        if (scene_t > 0.0f) seg.y = std::min(seg.y, scene_t);  // the scene's geometry hides what lies behind it
        return seg;
    }

    // What lies behind the cloud layer along dir: the sky, or the ground with the clouds'
    // shadows (cr_background).
    vec3 behind(vec3 dir) const {
        vec3 normal;
        const float scene_t = terrain_distance(s, dir, &normal);
        if (scene_t > 0.0f) return terrain_radiance(dir * scene_t, normal);
        return background(s, k, dir, s.sun_disc) * (s.shadows ? ground_shadow(dir) : 1.0f);
    }

    // The sun's transmittance through the clouds at p from the shadow map (1 outside it).
    float sun_transmittance(vec3 p) const {
        const vec3 uvd = cm::shadow_map_project(p, k.shadow_origin, k.shadow_right, k.shadow_up, k.sun_dir, k.shadow_half_extent);
        return on_map(uvd) ? cm::beer_shadow_transmittance(shadow_lookup(vec2(uvd)), uvd.z) : 1.0f;
    }

    // A terrain box's radiance at p, face normal n (clouds.frag's cr_terrain): Lambertian rock
    // of albedo 0.25 lit by the sun through the clouds (with scene shadows) and by the sky light
    // above and the ground's below, in the shares of the hemisphere the face sees.
    vec3 terrain_radiance(vec3 p, vec3 n) const {
        const float sun = std::max(glm::dot(n, k.sun_dir), 0.0f) * (s.shadows ? sun_transmittance(p) : 1.0f);
        return (0.25f / 3.14159265f) * (k.sun_radiance * sun + 3.14159265f * glm::mix(k.ground, k.ambient_top, 0.5f + 0.5f * n.y));
    }

    // The full frame's pixel: the layer (clouds.frag's pass 0) over what lies behind it
    // (pass 3), through composite.frag.
    vec4 shade(int x, int y, int width, int height) const {
        const vec4 layer = shade_linear(x, y, width, height, nullptr, nullptr, nullptr, nullptr, true);
        return composite_display(behind(pixel_direction(k, x, y, width, height)), layer, k.exposure, s.dither, x, y, s.frame);
    }
};

// Every pixel of a width x height image, rows taken by `threads` workers.
template <class Shade>
image render_rows(int width, int height, unsigned threads, const Shade& shade) {
    image img;
    img.width = width;
    img.height = height;
    img.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), vec4(0.0f));
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::atomic<int> next_row{0};
    const auto work = [&] {
        for (int y; (y = next_row.fetch_add(1)) < height;)
            for (int x = 0; x < width; ++x) img.at(x, y) = shade(x, y);
    };
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    return img;
}

}  // namespace

std::uint32_t dither_hash(int x, int y, std::uint32_t frame) {
    const std::uint32_t pixel = static_cast<std::uint32_t>(x) + static_cast<std::uint32_t>(y) * 8192u;
    return cm::noise_hash(cm::noise_hash(pixel) + frame * 0x9e3779b9u);
}

vec4 composite_display(vec3 behind, vec4 layer, float exposure, bool dither, int x, int y, std::uint32_t frame) {
    vec3 shown = tonemap(behind * (1.0f - layer.a) + vec3(layer), exposure);
    if (dither) shown += cm::triangular_dither(dither_hash(x, y, frame)) * (1.0f / 255.0f);
    return vec4(shown, layer.a);
}

image render_cpu(const scene& s, const variant& v, const cloud_textures& textures, int width, int height, unsigned threads) {
    const pixel_program program(s, v, textures);
    return render_rows(width, height, threads, [&](int x, int y) { return program.shade(x, y, width, height); });
}

texture_read_stats count_texture_reads(const scene& s, const variant& v, const cloud_textures& textures, int width,
                                       int height, unsigned threads) {
    const pixel_program program(s, v, textures);
    std::vector<pixel_program::reads> counts(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    (void)render_rows(width, height, threads, [&](int x, int y) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        return program.shade_linear(x, y, width, height, &counts[i]);
    });
    texture_read_stats st;
    st.shadow_map = program.shadow_map_reads;
    std::vector<double> totals;
    double view = 0.0, light = 0.0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        if (!counts[i].in_layer) continue;
        totals.push_back(double(counts[i].view + counts[i].light));
        view += double(counts[i].view);
        light += double(counts[i].light);
    }
    st.pixels_in_layer = static_cast<int>(totals.size());
    if (totals.empty()) return st;
    std::sort(totals.begin(), totals.end());
    st.mean = (view + light) / double(totals.size());
    st.p95 = totals[std::min(totals.size() - 1, static_cast<std::size_t>(0.95 * double(totals.size())))];
    st.light_share = view + light > 0.0 ? light / (view + light) : 0.0;
    return st;
}

image render_cpu_lit_capacity(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                              int capacity, unsigned threads) {
    pixel_program program(s, v, textures);
    program.lit_capacity = capacity;
    return render_rows(width, height, threads, [&](int x, int y) { return program.shade_linear(x, y, width, height); });
}

image render_cpu_linear(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                        unsigned threads) {
    const pixel_program program(s, v, textures);
    return render_rows(width, height, threads, [&](int x, int y) { return program.shade_linear(x, y, width, height); });
}

diffusion_features render_cpu_diffusion_features(const scene& s, const variant& v, const cloud_textures& textures,
                                                 int width, int height, unsigned threads) {
    static constexpr cm::diffusion_model zero{};
    diffusion_features f;
    f.width = width;
    f.height = height;
    f.grad.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * diffusion_feature_count, 0.0f);
    const pixel_program program(s, v, textures, &zero);
    f.sky.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 2, 0.0f);
    const image fixed = render_rows(width, height, threads, [&](int x, int y) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        return program.shade_linear(x, y, width, height, nullptr, nullptr, &f.grad[i * diffusion_feature_count], &f.sky[i * 2]);
    });
    f.ambient_top = program.k.ambient_top;
    f.ambient_bottom = program.k.ambient_bottom;
    f.sun_radiance = program.k.sun_radiance;
    f.fixed.reserve(fixed.pixels.size());
    for (const vec4& c : fixed.pixels) f.fixed.emplace_back(c);
    return f;
}

image render_cpu_linear_with(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                             const cloudmath::diffusion_model& model, unsigned threads) {
    const pixel_program program(s, v, textures, &model);
    return render_rows(width, height, threads, [&](int x, int y) { return program.shade_linear(x, y, width, height); });
}

}  // namespace cloud_renderer

namespace cloud_renderer {

cpu_temporal_renderer::cpu_temporal_renderer(int width, int height, int max_samples)
    : width_(width), height_(height), max_samples_(max_samples),
      color_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
      aux_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {}

image cpu_temporal_renderer::frame(const scene& s, const variant& v, const cloud_textures& textures, unsigned threads) {
    const int w = width_, h = height_;
    const int lw = (w + 3) / 4, lh = (h + 3) / 4;  // the quarter-resolution pass
    const glm::uvec2 offset = cm::temporal_update_offset(s.frame);
    // The shading pass: pixel (4 i + offset.x, 4 j + offset.y), with the march jitter of
    // frame / 16 (each pixel's own sample count). Blocks on the right and top edges may
    // shade a pixel just outside the image: its sample still stands in for the block.
    scene shading = s;
    shading.frame = s.frame >> 4U;
    // The shadow map a slice a frame (temporal_shadow_rows): the whole of it on a first frame
    // or when the variant or the shape changed.
    const std::string map_key = permutation_key(v, s);
    const bool whole_map = !has_history_ || map_key != shadow_map_key_;
    const pixel_program program(shading, v, textures, nullptr, whole_map ? nullptr : &shadow_map_,
                                temporal_shadow_rows(s.frame, whole_map), tables_);
    shadow_map_ = program.shadow_map;
    shadow_map_key_ = map_key;
    std::vector<vec4> fresh(static_cast<std::size_t>(lw) * static_cast<std::size_t>(lh));
    std::vector<float> fresh_depth(fresh.size(), 0.0f);
    std::vector<pixel_program::reads> counts(fresh.size());
    (void)render_rows(lw, lh, threads, [&](int i, int j) {
        const std::size_t b = static_cast<std::size_t>(j) * static_cast<std::size_t>(lw) + static_cast<std::size_t>(i);
        fresh[b] = program.shade_linear(4 * i + int(offset.x), 4 * j + int(offset.y), w, h, &counts[b], &fresh_depth[b],
                                        nullptr, nullptr, true);
        return vec4(0.0f);
    });

    // The resolve pass (temporal_resolve.frag).
    const frame_constants k = make_frame_constants(s, tables_);
    const frame_constants pk = geometry_constants(has_history_ ? previous_ : s);  // its camera
    const vec3 motion = has_history_ ? vec3(s.wind.x - previous_.wind.x, s.camera_altitude - previous_.camera_altitude,
                                            s.wind.y - previous_.wind.y)
                                     : vec3(0.0f);
    const float aspect = float(w) / float(h);
    std::vector<vec4> color(color_.size());
    std::vector<vec2> aux(aux_.size());
    image display = render_rows(w, h, threads, [&](int x, int y) {
        const std::size_t b = static_cast<std::size_t>(y / 4) * static_cast<std::size_t>(lw) + static_cast<std::size_t>(x / 4);
        const bool is_fresh = (x & 3) == int(offset.x) && (y & 3) == int(offset.y);
        const float depth = fresh_depth[b] > 0.0f ? fresh_depth[b] : 1e7f;
        const vec3 dir = pixel_direction(k, x, y, w, h);
        // The background pass (clouds.frag's pass 3), at full resolution every frame: what
        // lies behind the layer, and whether the ray meets the cloud band at all.
        const vec3 behind = program.behind(dir);
        const vec2 stretch = program.view_stretch(dir);
        const vec3 uvz = cm::camera_project(dir * depth + motion, pk.forward, pk.right, pk.up, pk.tan_half_fov, aspect);
        bool valid = has_history_ && uvz.z > 0.0f && uvz.x >= 0.0f && uvz.x <= 1.0f && uvz.y >= 0.0f && uvz.y <= 1.0f;
        if (valid) {
            // The history there must be this pixel's: carried by its own motion (its nearest
            // texel's depth, the sky's at 1e7), it lands within temporal_reprojection_tolerance
            // of this pixel; else a cloud has moved in or out, and the new samples fill it.
            const int tx = std::clamp(int(uvz.x * float(w)), 0, w - 1), ty = std::clamp(int(uvz.y * float(h)), 0, h - 1);
            const float stored = aux_[static_cast<std::size_t>(ty) * static_cast<std::size_t>(w) + static_cast<std::size_t>(tx)].x;
            const vec2 ndc = vec2(uvz) * 2.0f - 1.0f;
            const vec3 was = glm::normalize(pk.forward + pk.right * (ndc.x * aspect * pk.tan_half_fov) + pk.up * (ndc.y * pk.tan_half_fov));
            // Under a metre is the sky's 0 blended by bilinear taps (a depth mixed across a cloud's
            // edge): the sky's infinity, not a point at the camera.
            const vec3 now = cm::camera_project(was * (stored >= 1.0f ? stored : 1e7f) - motion, k.forward, k.right, k.up,
                                                k.tan_half_fov, aspect);
            const vec2 miss(now.x * float(w) - (float(x) + 0.5f), now.y * float(h) - (float(y) + 0.5f));
            valid = now.z > 0.0f && glm::dot(miss, miss) <= temporal_reprojection_tolerance * temporal_reprojection_tolerance;
            // ... and lie in front of the scene there: a cloud the terrain now hides is not this
            // pixel's (the composite's use of the scene's depth; the march itself ends there).
            const float scene_t = terrain_distance(s, dir, nullptr);
            valid = valid && !(scene_t > 0.0f && stored > scene_t);
        }
        vec4 hc(0.0f);
        vec2 ha(0.0f);
        if (valid) {
            // Catmull-Rom taps clamped to the range of the bilinear ones (no ringing), the
            // depth and sample count bilinear.
            const vec4 fp = cm::texel_bilinear(vec2(uvz), vec2(float(w), float(h)));
            hc = catmull_rom_clamped(fp, w, h, color_);
            bilinear_taps(fp, w, h, [&](std::size_t ti, float weight) { ha += aux_[ti] * weight; });
        }
        // The fill (where it is needed): this frame's new samples (at 4 (i, j) + offset)
        // interpolated likewise.
        const auto fill = [&] {
            const vec2 q = (vec2(float(x), float(y)) - vec2(offset)) * 0.25f;
            return catmull_rom_clamped(vec4(std::floor(q.x), std::floor(q.y), q.x - std::floor(q.x), q.y - std::floor(q.y)),
                                       lw, lh, fresh);
        };
        vec4 c;
        vec2 a;
        if (is_fresh) {
            const float weight = valid ? cm::temporal_blend_weight(ha.y, float(max_samples_)) : 1.0f;
            c = glm::mix(hc, fresh[b], weight);
            a = vec2(fresh_depth[b], valid ? std::min(ha.y, float(max_samples_) - 1.0f) + 1.0f : 1.0f);
        } else if (valid && ha.y >= 0.5f) {
            c = hc;
            a = ha;
        } else if (valid) {
            // Not shaded yet (0 samples: filled): the fills of successive frames, each from
            // other pixels of the block, averaged until this pixel's own turn replaces them.
            c = glm::mix(hc, fill(), temporal_fill_blend);
            a = vec2(fresh_depth[b], 0.0f);
        } else {
            // No history (first frame, off the previous screen, or not this pixel's).
            c = fill();
            a = vec2(fresh_depth[b], 0.0f);
        }
        if (!(stretch.y > stretch.x)) c = vec4(0.0f);  // a ray that meets no cloud carries none
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        color[i] = c;
        aux[i] = a;
        // The composite (composite.frag): the new history over what lies behind it.
        return composite_display(behind, c, program.k.exposure, s.dither, x, y, s.frame);
    });
    color_.swap(color);
    aux_.swap(aux);
    previous_ = s;
    has_history_ = true;

    // The shaded pixels' reads (last_reads divides them by the in-layer pixels on demand).
    reads_view_ = reads_light_ = 0;
    for (const pixel_program::reads& r : counts) {
        reads_view_ += r.view;
        reads_light_ += r.light;
    }
    reads_shadow_map_ = program.shadow_map_reads;
    return display;
}

texture_read_stats cpu_temporal_renderer::last_reads() const {
    // Over the pixels of the last frame whose ray enters the layer (a segment test, no
    // texture read), counted here rather than in every frame.
    texture_read_stats st;
    st.shadow_map = reads_shadow_map_;
    if (!has_history_) return st;
    const frame_constants k = make_frame_constants(previous_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const vec3 dir = pixel_direction(k, x, y, width_, height_);
            const vec2 layer = cm::cloud_layer_segment(previous_.camera_altitude, dir.y, previous_.planet_radius,
                                                       previous_.layer_bottom, previous_.layer_top);
            if (layer.y > layer.x) ++st.pixels_in_layer;
        }
    const long total = reads_view_ + reads_light_;
    if (st.pixels_in_layer > 0) {
        st.mean = double(total) / double(st.pixels_in_layer);
        st.light_share = total > 0 ? double(reads_light_) / double(total) : 0.0;
        st.p95 = 0.0;  // per-pixel percentiles do not apply: 15 of 16 pixels read nothing
    }
    return st;
}

}  // namespace cloud_renderer
