// clouds.frag: the full-screen passes that ray-march a spherical cloud layer. Every piece of
// cloud math is a cloudmath GLSL function (cm_*); this file is the glue: the camera ray, the
// textures, the march loop and the switches between lighting variants. cpu_renderer.cpp is
// the same program in C++ with cloudmath's C++ functions, line for line.
//
// The host (gl_renderer.cpp) prepends, in this order:
//   #version 410 core
//   the permutation block (what engines ship: one program per variant, scene switches and
//     pass): `const int u_phase_model = 3;` ... for every CR_PARAM below and an empty
//     CR_PARAM, so that the compiler folds every switch and keeps only the permutation's own
//     paths (a pass that returns early does not carry the others' code: on SIMD hardware,
//     llvmpipe too, code after a uniform early return can still be paid for);
// and replaces the line `#include "cloudmath.glsl"` below with cloudmath::glsl_source().
// Frame and units: see scene.hpp (camera at the origin, +y up, metres).

// The permutation: the pass (below), the density field's shape (scene.hpp's cloud_shape: 0
// classic, 1 detailed), the lighting variant and what the picture draws besides the clouds:
// the constants of scene.hpp's two tables (CLOUD_RENDERER_VARIANT_TABLE,
// CLOUD_RENDERER_SCENE_SWITCHES; the dither is composite.frag's), which the host's block
// defines; ctest cloud_renderer.variant_table checks these lines against them.
CR_PARAM(int, u_pass)
CR_PARAM(int, u_shape)
CR_PARAM(int, u_phase_model)      // 0 HG, 1 dual-lobe HG, 2 Cornette-Shanks, 3 Mie fit
CR_PARAM(int, u_lighting)         // 0 Wrenninge octaves, 1 diffusion model (diffusion_lighting.glsl) with
                                  // CM_DIFFUSION_MODEL_CLOUDS, 2 with CM_DIFFUSION_MODEL_FITTED
CR_PARAM(int, u_octaves)          // Wrenninge octaves
CR_PARAM(int, u_powder)           // 0 off, 1 on
CR_PARAM(int, u_light_mode)       // toward the sun: 0 cone, 1 march over the cloud type's band, 2 shadow map
CR_PARAM(int, u_behind_mode)      // behind the sample (diffusion model): 0 cone, 1 march, 2 shadow map
CR_PARAM(int, u_light_steps)      // light march steps, quadratic (cm_light_march_distance), jittered
CR_PARAM(int, u_refine)           // at most this many sub-steps for a view step thicker than optical depth 1
CR_PARAM(int, u_integration)      // 0 energy-conserving (analytic), 1 naive Riemann sum
CR_PARAM(int, u_view_steps)
CR_PARAM(int, u_schedule)         // view steps: 0 uniform, 1 growing with distance
CR_PARAM(int, u_shadows)          // 0 off, 1 cloud shadows on the ground from the Beer shadow map (the scene's)
CR_PARAM(int, u_occluded_ambient) // sky light inside clouds: 0 flat, 1 through the optical depth above / below
CR_PARAM(int, u_reach)            // the march toward the sun: 0 (far) capped at u_light_march_max, then
                                  // cr_far_steps(u_light_steps) full-density steps to the band's end
                                  // (30 km at most); 1 (band) its steps stretched to the band's end
CR_PARAM(int, u_sun_disc)         // 0 no sun disc, 1 the disc at its physical radiance
CR_PARAM(int, u_haze)             // 0 off, 1 aerial perspective (air between camera and cloud)
CR_PARAM(int, u_terrain)          // 0 none, 1 the example's terrain (u_terrain_boxes): the march ends at it

// The frame's constants: one uniform block, laid out once (std140) and shared by the passes
// (scene.hpp's `scene` and `frame_constants`). The host fills it from a C++ struct of the same
// layout (frame_block.hpp, its offsets checked against the program's at link); the web demo
// from the offsets the program reports. Members keep the u_ names: the code reads them as it
// would plain uniforms. Each vec3 shares its 16 bytes with the float after it.
layout(std140) uniform CrFrame {
    vec3 u_forward; float u_tan_half_fov;
    vec3 u_right; float u_cam_altitude;
    vec3 u_up; float u_planet_radius;
    vec3 u_sun_dir; float u_layer_bottom;
    vec3 u_sun_radiance; float u_layer_top;
    vec3 u_ambient_top; float u_sun_angular_radius;
    vec3 u_ambient_bottom; float u_aureole;  // the glow around the sun: u_aureole u_sun_radiance HG(mu, 0.75)
    vec3 u_sky_zenith; float u_coverage;
    vec3 u_sky_horizon; float u_cloud_type;
    vec3 u_ground; float u_extinction;
    // The Beer shadow map's frame (scene.hpp).
    vec3 u_shadow_origin; float u_albedo;
    vec3 u_shadow_right; float u_max_distance;
    vec3 u_shadow_up; float u_shadow_half_extent;
    // The physical sky (read with CR_PHYSICAL_SKY): the aerial-perspective table's size (n_d,
    // n_az, n_el) and last distance; the far shadow's range (alt_lo, alt_hi, mu_lo, mu_hi).
    vec3 u_haze_table_size; float u_haze_table_distance;
    vec4 u_far_shadow_range;
    // The example's terrain (scene.hpp's terrain_boxes, with u_terrain): boxes standing on the
    // ground, each (x, z) of its centre relative to the camera's foot, half width, top altitude.
    vec4 u_terrain_boxes[4];
    vec3 u_sun_by_height[8];  // the physical sky's sun on the clouds by height in the layer (frame_constants::sun_by_height)
    vec2 u_resolution; vec2 u_band;  // the image; altitudes outside which the field has no density (cloud_band)
    vec2 u_wind; vec2 u_far_shadow_size;  // ...; the far shadow's n_alt, n_mu
    uvec2 u_update_offset; uint u_frame; float u_exposure;  // the temporal passes' pixel of each 4 x 4 block; ...;
                                                            // the frame's exposure (composite.frag's, kept with the frame)
    float u_base_tile, u_detail_tile, u_weather_tile, u_weather_wide_tile;
    float u_curl_tile, u_curl_strength, u_type_spread, u_top_rounding;
    float u_density_scale, u_phase_g, u_phase_g_back, u_phase_w;
    float u_droplet_diameter, u_ms_a, u_ms_b, u_ms_c;
    float u_phase_mean_cosine;  // the diffusion model's g for u_phase_model
    float u_cone_step, u_cone_spread, u_cone_far_distance;
    float u_cone_far_length, u_light_march_max, u_min_transmittance;
    float u_march_near_distance;  // growing view steps: nearly uniform closer than this
    float u_far_shadow_reach;   // pass 4: where the light march ends (far_shadow_table::reach)
    float u_far_shadow_period;  // pass 4: the field's horizontal period (the weather map's tile)
};

uniform sampler3D u_base;      // 128^3 RGBA8: Perlin-Worley + Worley fBm (noise_bake.hpp)
uniform sampler3D u_detail;    // 32^3 RGB8: Worley fBm
uniform sampler2D u_weather;   // 256^2 RGB8: R coverage (the classic shape reads only R)
uniform sampler2D u_weather_wide;  // 1024^2 RGB8: R coverage, G type, B top (the detailed shape)
uniform sampler2D u_curl;      // 128^2 RGB8: curl noise, curl_bake_encode
uniform sampler2D u_shadow_map;  // CR_SHADOW_MAP_SIZE^2 RGBA32F: (front, mean extinction, optical depth) of pass 2
#ifdef CR_PHYSICAL_SKY
// The physical sky's aerial perspective (physical_sky.hpp, defined by the host for
// sky_model::physical): the atmosphere's in-scattered radiance by the view's zenith cosine,
// its azimuth from the sun's and the distance, nodes in an (n_d n_az) x n_el RGB32F image.
uniform sampler2D u_haze_table;
// The background: the sky-view table at the camera (physical_sky.hpp), an n_az x n_el RGB32F image.
uniform sampler2D u_sky_view;
// The clouds' shadow beyond the light march (far_shadow.hpp): mean transmittance by altitude (x)
// and the sun's zenith cosine (y), an n_alt x n_mu R32F image.
uniform sampler2D u_far_shadow;
#endif

// The passes (u_pass): 4 (the physical sky only) the far shadow's table: output pixel (a, m) is
// node (a, m) (cr_far_shadow_texel). 0 the cloud layer at every pixel (the full frame). 1 the
// shading pass of the temporal scheme (temporal_resolve.frag), one pixel of every 4 x 4 block:
// the output pixel (i, j) shades the image's pixel (4 i, 4 j) + u_update_offset (u_resolution
// stays the full image's size). Both write the cloud layer alone: its premultiplied linear
// radiance (the aerial perspective over the cloud included), its opacity and the cloud's depth,
// which composite.frag lays over pass 3's background (the temporal resolve in between).
// 2 the Beer shadow map: output pixel (i, j) is texel (i, j) (cr_shadow_texel). 3 what lies
// behind the cloud layer (the sky, the ground, the terrain) and the scene's depth, at every pixel.
// u_pass is the permutation's first switch (CR_PARAM above): one program per pass.

layout(location = 0) out vec4 out_color;   // rgb: the layer's linear radiance (pass 3: what lies behind it);
                                           // a: cloud opacity (pass 3: 1 where the ray meets the band)
layout(location = 1) out float out_depth;  // passes 0 and 1: the cloud's transmittance-weighted distance, 0 for none;
                                           // pass 3: the scene's (the terrain's) distance, 0 for none

// cloudmath calls these back (declared before the include, defined below).
float cr_cone_extinction(vec3 p, int i);
float cr_phase(float mu, float scale);
#define CM_CONE_EXTINCTION cr_cone_extinction
#define CM_MS_PHASE cr_phase
#define CM_DIFFUSION_PHASE cr_phase
#include "cloudmath.glsl"

// The unit vertical at the camera-relative point p (away from the planet's centre).
vec3 cr_up(vec3 p) { return normalize(vec3(p.x, p.y + (u_planet_radius + u_cam_altitude), p.z)); }

// The sun on a cloud at height fraction h of the layer: with the physical sky, its
// illuminance by height (scene.cpp's sun_at_height); else the one sun_radiance.
#ifdef CR_PHYSICAL_SKY
vec3 cr_sun_at(float h) {
    float x = cm_saturate(h) * 7.0;
    int i = min(int(x), 6);
    return mix(u_sun_by_height[i], u_sun_by_height[i + 1], x - float(i));
}
// The far shadow at p (altitude `altitude`): far_shadow.cpp's far_shadow_lookup by the sun's
// zenith cosine at p, bilinear between texelFetch'd nodes.
float cr_far_shadow(vec3 p, float altitude) {
    ivec2 size = ivec2(u_far_shadow_size + 0.5);
    vec2 c = vec2(cm_saturate((altitude - u_far_shadow_range.x) / (u_far_shadow_range.y - u_far_shadow_range.x)),
                  cm_saturate((dot(u_sun_dir, cr_up(p)) - u_far_shadow_range.z) / (u_far_shadow_range.w - u_far_shadow_range.z))) *
             vec2(size - 1);
    ivec2 i = clamp(ivec2(c), ivec2(0), size - 2);
    vec2 f = clamp(c - vec2(i), 0.0, 1.0);
    float lower = mix(texelFetch(u_far_shadow, i, 0).r, texelFetch(u_far_shadow, i + ivec2(1, 0), 0).r, f.x);
    float upper = mix(texelFetch(u_far_shadow, i + ivec2(0, 1), 0).r, texelFetch(u_far_shadow, i + ivec2(1, 1), 0).r, f.x);
    return mix(lower, upper, f.y);
}
// The depth toward the sun the occluded sky light reads: with the physical sky the light
// estimate without its far field (near), which shades the sun but not the sky above the
// sample (cpu_renderer.cpp's sky_depth_toward_sun says why and what it measures).
float cr_sky_depth_toward_sun(float whole, float near) { return near; }
#else
vec3 cr_sun_at(float h) { return u_sun_radiance; }
float cr_far_shadow(vec3 p, float altitude) { return 1.0; }
// ... with the artistic sky the whole estimate, which its table was fitted with.
float cr_sky_depth_toward_sun(float whole, float near) { return whole; }
#endif

const int CR_CONE_SAMPLES = 6;             // scene.hpp's cone_samples
const float CR_LIGHT_LONG_REACH = 30000.0;  // ... light_long_reach

// scene.hpp's far_step_count: twice as many far steps as the near march (u_reach 0).
int cr_far_steps(int light_steps) { return light_steps < 2 ? 1 : 2 * light_steps; }
const int CR_SHADOW_MAP_SIZE = 128;      // scene.hpp's shadow_map_size
const int CR_SHADOW_MAP_STEPS = 24;      // ... shadow_map_steps
const float CR_GROUND_SKY_SHARE = 0.4;   // ... ground_sky_share

CmMieApproxParams cr_mie;  // set once per pixel in main()
vec2 cr_band;              // altitudes of the cloud type's band (no density outside), set in main()

// Altitude of a camera-relative point, without |p - centre| - R's cancellation.
float cr_altitude(vec3 p) { return cm_point_altitude(p, u_cam_altitude, u_planet_radius); }

// The base shape at p: the density before the detail erodes it (an upper bound of
// cr_density), from the weather map and the base volume only.
float cr_base_density(vec3 p, float altitude) {
    float h = cm_height_fraction(altitude, u_layer_bottom, u_layer_top);
    if (h <= 0.0 || h >= 1.0) return 0.0;
    vec3 q = vec3(p.x + u_wind.x, altitude, p.z + u_wind.y);
    if (u_shape == 1) {
        vec3 w = textureLod(u_weather_wide, q.xz / u_weather_wide_tile, 0.0).rgb;
        vec4 b = textureLod(u_base, q / u_base_tile, 0.0);
        return cm_cloud_shape_density(b, w, h, u_coverage, u_cloud_type, u_type_spread, u_top_rounding);
    }
    float coverage = cm_saturate(textureLod(u_weather, q.xz / u_weather_tile, 0.0).r - 0.5 + u_coverage);
    vec4 base = textureLod(u_base, q / u_base_tile, 0.0);
    float shaped = cm_nubis_base_cloud(base) * cm_height_gradient_for_type(h, u_cloud_type);
    return cm_apply_coverage(shaped, coverage);
}

// The detail's erosion of the base shape `covered` (cr_base_density's value at p): the Nubis
// density. The detail volume is read only where the base cloud survives coverage.
float cr_detail_density(vec3 p, float altitude, float covered) {
    if (covered <= 0.0) return 0.0;
    float h = cm_height_fraction(altitude, u_layer_bottom, u_layer_top);
    vec3 q = vec3(p.x + u_wind.x, altitude, p.z + u_wind.y);
    if (u_shape == 1) {
        // Curl noise displaces the detail, most at the cloud's base (wispy bases, billowy tops).
        vec3 curl = (2.0 * textureLod(u_curl, q.xz / u_curl_tile, 0.0).rgb - 1.0) * 4.0;  // curl_bake_decode
        q += curl * (u_curl_strength * (1.0 - h));
        vec3 d = textureLod(u_detail, q / u_detail_tile, 0.0).rgb;
        return cm_saturate(cm_erode(covered, cm_nubis_detail_erosion(d, h)) * u_density_scale);
    }
    vec3 detail = textureLod(u_detail, q / u_detail_tile, 0.0).rgb;
    return cm_erode(covered, cm_nubis_detail_erosion(detail, h));
}

// Nubis density at p (what cm_nubis_density computes in one call), base then detail.
float cr_density(vec3 p, float altitude) { return cr_detail_density(p, altitude, cr_base_density(p, altitude)); }

float cr_cone_extinction(vec3 p, int i) { return u_extinction * cr_density(p, cr_altitude(p)); }

// The phase model with eccentricities scaled by `scale` (c^i of octave i).
float cr_phase(float mu, float scale) {
    if (u_phase_model == 0) return cm_phase_hg(mu, scale * u_phase_g);
    if (u_phase_model == 1) return cm_phase_hg_dual(mu, scale * u_phase_g, scale * u_phase_g_back, u_phase_w);
    if (u_phase_model == 2) return cm_phase_cornette_shanks(mu, scale * u_phase_g);
    CmMieApproxParams m = cr_mie;
    m.g_hg *= scale;
    m.g_draine *= scale;
    return cm_phase_mie_approx(mu, m);
}

// The Beer shadow map's texel at uv: bilinear (cm_texel_bilinear), taps clamped to the map.
vec3 cr_shadow_lookup(vec2 uv) {
    vec4 fp = cm_texel_bilinear(uv, vec2(float(CR_SHADOW_MAP_SIZE)));
    vec3 texel = vec3(0.0);
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            ivec2 t = clamp(ivec2(fp.xy) + ivec2(dx, dy), ivec2(0), ivec2(CR_SHADOW_MAP_SIZE - 1));
            texel += texelFetch(u_shadow_map, t, 0).xyz * ((dx != 0 ? fp.z : 1.0 - fp.z) * (dy != 0 ? fp.w : 1.0 - fp.w));
        }
    return texel;
}

// Distance of fraction u of a light march of `length`: quadratic steps, short near the sample.
float cr_light_distance(float u, float length) { return cm_light_march_distance(u, length); }

// The last cr_light_optical_depth's depth without the far field (u_reach 0): the
// physical sky's occluded sky light reads it (cr_sky_depth_toward_sun).
float cr_light_near_tau = 0.0;

bool cr_on_map(vec3 uvd) { return uvd.x >= 0.0 && uvd.x <= 1.0 && uvd.y >= 0.0 && uvd.y <= 1.0; }

// Optical depth from p along the unit vector `toward` (the sun, or away from it for the
// diffusion model's tau_behind) by the cone (mode 0), a march (mode 1) to where the cloud
// type's altitude band ends (no density beyond it; quadratic steps, sampled at light_offset
// within each), or the shadow map (mode 2: toward the sun its optical depth at
// p's depth, away from it the rest of the column; off the map the cone). It sets
// cr_light_near_tau.
float cr_light_optical_depth(vec3 p, float altitude, vec3 toward, int mode, float light_offset) {
    if (mode == 2) {
        vec3 uvd = cm_shadow_map_project(p, u_shadow_origin, u_shadow_right, u_shadow_up, u_sun_dir, u_shadow_half_extent);
        if (cr_on_map(uvd)) {
            vec3 texel = cr_shadow_lookup(uvd.xy);
            float before = cm_beer_shadow_optical_depth(texel, uvd.z);
            cr_light_near_tau = dot(toward, u_sun_dir) > 0.0 ? before : max(texel.z - before, 0.0);
            return cr_light_near_tau;
        }
        mode = 0;
    }
    if (mode == 0) {
        CmConeLightConfig cone = CmConeLightConfig(CR_CONE_SAMPLES, u_cone_step, u_cone_spread,
                                                   u_cone_far_distance, u_cone_far_length);
        cr_light_near_tau = cm_cone_optical_depth(p, toward, cone);
        return cr_light_near_tau;
    }
    // March: midpoint steps up to where the ray leaves the cloud type's band.
    vec2 seg = cm_cloud_layer_segment(altitude, dot(toward, cr_up(p)), u_planet_radius, cr_band.x, cr_band.y);
    float reach = u_reach == 1 ? CR_LIGHT_LONG_REACH : u_light_march_max;
    float length_to_exit = seg.y > seg.x ? min(seg.y, reach) : 0.0;
    float n = float(u_light_steps);
    float tau = 0.0;
    for (int i = 0; i < u_light_steps; ++i) {
        float ds = cr_light_distance((float(i) + 1.0) / n, length_to_exit) - cr_light_distance(float(i) / n, length_to_exit);
        tau += cr_cone_extinction(p + toward * cr_light_distance((float(i) + light_offset) / n, length_to_exit), i) * ds;
    }
    cr_light_near_tau = tau;
    // The far field by steps (u_reach 0): toward the sun, the rest of the band beyond the
    // capped march, uniform steps on the full density.
    if (u_reach == 0 && seg.y > length_to_exit && dot(toward, u_sun_dir) > 0.0) {
        int nf = cr_far_steps(u_light_steps);
        float span = (min(seg.y, CR_LIGHT_LONG_REACH) - length_to_exit) / float(nf);
        for (int j = 0; j < nf; ++j) {
            vec3 q = p + toward * (length_to_exit + (float(j) + light_offset) * span);
            tau += u_extinction * cr_density(q, cr_altitude(q)) * span;
        }
    }
    return tau;
}

// Radiance scattered toward the camera per unit scattering coefficient: sunlight through
// the octaves or the diffusion model (phase and transmittance), the powder term, and
// isotropic sky light. tau_behind and tau_view are used by the diffusion model only; far: the
// far shadow's transmittance (cr_far_shadow), on the sun's light only; tau_sky: the depth
// toward the sun the occluded sky light reads (cr_sky_depth_toward_sun).
vec3 cr_in_scattering(float tau_light, float tau_behind, float tau_view, float mu, float h, float far, float tau_sky) {
    float sun = u_lighting == 1
        ? cm_diffusion_scattering_with(tau_light, tau_behind, tau_view, mu, u_phase_mean_cosine, u_albedo,
                                       CM_DIFFUSION_MODEL_CLOUDS)
        : u_lighting == 2
        ? cm_diffusion_scattering_with(tau_light, tau_behind, tau_view, mu, u_phase_mean_cosine, u_albedo,
                                       CM_DIFFUSION_MODEL_FITTED)
        : cm_multiple_scattering_with(tau_light, mu, u_ms_a, u_ms_b, u_ms_c, u_octaves);
    if (u_powder != 0) {
        // Schneider 2015's Beer-Powder factor 2 (1 - e^(-2 tau)), strongest looking away
        // from the sun and gone looking into it (where the dark edges are not seen).
        sun *= mix(2.0 * cm_powder(tau_light, 2.0), 1.0, 0.5 + 0.5 * mu);
    }
    if (u_occluded_ambient == 0) return cr_sun_at(h) * (sun * far) + mix(u_ambient_bottom, u_ambient_top, h);
    // Vertical optical depths above (x) and below (y) from the slanted light estimates times
    // the sun's elevation sine; with the sun below the horizon the estimate away from it looks
    // up (a uniform select: no divergence).
    vec2 depths = (u_sun_dir.y >= 0.0 ? vec2(tau_sky, tau_behind) : vec2(tau_behind, tau_sky)) * abs(u_sun_dir.y);
    return cr_sun_at(h) * (sun * far) + mix(u_ambient_bottom * cm_diffuse_transmittance(depths.y, u_phase_mean_cosine),
                                      u_ambient_top * cm_diffuse_transmittance(depths.x, u_phase_mean_cosine), h);
}

// Texel (i, j) of the Beer shadow map (pass 2): midpoint steps along the sunlight through the
// cloud type's band, depths from the map's plane.
vec3 cr_shadow_texel(vec2 ij) {
    vec2 ab = ((ij + 0.5) / float(CR_SHADOW_MAP_SIZE) * 2.0 - 1.0) * u_shadow_half_extent;
    vec3 p0 = u_shadow_origin + u_shadow_right * ab.x + u_shadow_up * ab.y;
    vec2 seg = cm_cloud_layer_segment(cr_altitude(p0), -dot(u_sun_dir, cr_up(p0)), u_planet_radius, cr_band.x, cr_band.y);
    CmBeerShadowAccumulator acc = cm_beer_shadow_accumulator();
    if (seg.y > seg.x) {
        float ds = (seg.y - seg.x) / float(CR_SHADOW_MAP_STEPS);
        for (int m = 0; m < CR_SHADOW_MAP_STEPS; ++m) {
            float t = seg.x + float(m) * ds;
            vec3 q = p0 - u_sun_dir * (t + 0.5 * ds);
            cm_beer_shadow_add_step(acc, t, ds, u_extinction * cr_density(q, cr_altitude(q)));
        }
    }
    return cm_beer_shadow_texel(acc);
}

#ifdef CR_PHYSICAL_SKY
// Node (a, m) of the far shadow's table (pass 4): far_shadow.cpp's node_mean, step for step.
// The mean over 12 x 12 stratified starts across the field's period of the transmittance of
// the sun's path beyond the light march (its stretches in the band after u_far_shadow_reach,
// 400 m steps, stopped past optical depth 9.2), 0 where the path meets the ground.
float cr_far_shadow_texel(ivec2 node) {
    ivec2 size = ivec2(u_far_shadow_size + 0.5);
    float lo = u_far_shadow_range.x, hi = u_far_shadow_range.y;
    float alt = lo + (hi - lo) * float(node.x) / float(size.x - 1);
    float mu = u_far_shadow_range.z + (u_far_shadow_range.w - u_far_shadow_range.z) * float(node.y) / float(size.y - 1);
    uint seed = uint(node.y * size.x + node.x) * 7919u;
    float R = u_planet_radius, r0 = u_planet_radius + u_cam_altitude;
    vec2 ground = cm_ray_sphere_intersect_altitude(alt, mu, R, 0.0);
    if (ground.x >= 0.0 && ground.y > ground.x) return 0.0;
    vec2 seg = cm_cloud_layer_segment(alt, mu, R, lo, hi);
    float start = seg.y > seg.x ? min(seg.y, u_far_shadow_reach) : 0.0;
    float end = cm_ray_sphere_intersect_altitude(alt, mu, R, hi).y;
    if (!(end > start)) return 1.0;
    vec2 dip = cm_ray_sphere_intersect_altitude(alt, mu, R, lo);
    bool dips = dip.x > 0.0 && dip.y > dip.x;
    vec2 stretches[2] = vec2[2](vec2(start, dips ? min(dip.x, end) : end), vec2(dips ? max(dip.y, start) : end, end));
    float sin_mu = sqrt(max(1.0 - mu * mu, 0.0));
    const int n = 12;  // far_shadow.hpp's far_shadow_grid
    float sum = 0.0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint h = cm_noise_hash(seed + uint(j * n + i));
            float x = u_far_shadow_period * ((float(i) + cm_sample_jitter(h, 0u, 0u)) / float(n) - 0.5);
            float z = u_far_shadow_period * ((float(j) + cm_sample_jitter(h, 0u, 1u)) / float(n) - 0.5);
            float jitter = cm_sample_jitter(h, 0u, 2u);
            vec3 up = normalize(vec3(x, r0, z));
            vec3 p = up * (R + alt) - vec3(0.0, r0, 0.0);
            vec3 across = u_sun_dir - up * dot(u_sun_dir, up);
            across = length(across) > 1e-6 ? normalize(across) : normalize(cross(up, vec3(0.0, 0.0, 1.0)));
            vec3 d = up * mu + across * sin_mu;
            float tau = 0.0;
            for (int k = 0; k < 2; ++k) {
                float len = stretches[k].y - stretches[k].x;
                if (!(len > 0.0) || tau > 9.2) continue;
                int steps = max(1, int(ceil(len / 400.0)));  // far_shadow.hpp's far_shadow_step
                float ds = len / float(steps);
                for (int m = 0; m < steps && tau <= 9.2; ++m) {
                    vec3 q = p + d * (stretches[k].x + (float(m) + jitter) * ds);
                    tau += u_extinction * cr_density(q, cr_altitude(q)) * ds;
                }
            }
            sum += exp(-tau);
        }
    return sum / float(n * n);
}
#endif

// The scene's opaque geometry along dir, what an engine's depth buffer holds: the distance to
// the nearest terrain box and its outward normal, or -1 (scene.cpp's terrain_distance). The
// cloud march ends there, and the background pass draws the box. An engine reads its depth
// buffer here instead (docs/integration.md).
float cr_scene_distance(vec3 dir, out vec3 normal) {
    normal = vec3(0.0, 1.0, 0.0);
    float nearest = -1.0;
    if (u_terrain == 0) return nearest;
    // Slabs from the camera (at the origin); a zero component is a tiny one of its sign.
    vec3 inv = vec3(dir.x < 0.0 ? -1.0 : 1.0, dir.y < 0.0 ? -1.0 : 1.0, dir.z < 0.0 ? -1.0 : 1.0) / max(abs(dir), vec3(1e-8));
    for (int i = 0; i < 4; ++i) {
        vec4 b = u_terrain_boxes[i];
        // From below the ground (the planet's curvature drops it 8 m at 10 km) to the top.
        vec3 t0 = vec3(b.x - b.z, -u_cam_altitude - 1000.0, b.y - b.z) * inv;
        vec3 t1 = vec3(b.x + b.z, b.w - u_cam_altitude, b.y + b.z) * inv;
        vec3 near = min(t0, t1), far = max(t0, t1);
        float enter = max(max(near.x, near.y), near.z), leave = min(min(far.x, far.y), far.z);
        if (enter > 0.0 && enter < leave && (nearest < 0.0 || enter < nearest)) {
            nearest = enter;
            normal = enter == near.x ? vec3(-sign(dir.x), 0.0, 0.0) : enter == near.y ? vec3(0.0, -sign(dir.y), 0.0) : vec3(0.0, 0.0, -sign(dir.z));
        }
    }
    return nearest;
}

// The sun's transmittance through the clouds at p from the shadow map (1 outside it).
float cr_sun_transmittance(vec3 p) {
    vec3 uvd = cm_shadow_map_project(p, u_shadow_origin, u_shadow_right, u_shadow_up, u_sun_dir, u_shadow_half_extent);
    return cr_on_map(uvd) ? cm_beer_shadow_transmittance(cr_shadow_lookup(uvd.xy), uvd.z) : 1.0;
}

// A terrain box's radiance at p, face normal n: Lambertian rock of albedo 0.25 lit by the sun
// through the clouds (with scene shadows) and by the sky light above and the ground's below,
// in the shares of the hemisphere the face sees (scene.cpp's terrain_radiance).
vec3 cr_terrain(vec3 p, vec3 n) {
    float sun = max(dot(n, u_sun_dir), 0.0) * (u_shadows != 0 ? cr_sun_transmittance(p) : 1.0);
    return (0.25 / CM_PI) * (u_sun_radiance * sun + CM_PI * mix(u_ground, u_ambient_top, 0.5 + 0.5 * n.y));
}

// What the shadow map leaves of the ground's light at ground point g: the sky's share plus
// the sun's times the clouds' transmittance (1 outside the map).
float cr_ground_shadow(vec3 g) {
    vec3 uvd = cm_shadow_map_project(g, u_shadow_origin, u_shadow_right, u_shadow_up, u_sun_dir, u_shadow_half_extent);
    if (!cr_on_map(uvd)) return 1.0;
    return mix(CR_GROUND_SKY_SHARE, 1.0, cm_beer_shadow_transmittance(cr_shadow_lookup(uvd.xy), uvd.z));
}

#ifdef CR_PHYSICAL_SKY
// Where a direction lies in the haze and sky-view tables, fractions in [0, 1]: x the azimuth
// from the sun's over pi, y 0.5 + 0.5 sign(mu) sqrt|mu| (physical_sky.cpp's sky_coordinates).
vec2 cr_sky_coordinates(vec3 dir) {
    float mu = clamp(dir.y, -1.0, 1.0);
    float h = length(dir.xz), hs = length(u_sun_dir.xz);
    float cos_phi = h > 1e-6 && hs > 1e-6 ? clamp(dot(dir.xz, u_sun_dir.xz) / (h * hs), -1.0, 1.0) : 1.0;
    return vec2(acos(cos_phi) / CM_PI, 0.5 + 0.5 * sign(mu) * sqrt(abs(mu)));
}

// The air's light between the camera and `distance` along dir: physical_sky.cpp's haze_lookup.
vec3 cr_haze_node(int d, int az, int el, ivec3 size) { return texelFetch(u_haze_table, ivec2(d + size.x * az, el), 0).rgb; }
vec3 cr_haze(vec3 dir, float distance) {
    ivec3 size = ivec3(u_haze_table_size + 0.5);
    vec2 c = cr_sky_coordinates(dir) * vec2(size.yz - 1);
    float d = sqrt(clamp(distance / u_haze_table_distance, 0.0, 1.0)) * float(size.x - 1);
    ivec3 i0 = clamp(ivec3(vec3(d, c)), ivec3(0), size - 2);
    vec3 f = clamp(vec3(d, c) - vec3(i0), 0.0, 1.0);
    vec3 r00 = mix(cr_haze_node(i0.x, i0.y, i0.z, size), cr_haze_node(i0.x + 1, i0.y, i0.z, size), f.x);
    vec3 r10 = mix(cr_haze_node(i0.x, i0.y + 1, i0.z, size), cr_haze_node(i0.x + 1, i0.y + 1, i0.z, size), f.x);
    vec3 r01 = mix(cr_haze_node(i0.x, i0.y, i0.z + 1, size), cr_haze_node(i0.x + 1, i0.y, i0.z + 1, size), f.x);
    vec3 r11 = mix(cr_haze_node(i0.x, i0.y + 1, i0.z + 1, size), cr_haze_node(i0.x + 1, i0.y + 1, i0.z + 1, size), f.x);
    return mix(mix(r00, r10, f.y), mix(r01, r11, f.y), f.z);
}

// The sky's radiance in direction dir: physical_sky.cpp's sky_view_lookup.
vec3 cr_sky_view(vec3 dir) {
    ivec2 size = textureSize(u_sky_view, 0);
    vec2 c = cr_sky_coordinates(dir) * vec2(size - 1);
    ivec2 i0 = clamp(ivec2(c), ivec2(0), size - 2);
    vec2 f = clamp(c - vec2(i0), 0.0, 1.0);
    vec3 lower = mix(texelFetch(u_sky_view, i0, 0).rgb, texelFetch(u_sky_view, i0 + ivec2(1, 0), 0).rgb, f.x);
    vec3 upper = mix(texelFetch(u_sky_view, i0 + ivec2(0, 1), 0).rgb, texelFetch(u_sky_view, i0 + ivec2(1, 1), 0).rgb, f.x);
    return mix(lower, upper, f.y);
}
#endif

vec3 cr_background(vec3 dir) {
    vec3 normal;
    float scene = cr_scene_distance(dir, normal);
    if (scene > 0.0) return cr_terrain(dir * scene, normal);
    vec2 ground = cm_ray_sphere_intersect_altitude(u_cam_altitude, dir.y, u_planet_radius, 0.0);
    if (ground.x >= 0.0 && ground.y > ground.x) return u_shadows != 0 ? u_ground * cr_ground_shadow(dir * ground.x) : u_ground;
    float mu = dot(dir, u_sun_dir);
#ifdef CR_PHYSICAL_SKY
    vec3 sky = cr_sky_view(dir);  // the atmosphere's sky, its glow toward the sun included
#else
    vec3 sky = mix(u_sky_horizon, u_sky_zenith, sqrt(cm_saturate(dir.y)));
    sky += u_sun_radiance * (u_aureole * cm_phase_hg(mu, 0.75));  // glow around the sun
#endif
    if (u_sun_disc != 0) sky += u_sun_radiance * cm_sun_disc_radiance(1.0, mu, u_sun_angular_radius, 0.6);  // physical disc
    return sky;
}

// A view sample in cloud, recorded by the march for the light pass (cr_light_samples).
struct CrLitSample {
    float t;              // distance along the view ray
    float sigma_t;        // extinction
    float ds;             // length of its step
    float tau_view;       // optical depth from the camera to the step's middle
    float transmittance;  // the view's transmittance in front of the step
};
const int CR_LIT_SAMPLES = 32;  // scene.hpp's lit_samples
CrLitSample cr_lit[CR_LIT_SAMPLES];

// The light pass: the light estimates of the samples the march recorded, in its order, and
// each one's source added to `luminance` with its transmittance (the same sums as lighting
// each sample inside the view loop; out of it, no group of pixels pays a light march for a
// view step that only some of them spend in cloud).
void cr_light_samples(inout vec3 luminance, int count, vec3 dir, float mu, uint pixel_hash, inout uint light_index) {
    for (int k = 0; k < count; ++k) {
        CrLitSample q = cr_lit[k];
        float alts = cm_altitude_along_ray(u_cam_altitude, dir.y, u_planet_radius, q.t);
        // The light march's offset: new for each light estimate and frame.
        float lo = cm_sample_jitter(pixel_hash, u_frame, light_index++);
        float tau_light = cr_light_optical_depth(dir * q.t, alts, u_sun_dir, u_light_mode, lo);
        float tau_sky = cr_sky_depth_toward_sun(tau_light, cr_light_near_tau);
        float tau_behind = u_lighting != 0 ? cr_light_optical_depth(dir * q.t, alts, -u_sun_dir, u_behind_mode, lo) : 0.0;
        float h = cm_height_fraction(alts, u_layer_bottom, u_layer_top);
        vec3 S = (u_albedo * q.sigma_t) * cr_in_scattering(tau_light, tau_behind, q.tau_view, mu, h, cr_far_shadow(dir * q.t, alts), tau_sky);
        // Energy-conserving (cm_march_add_segment's source term), or the textbook Riemann sum,
        // kept as a variant to show its error: the source at full strength over the whole
        // step, ignoring the decay within it.
        luminance += u_integration == 0 ? vec3(q.transmittance) * cm_integrate_scattering(S, q.sigma_t, q.ds)
                                        : vec3(q.transmittance) * S * q.ds;
    }
}

// Distance of fraction u of the view march over [t0, t1] (scene.hpp's step_schedule).
float cr_march_distance(float u, float t0, float t1) {
    return u_schedule == 1 ? cm_march_schedule_distance(u, t0, t1, u_march_near_distance) : t0 + u * (t1 - t0);
}

// The pixel's hash: the march's start offset is it advanced by R1 each frame
// (cm_frame_jitter), the light marches' offsets by their index too (cm_sample_jitter).
uint cr_pixel_hash(vec2 pixel) { return cm_noise_hash(uint(pixel.x) + uint(pixel.y) * 8192u); }

void main() {
    // The centre of the image pixel this invocation shades.
    vec2 pixel = u_pass == 1 ? floor(gl_FragCoord.xy) * 4.0 + vec2(u_update_offset) + 0.5 : gl_FragCoord.xy;
    vec2 ndc = pixel / u_resolution * 2.0 - 1.0;
    float aspect = u_resolution.x / u_resolution.y;
    vec3 dir = normalize(u_forward + u_right * (ndc.x * aspect * u_tan_half_fov) + u_up * (ndc.y * u_tan_half_fov));
    // The classic shape's band is the cloud type's range (what scene.cpp's cloud_band gives
    // for it, computed here so that hosts without u_band, the web demo, need not).
    cr_band = u_shape == 1 ? u_band : cm_height_range_for_type(u_cloud_type) * (u_layer_top - u_layer_bottom) + u_layer_bottom;
    if (u_pass == 2) {
        out_color = vec4(cr_shadow_texel(floor(gl_FragCoord.xy)), 0.0);
        out_depth = 0.0;
        return;
    }
#ifdef CR_PHYSICAL_SKY
    if (u_pass == 4) {
        out_color = vec4(cr_far_shadow_texel(ivec2(gl_FragCoord.xy)), 0.0, 0.0, 0.0);
        out_depth = 0.0;
        return;
    }
#endif

    // The view stretch: from where the ray enters the layer, at most u_max_distance. The
    // march covers the part of it inside the cloud type's altitude band (no density outside).
    vec2 layer = cm_cloud_layer_segment(u_cam_altitude, dir.y, u_planet_radius, u_layer_bottom, u_layer_top);
    vec2 in_band = cm_cloud_layer_segment(u_cam_altitude, dir.y, u_planet_radius, cr_band.x, cr_band.y);
    vec2 seg = vec2(max(layer.x, in_band.x), min(min(layer.y, layer.x + u_max_distance), in_band.y));
    vec3 scene_normal;
    float scene = cr_scene_distance(dir, scene_normal);
    if (scene > 0.0) seg.y = min(seg.y, scene);  // the scene's geometry hides what lies behind it
    if (u_pass == 3) {
        // The background, at full resolution every frame: what lies behind the cloud layer, and
        // whether the ray meets the band at all (a ray that does not carries no cloud: the
        // temporal resolve's test). The composite lays the layer (for the temporal scheme, the
        // reprojected one) over it, so the sky, the ground and the clouds' moving shadows on
        // it never lag.
        out_color = vec4(cr_background(dir), seg.y > seg.x ? 1.0 : 0.0);
        out_depth = max(scene, 0.0);  // the scene's depth (0: none), for the resolve
        return;
    }

    cr_mie = cm_mie_approx_params(u_droplet_diameter);  // after the passes that light nothing
    CmMarchAccumulator acc = cm_march_accumulator();
    float cloud_depth = 0.0;  // transmittance-weighted distance of the cloud, 0 for none
    if (seg.y > seg.x) {
        float t1 = seg.y;
        uint pixel_hash = cr_pixel_hash(pixel);
        float offset = cm_frame_jitter(pixel_hash, u_frame);
        float mu = dot(dir, u_sun_dir);
        float n = float(u_view_steps);
        float tau_view = 0.0;  // optical depth from the camera to the start of the step
        float depth_sum = 0.0;      // sum of each step's opacity times its distance
        float step_begin = seg.x;   // = cr_march_distance(0)
        float step_end = seg.x;     // the end of view step i, once its sample is taken
        bool after_empty = true;    // no cloud since the last empty sample (or the start)
        float last_empty = -1.0;    // the last view sample with no cloud
        uint light_index = 0u;      // light estimates so far (their jitter's index)
        // The march is one flat loop with one density sample per turn: view step i's sample
        // or sub-step m of the refined step i (u_refine: a step thicker than optical depth 1 is
        // marched again in `sub` sub-steps of length sub_ds from sub_from, the last empty sample
        // when it is the first step in cloud; its own sample then only told that it has cloud).
        // No loop is nested in it.
        int i = 0, m = 0, sub = 0;
        float sub_from = 0.0, sub_ds = 0.0;
        bool opaque = false;
        for (;;) {
            // March, recording the samples in cloud, until the buffer is full, the ray has
            // left the band or the cloud is opaque; then light them; go on if the buffer was full.
            int count = 0;
            while (!opaque && count < CR_LIT_SAMPLES && (m < sub || i < u_view_steps)) {
                bool refining = m < sub;
                float t = refining ? sub_from + (float(m) + offset) * sub_ds : cr_march_distance((float(i) + offset) / n, seg.x, t1);
                float altitude = cm_altitude_along_ray(u_cam_altitude, dir.y, u_planet_radius, t);
                float density = cr_density(dir * t, altitude);
                float ds;
                if (refining) {
                    ds = sub_ds;
                    if (++m == sub) {
                        step_begin = step_end;
                        ++i;
                    }
                    if (density <= 0.0) continue;
                } else {
                    step_end = cr_march_distance((float(i) + 1.0) / n, seg.x, t1);
                    if (density <= 0.0) {
                        last_empty = t;
                        step_begin = step_end;
                        after_empty = true;
                        ++i;
                        continue;
                    }
                    float r0 = after_empty && last_empty >= 0.0 ? last_empty : step_begin;
                    int n_sub = cm_refine_substeps(u_extinction * density * (step_end - r0), u_refine);
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
                float sigma_t = u_extinction * density;
                float before = acc.transmittance.r;  // grey extinction: every channel alike
                cr_lit[count++] = CrLitSample(t, sigma_t, ds, tau_view + 0.5 * sigma_t * ds, before);
                tau_view += sigma_t * ds;
                acc.transmittance *= cm_beer_lambert(sigma_t * ds);
                depth_sum += (before - acc.transmittance.r) * t;
                opaque = cm_march_is_opaque(acc, u_min_transmittance);
            }
            cr_light_samples(acc.luminance, count, dir, mu, pixel_hash, light_index);
            if (opaque || count < CR_LIT_SAMPLES) break;
        }
        // Aerial perspective at the cloud's transmittance-weighted depth: the air dims its
        // light and adds the horizon's haze in proportion to its opacity.
        float opacity = 1.0 - acc.transmittance.r;
        if (opacity > 0.0) cloud_depth = depth_sum / opacity;
        if (u_haze != 0 && opacity > 0.0) {
            vec3 tau_air = cm_air_optical_depth(u_cam_altitude, dir.y, depth_sum / opacity);
#ifdef CR_PHYSICAL_SKY
            acc.luminance = acc.luminance * exp(-tau_air) + cr_haze(dir, depth_sum / opacity) * opacity;
#else
            acc.luminance = cm_aerial_perspective(acc.luminance, u_sky_horizon * opacity, tau_air);
#endif
        }
    }
    float alpha = 1.0 - (acc.transmittance.r + acc.transmittance.g + acc.transmittance.b) / 3.0;
    out_depth = cloud_depth;
    out_color = vec4(acc.luminance, alpha);  // the layer alone: pass 3 gives what lies behind it
}
