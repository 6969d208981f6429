// clouds.wgsl: clouds.frag in WGSL, line for line, and composite.frag as a second fragment entry
// point (cr_composite). It mirrors clouds.frag (the same functions
// in the same order, the same names, the same arithmetic); read clouds.frag for the comments
// on what each piece does. Every piece of cloud math is a cloudmath WGSL function (cm_*,
// include/cloudmath/wgsl/, generated from the GLSL twins).
//
// The host (web/demo/webgpu.js) puts in front of it include/cloudmath/wgsl/cloudmath.wgsl (the
// library without hooks) and the *_hooks.wgsl files (cm_cone_optical_depth,
// cm_multiple_scattering_with, cm_diffusion_scattering_with), which call the hooks defined
// below; the variant switches are pipeline-overridable constants (webgpu.js makes one pipeline per
// permutation, as the desktop renderer compiles one program per permutation).
//
// What differs from clouds.frag, all forced by WGSL:
// - Uniforms are the members of one uniform struct, U, with the GLSL names: u_x is U.u_x.
//   The variant switches (CR_PARAM) are `override` constants with the GLSL names.
// - Each sampler2D / sampler3D is a texture and a sampler binding (u_x, u_x_sampler);
//   textureLod -> textureSampleLevel, textureSize(t, 0) -> textureDimensions(t),
//   texelFetch -> textureLoad. u_shadow_map (RGBA32F, read with textureLoad only) has no sampler.
// - The hooks have fixed names: cm_cone_extinction (CM_CONE_EXTINCTION), cm_ms_phase
//   (CM_MS_PHASE) and cm_diffusion_phase (CM_DIFFUSION_PHASE) call cr_cone_extinction and
//   cr_phase.
// - gl_FragCoord has its origin at the bottom left, WebGPU's position at the top left:
//   cr_fragment and cr_composite flip y (frag_coord) so that every pixel gets the same ray,
//   jitter and dither as in GLSL.
// - cr_fragment's outputs are a struct (location 0 colour, location 1 depth); cr_composite
//   returns its colour alone.
// - No ?: operator: select() where both sides are cheap and free of side effects, if/else
//   otherwise (light_index++ is a statement of its own). Function parameters are immutable
//   (cr_light_optical_depth copies `mode`); `from` is a reserved word (from_); overloaded
//   cm_ functions carry their type suffix (cm_aerial_perspective_v3v3v3,
//   cm_integrate_scattering_v3ff), in/out values are passed as pointers (&acc.luminance, &light_index).
// - Globals set per pixel are var<private>.
// - clouds.frag's #ifdef CR_PHYSICAL_SKY sections are branches on the override u_physical_sky
//   (folded per pipeline); their three tables are bound in both skies (1 x 1 stand-ins when the
//   sky is artistic), read with textureLoad only.

// The permutation (clouds.frag's CR_PARAM lines): pipeline-overridable constants, one pipeline
// per variant and density field, so the compiler folds every switch (values in scene.hpp's
// `variant`; u_shape 0 classic, 1 detailed).
override u_pass: i32;
override u_shape: i32;
override u_phase_model: i32;
override u_lighting: i32;
override u_octaves: i32;
override u_powder: i32;
override u_light_mode: i32;
override u_behind_mode: i32;
override u_light_steps: i32;
override u_refine: i32;
override u_integration: i32;
override u_view_steps: i32;
override u_schedule: i32;
override u_shadows: i32;
override u_occluded_ambient: i32;
override u_reach: i32;
override u_sun_disc: i32;
override u_haze: i32;
override u_dither: i32;  // composite.frag's switch: read by cr_composite only
override u_terrain: i32;
// clouds.frag's #define CR_PHYSICAL_SKY (the host's sky_model::physical): 1 the physical sky's
// tables and sun by height, 0 the artistic sky.
override u_physical_sky: i32;

struct CrUniforms {
    // The scene (scene.hpp's `scene` and `frame_constants`).
    u_resolution: vec2f,
    u_forward: vec3f, u_right: vec3f, u_up: vec3f,
    u_tan_half_fov: f32,
    u_cam_altitude: f32, u_planet_radius: f32, u_layer_bottom: f32, u_layer_top: f32,
    u_sun_dir: vec3f, u_sun_radiance: vec3f, u_ambient_top: vec3f, u_ambient_bottom: vec3f,
    u_sky_zenith: vec3f, u_sky_horizon: vec3f, u_ground: vec3f,
    u_sun_angular_radius: f32,
    u_aureole: f32,  // the glow around the sun: u_aureole u_sun_radiance HG(mu, 0.75)
    u_coverage: f32, u_cloud_type: f32, u_extinction: f32, u_albedo: f32, u_max_distance: f32,
    u_base_tile: f32, u_detail_tile: f32, u_weather_tile: f32,
    u_weather_wide_tile: f32, u_curl_tile: f32, u_curl_strength: f32, u_type_spread: f32, u_top_rounding: f32, u_density_scale: f32,
    u_band: vec2f,
    u_wind: vec2f,
    u_frame: u32,
    u_exposure: f32,
    u_phase_g: f32, u_phase_g_back: f32, u_phase_w: f32, u_droplet_diameter: f32,
    u_ms_a: f32, u_ms_b: f32, u_ms_c: f32,
    u_phase_mean_cosine: f32,
    u_cone_step: f32, u_cone_spread: f32, u_cone_far_distance: f32, u_cone_far_length: f32,
    u_light_march_max: f32, u_min_transmittance: f32,
    u_march_near_distance: f32,
    u_shadow_origin: vec3f, u_shadow_right: vec3f, u_shadow_up: vec3f,
    u_shadow_half_extent: f32,
    u_update_offset: vec2u,
    // The physical sky (clouds.frag's CR_PHYSICAL_SKY uniforms; unused with u_physical_sky 0).
    u_haze_table_size: vec3f,  // n_d, n_az, n_el
    u_haze_table_distance: f32,
    u_far_shadow_size: vec2f,  // n_alt, n_mu
    u_far_shadow_range: vec4f,  // alt_lo, alt_hi, mu_lo, mu_hi
    u_far_shadow_reach: f32,  // clouds.frag's pass 4 only (the table's drawing), which WebGPU takes from WebGL2
    u_far_shadow_period: f32,
    u_sun_by_height: array<vec3f, 8>,  // the sun on the clouds by height in the layer
    // The example's terrain (with u_terrain): each box's (x, z) of its centre, half width, top.
    u_terrain_boxes: array<vec4f, 4>,
}

@group(0) @binding(0) var<uniform> U: CrUniforms;
@group(0) @binding(1) var u_base: texture_3d<f32>;
@group(0) @binding(2) var u_base_sampler: sampler;
@group(0) @binding(3) var u_detail: texture_3d<f32>;
@group(0) @binding(4) var u_detail_sampler: sampler;
@group(0) @binding(5) var u_weather: texture_2d<f32>;
@group(0) @binding(6) var u_weather_sampler: sampler;
@group(0) @binding(7) var u_weather_wide: texture_2d<f32>;
@group(0) @binding(8) var u_weather_wide_sampler: sampler;
@group(0) @binding(9) var u_curl: texture_2d<f32>;
@group(0) @binding(10) var u_curl_sampler: sampler;
@group(0) @binding(11) var u_shadow_map: texture_2d<f32>;  // RGBA32F, textureLoad only
// The physical sky's tables (RGBA32F, textureLoad only): aerial perspective, sky view, far shadow.
@group(0) @binding(12) var u_haze_table: texture_2d<f32>;
@group(0) @binding(13) var u_sky_view: texture_2d<f32>;
@group(0) @binding(14) var u_far_shadow: texture_2d<f32>;
// composite.frag's inputs (cr_composite's pipeline only): the layer (pass 0) and what lies behind
// it (pass 3), RGBA32F, textureLoad only.
@group(1) @binding(0) var u_layer: texture_2d<f32>;
@group(1) @binding(1) var u_background: texture_2d<f32>;

struct CrOutput {
    @location(0) out_color: vec4f,
    @location(1) out_depth: f32,
}

// cloudmath calls these back (clouds.frag's #define CM_CONE_EXTINCTION cr_cone_extinction ...).
fn cm_cone_extinction(p: vec3f, i: i32) -> f32 { return cr_cone_extinction(p, i); }
fn cm_ms_phase(mu: f32, scale: f32) -> f32 { return cr_phase(mu, scale); }
fn cm_diffusion_phase(mu: f32, scale: f32) -> f32 { return cr_phase(mu, scale); }

fn cr_up(p: vec3f) -> vec3f { return normalize(vec3f(p.x, p.y + (U.u_planet_radius + U.u_cam_altitude), p.z)); }

fn cr_sun_at(h: f32) -> vec3f {
    if (u_physical_sky == 0) { return U.u_sun_radiance; }
    let x = cm_saturate(h) * 7.0;
    let i = min(i32(x), 6);
    return mix(U.u_sun_by_height[i], U.u_sun_by_height[i + 1], x - f32(i));
}

fn cr_far_shadow(p: vec3f, altitude: f32) -> f32 {
    if (u_physical_sky == 0) { return 1.0; }
    let size = vec2i(U.u_far_shadow_size + 0.5);
    let c = vec2f(cm_saturate((altitude - U.u_far_shadow_range.x) / (U.u_far_shadow_range.y - U.u_far_shadow_range.x)),
                  cm_saturate((dot(U.u_sun_dir, cr_up(p)) - U.u_far_shadow_range.z) / (U.u_far_shadow_range.w - U.u_far_shadow_range.z))) *
            vec2f(size - 1);
    let i = clamp(vec2i(c), vec2i(0), size - 2);
    let f = clamp(c - vec2f(i), vec2f(0.0), vec2f(1.0));
    let lower = mix(textureLoad(u_far_shadow, i, 0).r, textureLoad(u_far_shadow, i + vec2i(1, 0), 0).r, f.x);
    let upper = mix(textureLoad(u_far_shadow, i + vec2i(0, 1), 0).r, textureLoad(u_far_shadow, i + vec2i(1, 1), 0).r, f.x);
    return mix(lower, upper, f.y);
}

fn cr_sky_depth_toward_sun(whole: f32, near: f32) -> f32 { return select(whole, near, u_physical_sky != 0); }

const CR_CONE_SAMPLES = 6;
const CR_LIGHT_LONG_REACH = 30000.0;
fn cr_far_steps(light_steps: i32) -> i32 { return select(2 * light_steps, 1, light_steps < 2); }
const CR_SHADOW_MAP_SIZE = 128;
const CR_SHADOW_MAP_STEPS = 24;
const CR_GROUND_SKY_SHARE = 0.4;

var<private> cr_mie: CmMieApproxParams;
var<private> cr_band: vec2f;

fn cr_altitude(p: vec3f) -> f32 { return cm_point_altitude(p, U.u_cam_altitude, U.u_planet_radius); }

fn cr_base_density(p: vec3f, altitude: f32) -> f32 {
    let h = cm_height_fraction(altitude, U.u_layer_bottom, U.u_layer_top);
    if (h <= 0.0 || h >= 1.0) { return 0.0; }
    let q = vec3f(p.x + U.u_wind.x, altitude, p.z + U.u_wind.y);
    if (u_shape == 1) {
        let w = textureSampleLevel(u_weather_wide, u_weather_wide_sampler, q.xz / U.u_weather_wide_tile, 0.0).rgb;
        let b = textureSampleLevel(u_base, u_base_sampler, q / U.u_base_tile, 0.0);
        return cm_cloud_shape_density(b, w, h, U.u_coverage, U.u_cloud_type, U.u_type_spread, U.u_top_rounding);
    }
    let coverage = cm_saturate(textureSampleLevel(u_weather, u_weather_sampler, q.xz / U.u_weather_tile, 0.0).r - 0.5 + U.u_coverage);
    let base = textureSampleLevel(u_base, u_base_sampler, q / U.u_base_tile, 0.0);
    let shaped = cm_nubis_base_cloud(base) * cm_height_gradient_for_type(h, U.u_cloud_type);
    return cm_apply_coverage(shaped, coverage);
}

fn cr_detail_density(p: vec3f, altitude: f32, covered: f32) -> f32 {
    if (covered <= 0.0) { return 0.0; }
    let h = cm_height_fraction(altitude, U.u_layer_bottom, U.u_layer_top);
    var q = vec3f(p.x + U.u_wind.x, altitude, p.z + U.u_wind.y);
    if (u_shape == 1) {
        let curl = (2.0 * textureSampleLevel(u_curl, u_curl_sampler, q.xz / U.u_curl_tile, 0.0).rgb - 1.0) * 4.0;  // curl_bake_decode
        q += curl * (U.u_curl_strength * (1.0 - h));
        let d = textureSampleLevel(u_detail, u_detail_sampler, q / U.u_detail_tile, 0.0).rgb;
        return cm_saturate(cm_erode(covered, cm_nubis_detail_erosion(d, h)) * U.u_density_scale);
    }
    let detail = textureSampleLevel(u_detail, u_detail_sampler, q / U.u_detail_tile, 0.0).rgb;
    return cm_erode(covered, cm_nubis_detail_erosion(detail, h));
}

fn cr_density(p: vec3f, altitude: f32) -> f32 { return cr_detail_density(p, altitude, cr_base_density(p, altitude)); }

fn cr_cone_extinction(p: vec3f, i: i32) -> f32 { return U.u_extinction * cr_density(p, cr_altitude(p)); }

fn cr_phase(mu: f32, scale: f32) -> f32 {
    if (u_phase_model == 0) { return cm_phase_hg(mu, scale * U.u_phase_g); }
    if (u_phase_model == 1) { return cm_phase_hg_dual(mu, scale * U.u_phase_g, scale * U.u_phase_g_back, U.u_phase_w); }
    if (u_phase_model == 2) { return cm_phase_cornette_shanks(mu, scale * U.u_phase_g); }
    var m = cr_mie;
    m.g_hg *= scale;
    m.g_draine *= scale;
    return cm_phase_mie_approx(mu, m);
}

fn cr_shadow_lookup(uv: vec2f) -> vec3f {
    let fp = cm_texel_bilinear(uv, vec2f(f32(CR_SHADOW_MAP_SIZE)));
    var texel = vec3f(0.0);
    for (var dy = 0; dy < 2; dy++) {
        for (var dx = 0; dx < 2; dx++) {
            let t = clamp(vec2i(fp.xy) + vec2i(dx, dy), vec2i(0), vec2i(CR_SHADOW_MAP_SIZE - 1));
            texel += textureLoad(u_shadow_map, t, 0).xyz * (select(1.0 - fp.z, fp.z, dx != 0) * select(1.0 - fp.w, fp.w, dy != 0));
        }
    }
    return texel;
}

fn cr_light_distance(u: f32, length: f32) -> f32 { return cm_light_march_distance(u, length); }

fn cr_on_map(uvd: vec3f) -> bool { return uvd.x >= 0.0 && uvd.x <= 1.0 && uvd.y >= 0.0 && uvd.y <= 1.0; }

var<private> cr_light_near_tau: f32 = 0.0;

fn cr_light_optical_depth(p: vec3f, altitude: f32, toward: vec3f, mode_in: i32, light_offset: f32) -> f32 {
    var mode = mode_in;
    if (mode == 2) {
        let uvd = cm_shadow_map_project(p, U.u_shadow_origin, U.u_shadow_right, U.u_shadow_up, U.u_sun_dir, U.u_shadow_half_extent);
        if (cr_on_map(uvd)) {
            let texel = cr_shadow_lookup(uvd.xy);
            let before = cm_beer_shadow_optical_depth(texel, uvd.z);
            cr_light_near_tau = select(max(texel.z - before, 0.0), before, dot(toward, U.u_sun_dir) > 0.0);
            return cr_light_near_tau;
        }
        mode = 0;
    }
    if (mode == 0) {
        let cone = CmConeLightConfig(CR_CONE_SAMPLES, U.u_cone_step, U.u_cone_spread,
                                     U.u_cone_far_distance, U.u_cone_far_length);
        cr_light_near_tau = cm_cone_optical_depth(p, toward, cone);
        return cr_light_near_tau;
    }
    let seg = cm_cloud_layer_segment(altitude, dot(toward, cr_up(p)), U.u_planet_radius, cr_band.x, cr_band.y);
    let reach = select(U.u_light_march_max, CR_LIGHT_LONG_REACH, u_reach == 1);
    let length_to_exit = select(0.0, min(seg.y, reach), seg.y > seg.x);
    let n = f32(u_light_steps);
    var tau = 0.0;
    for (var i = 0; i < u_light_steps; i++) {
        let ds = cr_light_distance((f32(i) + 1.0) / n, length_to_exit) - cr_light_distance(f32(i) / n, length_to_exit);
        tau += cr_cone_extinction(p + toward * cr_light_distance((f32(i) + light_offset) / n, length_to_exit), i) * ds;
    }
    cr_light_near_tau = tau;
    if (u_reach == 0 && seg.y > length_to_exit && dot(toward, U.u_sun_dir) > 0.0) {
        let nf = cr_far_steps(u_light_steps);
        let span = (min(seg.y, CR_LIGHT_LONG_REACH) - length_to_exit) / f32(nf);
        for (var j = 0; j < nf; j++) {
            let q = p + toward * (length_to_exit + (f32(j) + light_offset) * span);
            tau += U.u_extinction * cr_density(q, cr_altitude(q)) * span;
        }
    }
    return tau;
}

fn cr_in_scattering(tau_light: f32, tau_behind: f32, tau_view: f32, mu: f32, h: f32, far: f32, tau_sky: f32) -> vec3f {
    var sun: f32;
    if (u_lighting == 1) {
        sun = cm_diffusion_scattering_with(tau_light, tau_behind, tau_view, mu, U.u_phase_mean_cosine, U.u_albedo,
                                           CM_DIFFUSION_MODEL_CLOUDS);
    } else if (u_lighting == 2) {
        sun = cm_diffusion_scattering_with(tau_light, tau_behind, tau_view, mu, U.u_phase_mean_cosine, U.u_albedo,
                                           CM_DIFFUSION_MODEL_FITTED);
    } else {
        sun = cm_multiple_scattering_with(tau_light, mu, U.u_ms_a, U.u_ms_b, U.u_ms_c, u_octaves);
    }
    if (u_powder != 0) {
        sun *= mix(2.0 * cm_powder(tau_light, 2.0), 1.0, 0.5 + 0.5 * mu);
    }
    if (u_occluded_ambient == 0) { return cr_sun_at(h) * (sun * far) + mix(U.u_ambient_bottom, U.u_ambient_top, h); }
    let depths = select(vec2<f32>(tau_behind, tau_sky), vec2<f32>(tau_sky, tau_behind), U.u_sun_dir.y >= 0.0) * abs(U.u_sun_dir.y);
    return cr_sun_at(h) * (sun * far) + mix(U.u_ambient_bottom * cm_diffuse_transmittance(depths.y, U.u_phase_mean_cosine),
                                        U.u_ambient_top * cm_diffuse_transmittance(depths.x, U.u_phase_mean_cosine), h);
}

fn cr_shadow_texel(ij: vec2f) -> vec3f {
    let ab = ((ij + 0.5) / f32(CR_SHADOW_MAP_SIZE) * 2.0 - 1.0) * U.u_shadow_half_extent;
    let p0 = U.u_shadow_origin + U.u_shadow_right * ab.x + U.u_shadow_up * ab.y;
    let seg = cm_cloud_layer_segment(cr_altitude(p0), -dot(U.u_sun_dir, cr_up(p0)), U.u_planet_radius, cr_band.x, cr_band.y);
    var acc = cm_beer_shadow_accumulator();
    if (seg.y > seg.x) {
        let ds = (seg.y - seg.x) / f32(CR_SHADOW_MAP_STEPS);
        for (var m = 0; m < CR_SHADOW_MAP_STEPS; m++) {
            let t = seg.x + f32(m) * ds;
            let q = p0 - U.u_sun_dir * (t + 0.5 * ds);
            cm_beer_shadow_add_step(&acc, t, ds, U.u_extinction * cr_density(q, cr_altitude(q)));
        }
    }
    return cm_beer_shadow_texel(acc);
}

fn cr_scene_distance(dir: vec3f, normal: ptr<function, vec3f>) -> f32 {
    *normal = vec3f(0.0, 1.0, 0.0);
    var nearest = -1.0;
    if (u_terrain == 0) { return nearest; }
    let inv = vec3f(select(1.0, -1.0, dir.x < 0.0), select(1.0, -1.0, dir.y < 0.0), select(1.0, -1.0, dir.z < 0.0)) / max(abs(dir), vec3f(1e-8));
    for (var i = 0; i < 4; i++) {
        let b = U.u_terrain_boxes[i];
        let t0 = vec3f(b.x - b.z, -U.u_cam_altitude - 1000.0, b.y - b.z) * inv;
        let t1 = vec3f(b.x + b.z, b.w - U.u_cam_altitude, b.y + b.z) * inv;
        let near = min(t0, t1);
        let far = max(t0, t1);
        let enter = max(max(near.x, near.y), near.z);
        let leave = min(min(far.x, far.y), far.z);
        if (enter > 0.0 && enter < leave && (nearest < 0.0 || enter < nearest)) {
            nearest = enter;
            if (enter == near.x) {
                *normal = vec3f(-sign(dir.x), 0.0, 0.0);
            } else if (enter == near.y) {
                *normal = vec3f(0.0, -sign(dir.y), 0.0);
            } else {
                *normal = vec3f(0.0, 0.0, -sign(dir.z));
            }
        }
    }
    return nearest;
}

fn cr_sun_transmittance(p: vec3f) -> f32 {
    let uvd = cm_shadow_map_project(p, U.u_shadow_origin, U.u_shadow_right, U.u_shadow_up, U.u_sun_dir, U.u_shadow_half_extent);
    if (!cr_on_map(uvd)) { return 1.0; }
    return cm_beer_shadow_transmittance(cr_shadow_lookup(uvd.xy), uvd.z);
}

fn cr_terrain(p: vec3f, n: vec3f) -> vec3f {
    var sun = max(dot(n, U.u_sun_dir), 0.0);
    if (u_shadows != 0) { sun *= cr_sun_transmittance(p); }
    return (0.25 / CM_PI) * (U.u_sun_radiance * sun + CM_PI * mix(U.u_ground, U.u_ambient_top, 0.5 + 0.5 * n.y));
}

fn cr_ground_shadow(g: vec3f) -> f32 {
    let uvd = cm_shadow_map_project(g, U.u_shadow_origin, U.u_shadow_right, U.u_shadow_up, U.u_sun_dir, U.u_shadow_half_extent);
    if (!cr_on_map(uvd)) { return 1.0; }
    return mix(CR_GROUND_SKY_SHARE, 1.0, cm_beer_shadow_transmittance(cr_shadow_lookup(uvd.xy), uvd.z));
}

fn cr_sky_coordinates(dir: vec3f) -> vec2f {
    let mu = clamp(dir.y, -1.0, 1.0);
    let h = length(dir.xz);
    let hs = length(U.u_sun_dir.xz);
    var cos_phi = 1.0;
    if (h > 1e-6 && hs > 1e-6) { cos_phi = clamp(dot(dir.xz, U.u_sun_dir.xz) / (h * hs), -1.0, 1.0); }
    return vec2f(acos(cos_phi) / CM_PI, 0.5 + 0.5 * sign(mu) * sqrt(abs(mu)));
}

fn cr_haze_node(d: i32, az: i32, el: i32, size: vec3i) -> vec3f { return textureLoad(u_haze_table, vec2i(d + size.x * az, el), 0).rgb; }
fn cr_haze(dir: vec3f, distance: f32) -> vec3f {
    let size = vec3i(U.u_haze_table_size + 0.5);
    let c = cr_sky_coordinates(dir) * vec2f(size.yz - 1);
    let d = sqrt(clamp(distance / U.u_haze_table_distance, 0.0, 1.0)) * f32(size.x - 1);
    let i0 = clamp(vec3i(vec3f(d, c)), vec3i(0), size - 2);
    let f = clamp(vec3f(d, c) - vec3f(i0), vec3f(0.0), vec3f(1.0));
    let r00 = mix(cr_haze_node(i0.x, i0.y, i0.z, size), cr_haze_node(i0.x + 1, i0.y, i0.z, size), f.x);
    let r10 = mix(cr_haze_node(i0.x, i0.y + 1, i0.z, size), cr_haze_node(i0.x + 1, i0.y + 1, i0.z, size), f.x);
    let r01 = mix(cr_haze_node(i0.x, i0.y, i0.z + 1, size), cr_haze_node(i0.x + 1, i0.y, i0.z + 1, size), f.x);
    let r11 = mix(cr_haze_node(i0.x, i0.y + 1, i0.z + 1, size), cr_haze_node(i0.x + 1, i0.y + 1, i0.z + 1, size), f.x);
    return mix(mix(r00, r10, f.y), mix(r01, r11, f.y), f.z);
}

fn cr_sky_view(dir: vec3f) -> vec3f {
    let size = vec2i(textureDimensions(u_sky_view));
    let c = cr_sky_coordinates(dir) * vec2f(size - 1);
    let i0 = clamp(vec2i(c), vec2i(0), size - 2);
    let f = clamp(c - vec2f(i0), vec2f(0.0), vec2f(1.0));
    let lower = mix(textureLoad(u_sky_view, i0, 0).rgb, textureLoad(u_sky_view, i0 + vec2i(1, 0), 0).rgb, f.x);
    let upper = mix(textureLoad(u_sky_view, i0 + vec2i(0, 1), 0).rgb, textureLoad(u_sky_view, i0 + vec2i(1, 1), 0).rgb, f.x);
    return mix(lower, upper, f.y);
}

fn cr_background(dir: vec3f) -> vec3f {
    var normal: vec3f;
    let scene = cr_scene_distance(dir, &normal);
    if (scene > 0.0) { return cr_terrain(dir * scene, normal); }
    let ground = cm_ray_sphere_intersect_altitude(U.u_cam_altitude, dir.y, U.u_planet_radius, 0.0);
    if (ground.x >= 0.0 && ground.y > ground.x) {
        if (u_shadows != 0) { return U.u_ground * cr_ground_shadow(dir * ground.x); }
        return U.u_ground;
    }
    let mu = dot(dir, U.u_sun_dir);
    var sky: vec3f;
    if (u_physical_sky != 0) {
        sky = cr_sky_view(dir);
    } else {
        sky = mix(U.u_sky_horizon, U.u_sky_zenith, sqrt(cm_saturate(dir.y)));
        sky += U.u_sun_radiance * (U.u_aureole * cm_phase_hg(mu, 0.75));
    }
    if (u_sun_disc != 0) { sky += U.u_sun_radiance * cm_sun_disc_radiance(1.0, mu, U.u_sun_angular_radius, 0.6); }
    return sky;
}

struct CrLitSample {
    t: f32,
    sigma_t: f32,
    ds: f32,
    tau_view: f32,
    transmittance: f32,
}
const CR_LIT_SAMPLES = 32;
var<private> cr_lit: array<CrLitSample, CR_LIT_SAMPLES>;

fn cr_light_samples(luminance: ptr<function, vec3f>, count: i32, dir: vec3f, mu: f32, pixel_hash: u32, light_index: ptr<function, u32>) {
    for (var k = 0; k < count; k++) {
        let q = cr_lit[k];
        let alts = cm_altitude_along_ray(U.u_cam_altitude, dir.y, U.u_planet_radius, q.t);
        let lo = cm_sample_jitter(pixel_hash, U.u_frame, *light_index);
        *light_index += 1u;
        let tau_light = cr_light_optical_depth(dir * q.t, alts, U.u_sun_dir, u_light_mode, lo);
        let tau_sky = cr_sky_depth_toward_sun(tau_light, cr_light_near_tau);
        var tau_behind = 0.0;
        if (u_lighting != 0) { tau_behind = cr_light_optical_depth(dir * q.t, alts, -U.u_sun_dir, u_behind_mode, lo); }
        let h = cm_height_fraction(alts, U.u_layer_bottom, U.u_layer_top);
        let S = (U.u_albedo * q.sigma_t) * cr_in_scattering(tau_light, tau_behind, q.tau_view, mu, h, cr_far_shadow(dir * q.t, alts), tau_sky);
        if (u_integration == 0) {
            *luminance += vec3f(q.transmittance) * cm_integrate_scattering_v3ff(S, q.sigma_t, q.ds);
        } else {
            *luminance += vec3f(q.transmittance) * S * q.ds;
        }
    }
}

fn cr_march_distance(u: f32, t0: f32, t1: f32) -> f32 {
    if (u_schedule == 1) { return cm_march_schedule_distance(u, t0, t1, U.u_march_near_distance); }
    return t0 + u * (t1 - t0);
}

fn cr_pixel_hash(pixel: vec2f) -> u32 { return cm_noise_hash(u32(pixel.x) + u32(pixel.y) * 8192u); }

@vertex
fn cr_vertex(@builtin(vertex_index) id: u32) -> @builtin(position) vec4f {
    // The full-screen triangle of the WebGL2 demo's vertex shader.
    return vec4f(select(-1.0, 3.0, id == 1u), select(-1.0, 3.0, id == 2u), 0.0, 1.0);
}

@fragment
fn cr_fragment(@builtin(position) position: vec4f) -> CrOutput {
    var out: CrOutput;
    // gl_FragCoord.xy: y up from the bottom row, pixel centres at .5.
    let frag_coord = vec2f(position.x, U.u_resolution.y - position.y);
    let pixel = select(frag_coord, floor(frag_coord) * 4.0 + vec2f(U.u_update_offset) + 0.5, u_pass == 1);
    let ndc = pixel / U.u_resolution * 2.0 - 1.0;
    let aspect = U.u_resolution.x / U.u_resolution.y;
    let dir = normalize(U.u_forward + U.u_right * (ndc.x * aspect * U.u_tan_half_fov) + U.u_up * (ndc.y * U.u_tan_half_fov));
    cr_band = select(cm_height_range_for_type(U.u_cloud_type) * (U.u_layer_top - U.u_layer_bottom) + U.u_layer_bottom, U.u_band, u_shape == 1);
    if (u_pass == 2) {
        out.out_color = vec4f(cr_shadow_texel(floor(frag_coord)), 0.0);
        out.out_depth = 0.0;
        return out;
    }

    let layer = cm_cloud_layer_segment(U.u_cam_altitude, dir.y, U.u_planet_radius, U.u_layer_bottom, U.u_layer_top);
    let in_band = cm_cloud_layer_segment(U.u_cam_altitude, dir.y, U.u_planet_radius, cr_band.x, cr_band.y);
    var seg = vec2f(max(layer.x, in_band.x), min(min(layer.y, layer.x + U.u_max_distance), in_band.y));
    var scene_normal: vec3f;
    let scene = cr_scene_distance(dir, &scene_normal);
    if (scene > 0.0) { seg.y = min(seg.y, scene); }
    if (u_pass == 3) {
        out.out_color = vec4f(cr_background(dir), select(0.0, 1.0, seg.y > seg.x));
        out.out_depth = max(scene, 0.0);
        return out;
    }

    cr_mie = cm_mie_approx_params(U.u_droplet_diameter);
    var acc = cm_march_accumulator();
    var cloud_depth = 0.0;
    if (seg.y > seg.x) {
        let t1 = seg.y;
        let pixel_hash = cr_pixel_hash(pixel);
        let offset = cm_frame_jitter(pixel_hash, U.u_frame);
        let mu = dot(dir, U.u_sun_dir);
        let n = f32(u_view_steps);
        var tau_view = 0.0;
        var depth_sum = 0.0;
        var step_begin = seg.x;
        var step_end = seg.x;
        var after_empty = true;
        var last_empty = -1.0;
        var light_index = 0u;
        var i = 0;
        var m = 0;
        var sub = 0;
        var sub_from = 0.0;
        var sub_ds = 0.0;
        var opaque = false;
        loop {
            var count = 0;
            while (!opaque && count < CR_LIT_SAMPLES && (m < sub || i < u_view_steps)) {
                let refining = m < sub;
                var t: f32;
                if (refining) {
                    t = sub_from + (f32(m) + offset) * sub_ds;
                } else {
                    t = cr_march_distance((f32(i) + offset) / n, seg.x, t1);
                }
                let altitude = cm_altitude_along_ray(U.u_cam_altitude, dir.y, U.u_planet_radius, t);
                let density = cr_density(dir * t, altitude);
                var ds: f32;
                if (refining) {
                    ds = sub_ds;
                    m++;
                    if (m == sub) {
                        step_begin = step_end;
                        i++;
                    }
                    if (density <= 0.0) { continue; }
                } else {
                    step_end = cr_march_distance((f32(i) + 1.0) / n, seg.x, t1);
                    if (density <= 0.0) {
                        last_empty = t;
                        step_begin = step_end;
                        after_empty = true;
                        i++;
                        continue;
                    }
                    let r0 = select(step_begin, last_empty, after_empty && last_empty >= 0.0);
                    let n_sub = cm_refine_substeps(U.u_extinction * density * (step_end - r0), u_refine);
                    after_empty = false;
                    if (n_sub > 1) {
                        sub = n_sub;
                        m = 0;
                        sub_from = r0;
                        sub_ds = (step_end - r0) / f32(n_sub);
                        continue;
                    }
                    ds = step_end - step_begin;
                    step_begin = step_end;
                    i++;
                }
                let sigma_t = U.u_extinction * density;
                let before = acc.transmittance.r;
                cr_lit[count] = CrLitSample(t, sigma_t, ds, tau_view + 0.5 * sigma_t * ds, before);
                count++;
                tau_view += sigma_t * ds;
                acc.transmittance *= cm_beer_lambert(sigma_t * ds);
                depth_sum += (before - acc.transmittance.r) * t;
                opaque = cm_march_is_opaque(acc, U.u_min_transmittance);
            }
            cr_light_samples(&acc.luminance, count, dir, mu, pixel_hash, &light_index);
            if (opaque || count < CR_LIT_SAMPLES) { break; }
        }
        let opacity = 1.0 - acc.transmittance.r;
        if (opacity > 0.0) { cloud_depth = depth_sum / opacity; }
        if (u_haze != 0 && opacity > 0.0) {
            let tau_air = cm_air_optical_depth(U.u_cam_altitude, dir.y, depth_sum / opacity);
            if (u_physical_sky != 0) {
                acc.luminance = acc.luminance * exp(-tau_air) + cr_haze(dir, depth_sum / opacity) * opacity;
            } else {
                acc.luminance = cm_aerial_perspective_v3v3v3(acc.luminance, U.u_sky_horizon * opacity, tau_air);
            }
        }
    }
    let alpha = 1.0 - (acc.transmittance.r + acc.transmittance.g + acc.transmittance.b) / 3.0;
    out.out_depth = cloud_depth;
    out.out_color = vec4f(acc.luminance, alpha);
    return out;
}

// composite.frag: the layer over what lies behind it, the tonemap and the dither. Both inputs
// were drawn by this module's cr_fragment, so they share WebGPU's rows (top first); the dither's
// pixel is gl_FragCoord's (y up from the bottom row).
@fragment
fn cr_composite(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let p = vec2i(position.xy);
    let layer = textureLoad(u_layer, p, 0);
    let behind = textureLoad(u_background, p, 0).rgb;
    var shown = pow(vec3f(1.0) - exp(-(behind * (1.0 - layer.a) + layer.rgb) * U.u_exposure), vec3f(1.0 / 2.2));
    if (u_dither != 0) {
        let frag_coord = vec2f(position.x, U.u_resolution.y - position.y);
        let index = u32(frag_coord.x) + u32(frag_coord.y) * 8192u;
        shown += cm_triangular_dither(cm_noise_hash(cm_noise_hash(index) + U.u_frame * 0x9e3779b9u)) * (1.0 / 255.0);
    }
    return vec4f(shown, layer.a);
}
