// The scene and the lighting variant of the cloud renderer: plain data shared by the GPU
// renderer (which turns it into shader uniforms or constants) and the CPU reference (which
// reads it directly), so both draw exactly the same thing.
//
// Frame:  the camera sits at the origin, altitude `camera_altitude` above a planet whose
//         centre is straight below it; +y is up at the camera, -z is north, +x east.
//         Positions are camera-relative (metres); the cloud textures are looked up at
//         (x + wind.x, altitude, z + wind.y), so the clouds follow the planet's curvature and
//         stay put when the camera climbs.
#ifndef CLOUD_RENDERER_SCENE_HPP
#define CLOUD_RENDERER_SCENE_HPP

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <memory>
#include <string>
#include <vector>

namespace cloud_renderer {

struct sky_view_table;  // physical_sky.hpp
class cpu_sky_tables;   // ...

enum class phase_model { hg, dual_hg, cornette_shanks, mie };
// How a light estimate gets its optical depth: the cone, a march over the cloud type's band,
// or the Beer shadow map (toward the sun: its optical depth at the sample's depth; away from
// it: the column's total minus that; the cone outside the map). The map is the cheapest
// (docs/peer_bench.md: no light march at all), the march the most accurate.
enum class light_mode { cone, march, map };
enum class integration_mode { analytic, naive };
// Where the view march puts its steps between where the ray enters the cloud type's altitude
// band and max_distance further: equal steps, or steps that grow with distance
// (march_schedule_distance with frame_constants::march_near_distance; it gains up to 1.3 dB
// of the image on some presets for up to 11% more reads and loses up to 1.9 dB of the horizon
// band on others: docs/renderer.md, Convergence).
enum class step_schedule { uniform, growing };
// The sun term: Wrenninge's octaves (multiple_scattering.hpp) or the diffusion model
// (diffusion_lighting.hpp), which also needs the optical depth behind the sample (a second
// light estimate away from the sun, by the cone or a march: `behind`) and from the camera
// (tracked by the march).
enum class lighting_model { octaves, diffusion };
// The diffusion model's fitted numbers: diffusion_models::clouds (fitted to whole-cloud
// images of this renderer against their path-traced truth, on the selection presets of
// both fields: the default) or diffusion_models::fitted (fitted to homogeneous spheres and
// slabs, the default before, and still the closer of the two on them). The same cost.
enum class diffusion_table { clouds, fitted };
// How far the light march toward the sun reaches beyond its first light_march_max (6 km; a
// high sun's band ends sooner and both are the same): `far`, the default, marches the 6 km in
// light_steps quadratic steps and then far_step_count(light_steps) uniform full-density
// steps to where the band ends, up to light_long_reach (30 km); `band` stretches the
// light_steps steps over the whole path to the band's end, up to light_long_reach: the same
// reads as a 6 km march, further from the truth at a low sun (docs/lighting_truth.md,
// reach_band). docs/lighting_research.md keeps the other reaches measured and removed.
enum class reach_mode { far, band };

// What the issue calls a lighting variant: the switches that a current report row or test
// shows best at something (cost or error), and the octaves, the baseline users compare
// against. Defaults: the diffusion model, which is closer to the path-traced truth than the
// octaves on every preset (docs/lighting_truth.md), with the optical depth toward the sun and
// behind the sample from 6-step marches over the cloud type's altitude band (quadratic steps,
// each light estimate's offset jittered per sample and frame), and sky light occluded by the
// optical depth above and below. `lighting=octaves,powder=on,light=cone,ambient=flat` is the
// production octave choice it replaced (a 6-sample cone with the far sample, 3 octaves,
// powder, unoccluded sky light). The switches removed from the renderer, with the
// measurements that removed them: docs/lighting_research.md, "Switches removed".
// The variant's switches in one table, the one place a switch is listed. Each row: the member,
// its default (the member's type is the default's), its --variant key, the range of an
// integer, the words of a bool (off, on), the shader's permutation constant (clouds.frag's
// CR_PARAM line, clouds.wgsl's override; empty: none of its own) and that constant's value for
// variant v (an enum's is its index). The struct below, apply_variant_spec, variant_spec and the
// permutation block of fragment_shader_source are made from it; an enum's words are
// value_names' (scene.cpp). ctest cloud_renderer.variant_table (test_variant_table.cpp)
// checks that clouds.frag's CR_PARAM lines, clouds.wgsl's overrides and the web demo's
// permutation values (web/demo/main.js) name the same constants: a switch added in one place
// alone fails it.
//  member            default                        key            range    bool words          shader constant       its value
#define CLOUD_RENDERER_VARIANT_TABLE(X)                                                                                                                \
    X(phase,            phase_model::dual_hg,          "phase",       0, 0,    "", "",             "u_phase_model",      int(v.phase))              \
    X(lighting,         lighting_model::diffusion,     "lighting",    0, 0,    "", "",             "u_lighting",         lighting_constant(v))      \
    X(table,            diffusion_table::clouds,       "table",       0, 0,    "", "",             "",                   0)                         \
    X(octaves,          3,                             "octaves",     1, 8,    "", "",             "u_octaves",          v.octaves)                 \
    X(powder,           false,                         "powder",      0, 0,    "off", "on",        "u_powder",           v.powder ? 1 : 0)          \
    X(light,            light_mode::march,             "light",       0, 0,    "", "",             "u_light_mode",       int(v.light))              \
    X(behind,           light_mode::march,             "behind",      0, 0,    "", "",             "u_behind_mode",      int(v.behind))             \
    X(light_steps,      6,                             "light-steps", 1, 256,  "", "",             "u_light_steps",      v.light_steps)             \
    X(integration,      integration_mode::analytic,    "integration", 0, 0,    "", "",             "u_integration",      int(v.integration))        \
    X(view_steps,       64,                            "steps",       8, 1024, "", "",             "u_view_steps",       v.view_steps)              \
    X(schedule,         step_schedule::uniform,        "schedule",    0, 0,    "", "",             "u_schedule",         int(v.schedule))           \
    X(refine,           16,                            "refine",      1, 64,   "", "",             "u_refine",           v.refine)                  \
    X(occluded_ambient, true,                          "ambient",     0, 0,    "flat", "occluded", "u_occluded_ambient", v.occluded_ambient ? 1 : 0) \
    X(reach,            reach_mode::far,               "reach",       0, 0,    "", "",             "u_reach",            int(v.reach))

// The members (CLOUD_RENDERER_VARIANT_TABLE's rows, in order):
// - phase: the phase function;
// - lighting, table: the octaves or the diffusion model, and the diffusion model's numbers;
// - octaves, powder: Wrenninge's octaves (1..8) and Schneider's powder term;
// - light, behind: the optical depth toward the sun and the one behind the sample (diffusion
//   model only);
// - light_steps: the light march's steps to where the cloud type's band ends (1..256);
// - integration: energy-conserving or the naive Riemann sum;
// - view_steps, schedule: the view march's steps through the layer (8..1024) and their spacing;
// - refine: a view step whose sample gives it an optical depth above 1 is marched again in up
//   to `refine` sub-steps of optical depth <= 1 (refine_substeps), from the last empty sample
//   when it is the first step in cloud (the cloud's front lies between): the light is then
//   read near the front, not up to a step inside. 1: never (1..64);
// - occluded_ambient: the sky light (ambient) inside clouds, flat (the layer's top and bottom
//   colours mixed by height, unattenuated) or occluded: the top's light times
//   diffuse_transmittance of the optical depth above the sample, the bottom's of the depth
//   below, both estimated from the light estimates toward and away from the sun times the
//   sun's elevation sine (with the sun below the horizon the estimate away from it looks up,
//   toward it down);
// - reach: the light march toward a low sun (reach_mode).
struct variant {
#define CLOUD_RENDERER_VARIANT_MEMBER(member, default_value, key, lo, hi, off, on, shader, value) \
    decltype(default_value) member = default_value;
    CLOUD_RENDERER_VARIANT_TABLE(CLOUD_RENDERER_VARIANT_MEMBER)
#undef CLOUD_RENDERER_VARIANT_MEMBER
};
// clouds.frag's u_lighting: 0 the octaves, 1 the diffusion model with diffusion_models::clouds,
// 2 with diffusion_models::fitted.
inline int lighting_constant(const variant& v) {
    return v.lighting == lighting_model::octaves ? 0 : v.table == diffusion_table::clouds ? 1 : 2;
}
// The permutation's constants from the table (name, value), in its order: the shader's
// CR_PARAM constants of variant v (fragment_shader_source adds the scene's and the pass).
struct shader_constant {
    const char* name;
    int value;
};
std::vector<shader_constant> variant_constants(const variant& v);

// The density field. classic: the weather map's coverage (R) with the scene's one cloud type
// and height profile everywhere, a 60 km weather period. detailed: per-cloud type (G, within
// type_spread of the scene's) and top height (B: top at 60 to 100% of the type's profile),
// tops rounded by coverage that narrows with height, curl-noise distortion of the detail, a
// density scale for crisp edges, and the wide weather map (240 km period).
enum class cloud_shape { classic, detailed };
enum class sky_model { artistic, physical };
// The sun and sky (the default: physical, on the CPU, the GPU and in the tools; the renderer's
// --sky artistic keeps the other): `artistic`, the renderer's hand-made colours (a sky gradient with a glow
// around the sun, a sun reddened by a Kasten-Young air mass, display units, the exposure
// setting), or `physical`, from cloudmath's atmosphere (atmosphere.hpp, Earth's air): the sun's
// illuminance in lux by height in the layer (128 klux above the air), the sky's
// zenith and horizon luminance (cd/m^2) with an aureole fitted to the sky near the sun, the
// ground and the clouds' ambient light from the same sky, and the display exposure from EV100
// (exposure_from_ev100). See make_frame_constants and docs/atmosphere.md.

// Which light reaches the clouds, for the whole-cloud truth's split of its error by source
// (cloudmath_volume_truth render --light; the renderers' options do not set it): all; the sun
// alone (no sky light, no ground, a black background); or the sky alone (the sky, the ground
// the sun and sky light, and the background, but no sun on the clouds). The truth and the
// model are linear in the two, so the sun's and the sky's parts add up to the whole. With the
// physical sky only: the artistic sky's glow is drawn from the sun's colour.
enum class light_sources { all, sun, sky };

// The picture: camera, sun, sky, clouds. Angles in degrees, lengths in metres.
struct scene {
    std::string name = "custom";
    std::string description;
    float camera_altitude = 2.0f;
    float yaw = 0.0f;                // compass heading of the view, 0 = north (-z), 90 = east
    float pitch = 10.0f;             // elevation of the view above the horizon
    float fov_y = 60.0f;             // vertical field of view
    float sun_elevation = 30.0f;
    float sun_azimuth = 30.0f;       // compass heading of the sun
    float coverage = 0.3f;           // mean cloud coverage, 0..1 (shifts the weather map)
    float cloud_type = 0.6f;         // 0 stratus, 0.5 stratocumulus, 1 cumulus
    float planet_radius = 6371000.0f;
    float layer_bottom = 1500.0f;
    float layer_top = 4000.0f;
    float extinction = 0.04f;        // sigma_t (1/m) at density 1
    float albedo = 0.99f;            // sigma_s / sigma_t
    float max_distance = 35000.0f;   // the view march stops this far from where it enters
    float base_tile = 12000.0f;      // metres covered by one repeat of the base volume
    float detail_tile = 1500.0f;     // ... of the detail volume
    float weather_tile = 60000.0f;   // ... of the weather map (classic shape)
    cloud_shape shape = cloud_shape::detailed;
    float weather_wide_tile = 240000.0f;  // ... of the wide weather map (detailed shape)
    float curl_tile = 9000.0f;       // ... of the curl texture (detailed shape)
    float curl_strength = 180.0f;    // metres the curl displaces the detail at the cloud's base
    float type_spread = 0.5f;        // per-cloud type: cloud_type + (G - 0.5) type_spread
    float top_rounding = 0.6f;       // coverage at the cloud's top, as a share lost (0: flat tops)
    float density_scale = 4.0f;      // detailed density = saturate(eroded density * this)
    glm::vec2 wind{1200.0f, -800.0f};  // offset of the textures (animate it for wind)
    std::uint32_t frame = 0;         // frame number: advances each pixel's march jitter (frame_jitter)
    float exposure = 1.0f;           // the display's exposure with the artistic sky
    enum sky_model sky = sky_model::physical;
    float ev100 = -100.0f;           // the physical sky's exposure value; below -50: from the sky (auto_ev100)
    light_sources light = light_sources::all;  // the tools' split by source (above); the exposure stays the whole's
    // What the picture draws besides the clouds' light (the path-traced truths draw none of
    // them, so their tools turn them off; the renderer's --without): the sun disc at its
    // physical radiance in the background; aerial perspective (the air between the camera and
    // the cloud, and the horizon's haze); the clouds' shadows on the ground, from a Beer shadow
    // map (shadow_map.hpp) of shadow_map_size^2 texels, each a shadow_map_steps march along
    // the sunlight; a triangular dither of one 8-bit step on the display colour (no banding in
    // the sky's slow gradients; the convergence measurements turn it off to compare images).
    bool sun_disc = true;
    bool haze = true;
    bool shadows = true;
    bool dither = true;
    // The example's terrain (terrain_boxes, the `mountains` preset): opaque boxes standing in
    // the view, some into the cloud layer. The cloud march ends at them, the background draws
    // them, and the temporal resolve keeps no history the terrain now hides: what an engine's
    // depth buffer does (docs/integration.md).
    bool terrain = false;
};

// The scene's switches in one table: X(member, --without item, the permutation constant, the
// shader that reads it: clouds, the cloud passes' clouds.frag; composite, composite.frag, the
// display transform). The --without list, permutation_key and the permutation blocks of both
// shaders are made from it.
#define CLOUD_RENDERER_SCENE_SWITCHES(X)             \
    X(sun_disc, "sun-disc", "u_sun_disc", clouds)    \
    X(haze, "haze", "u_haze", clouds)                \
    X(shadows, "shadows", "u_shadows", clouds)       \
    X(dither, "dither", "u_dither", composite)       \
    X(terrain, "terrain", "u_terrain", clouds)
// The two shaders of a frame that take permutation constants.
enum class switch_shader { clouds, composite };
// A shader's permutation constants from the scene: for clouds.frag its density field's shape
// (u_shape) and its switches, for composite.frag its switches.
std::vector<shader_constant> scene_constants(const scene& s, switch_shader shader = switch_shader::clouds);
// Turns off the scene switch named `item` (a --without item); false for an unknown name.
bool turn_off_scene_switch(scene& s, const std::string& item);
// The --without items, "sun-disc, haze, shadows, dither or terrain".
std::string scene_switch_names();

// The terrain's boxes, camera-relative: the (x, z) of each centre (m; the camera at x = z = 0,
// looking along -z at yaw 0), its half width and its top's altitude. From below the ground
// (the curvature drops it 8 m at 10 km) to the top; shaded as Lambertian rock (terrain_radiance).
struct terrain_box {
    float x, z, half_width, top;
};
inline constexpr terrain_box terrain_boxes[4] = {
    {-3500.0f, -9000.0f, 1200.0f, 3300.0f},
    {1500.0f, -12500.0f, 1600.0f, 4500.0f},
    {5200.0f, -7500.0f, 900.0f, 2600.0f},
    {-800.0f, -16000.0f, 1400.0f, 5400.0f}};
// The distance along the unit direction dir to the nearest box (the scene's depth; its
// outward normal in *normal), or -1 where the ray meets none or the scene has no terrain
// (clouds.frag's cr_scene_distance).
float terrain_distance(const scene& s, glm::vec3 dir, glm::vec3* normal);

// The exposure the tonemap uses (frame_constants::exposure): scene::exposure with the artistic
// sky; with the physical one exposure_from_ev100(ev100) = 1 / (1.2 2^EV100) for luminance in
// cd/m^2, EV100 the scene's or auto_ev100. The tonemap (tonemap in cloud_density.hpp, the
// composite pass's in composite.frag and clouds.wgsl's cr_composite) is then
// (1 - e^(-exposure L))^(1 / 2.2) per channel.
float display_exposure(const scene& s);
// The physical sky's EV100 when the scene does not set one: ev100_from_luminance of the sky's
// mean luminance (zenith and horizon), which exposes it to middle grey.
float auto_ev100(const scene& s);
// Luminance of linear Rec. 709 rgb (cd/m^2 for the physical sky's radiance).
float luminance(const glm::vec3& c);

// The default before the renderer's rework (issue 15's baseline, with --shape classic): the
// octaves with powder, the cone toward the sun, flat sky light, no refinement.
inline constexpr const char* previous_default_spec = "lighting=octaves,powder=on,light=cone,ambient=flat,refine=1";

// The cone's samples toward the sun, its far one included (cone_light.hpp).
inline constexpr int cone_samples = 6;
// reach_mode's cap on the light march toward the sun (metres): the far steps end here, and
// reach=band's stretched march.
inline constexpr float light_long_reach = 30000.0f;
// reach=far: twice as many far steps as the near march has (12 for 6), so a converged
// reference (light-steps=128) converges the far field too. Twelve full-density steps
// (docs/lighting_research.md, "The far field on the full density"): closer to the
// path-traced truth at a low sun and converging in fewer steps.
inline constexpr int far_step_count(int light_steps) { return light_steps < 2 ? 1 : 2 * light_steps; }

// The march records the view samples in cloud, up to this many, and then lights them in a
// loop of its own (the light pass), out of the view loop; when the buffer fills, the light
// pass runs and the march goes on from where it stopped (no sample is dropped: the image is
// the same as lighting each sample where it is found, for any count).
inline constexpr int lit_samples = 32;
// The temporal scheme's resolve (temporal_resolve.frag, cpu_temporal_renderer).
// How far (pixels) the history's content, carried by its own motion, may land from the pixel
// that reads it before the resolve rejects it (a cloud moved in or out) and fills instead.
inline constexpr float temporal_reprojection_tolerance = 1.0f;
// A pixel not yet shaded takes this share of each frame's fill (the new samples of its block
// interpolated), so the fills from the block's other pixels average until its own turn.
// Chosen on a held-out sequence (cumulus, pan -0.3 degrees and 20 m of wind a frame), not
// the documented one: 0.1 gave 36.2 dB, 0.2 36.0, 0.3 35.9, 0 34.8.
inline constexpr float temporal_fill_blend = 0.1f;
// The Beer shadow map (scene::shadows): texels per side, midpoint steps per texel, and the
// share of the ground's light that comes from the sky (what a full shadow leaves).
inline constexpr int shadow_map_size = 128;
inline constexpr int shadow_map_steps = 24;
inline constexpr float ground_sky_share = 0.4f;
// The temporal scheme redraws the shadow map a slice at a time, as engines time-slice their
// shadow updates: frame f redraws rows [f % slices, f % slices + 1) * size / slices (the whole
// map on a first frame). A row is then at most slices - 1 frames old: at the docs' 30 m of
// wind a frame, 30 m, a twelfth of a texel (2 shadow_half_extent / shadow_map_size: 375 m).
// Measured on the docs' moving sequence (ground, pan 0.5 degrees, 30 m a frame, 320 x 180,
// frame 47 against its full render): 2 slices 35.75 dB, 4 slices 35.33, the whole map every
// frame 35.84; the shadow pass costs half of its whole-map time with 2 slices.
inline constexpr int temporal_shadow_slices = 2;
static_assert(shadow_map_size % temporal_shadow_slices == 0, "equal slices");
// Rows [first, end) of the map that temporal frame `frame` redraws (all when `whole`).
inline glm::ivec2 temporal_shadow_rows(std::uint32_t frame, bool whole) {
    if (whole) return {0, shadow_map_size};
    const int slice = static_cast<int>(frame % static_cast<std::uint32_t>(temporal_shadow_slices));
    return {slice * shadow_map_size / temporal_shadow_slices, (slice + 1) * shadow_map_size / temporal_shadow_slices};
}

// True when the frame draws the Beer shadow map: for the ground's shadows or a light
// estimate (light_mode::map).
inline bool needs_shadow_map(const variant& v, const scene& s) {
    return s.shadows || v.light == light_mode::map || v.behind == light_mode::map;
}

// Every preset, in the order --list-presets prints them; the first is the default.
const std::vector<scene>& presets();
// The preset with this name, or nullptr.
const scene* find_preset(const std::string& name);

// Derived values both renderers use, computed once on the CPU in float (so the GPU gets the
// very same numbers as uniforms): the camera basis, the sun direction and colours, and the
// light and phase parameters. The physical sky's sun and sky light come from its tables: the
// CPU's (make_frame_constants(s)) or the GPU's (make_frame_constants(s, physical_sky_inputs)).
struct frame_constants {
    glm::vec3 forward, right, up;    // camera basis (camera frame as described above)
    float tan_half_fov;
    glm::vec3 sun_dir;               // unit, toward the sun
    glm::vec3 sun_radiance;          // colour * intensity of direct sunlight
    glm::vec3 ambient_top, ambient_bottom;  // isotropic sky light at the layer top / bottom
    glm::vec3 sky_zenith, sky_horizon, ground;
    float sun_angular_radius;        // the sun disc's angular radius (radians)
    float aureole;                   // the glow around the sun: aureole sun_radiance HG(mu, 0.75) in the sky
    // The physical sky's sun on the clouds by height in the layer: its illuminance at altitudes
    // layer_bottom + h (layer_top - layer_bottom), h = i / (sun_heights - 1), linear between
    // (at sunset the layer's bottom lies in the Earth's shadow while its top is lit); unused
    // with the artistic sky, whose clouds see sun_radiance everywhere.
    glm::vec3 sun_by_height[8];
    // The physical sky's background: its sky-view table at the camera (physical_sky.hpp; the
    // CPU's, kept by a cpu_sky_tables, or physical_sky_inputs' at_camera; shared: it lives while held), which
    // sky_radiance and clouds.frag's cr_background read in place of the gradient and glow; null
    // with the artistic sky.
    std::shared_ptr<const sky_view_table> sky_view;
    float exposure;                  // the tonemap's (display_exposure)
    float ev100;                     // the physical sky's EV100 (0 with the artistic sky)
    float phase_g, phase_g_back, phase_w;   // HG / Cornette-Shanks g; dual lobe second g, weight
    float droplet_diameter;          // Mie fit, micrometres
    float ms_a, ms_b, ms_c;          // octave factors (attenuation, contribution, eccentricity)
    float cone_step, cone_spread, cone_far_distance, cone_far_length;
    float light_march_max;           // the light march covers at most this far
    float march_near_distance;       // growing view steps: nearly uniform closer than this
    glm::vec2 band;                  // altitudes outside which the field has no density (cloud_band)
    float min_transmittance;         // early exit of the view march
    // The Beer shadow map: a sun-aligned square of 2 shadow_half_extent around the ground
    // 12 km ahead of the camera, its plane (through shadow_origin, normal sun_dir) above the
    // cloud layer on the sun's side; shadow_right, shadow_up, sun_dir: its basis.
    glm::vec3 shadow_origin, shadow_right, shadow_up;
    float shadow_half_extent;
};

// The frame's constants, the physical sky's from the CPU (its sky marches and sky-view tables,
// made once per sun and geometry and kept in `tables`: physical_sky.hpp's cpu_sky_tables; the
// first form in the process's, shared_cpu_sky_tables()).
frame_constants make_frame_constants(const scene& s);
frame_constants make_frame_constants(const scene& s, cpu_sky_tables& tables);
// The frame's constants that need no sky light: the camera, the sun's direction, the light
// and phase parameters, the shadow map's frame (its sky and sun fields are the artistic
// sky's): make_frame_constants with no physical sky's tables built.
frame_constants geometry_constants(const scene& s);
// Where variant v's light estimate toward the sun ends, metres along the sun's path (unless
// the band ends first): the march's and the shadow map's light_long_reach, the cone's far
// sample's end. The physical sky's far shadow (far_shadow.hpp) begins there.
float light_reach(const variant& v, const frame_constants& k);
// Entries of frame_constants::sun_by_height.
inline constexpr int sun_heights = 8;
// The sun on a cloud at height fraction h of the layer: sun_by_height interpolated with the
// physical sky, sun_radiance with the artistic one (clouds.frag's cr_sun_at).
glm::vec3 sun_at_height(const frame_constants& k, bool physical, float h);

// What the physical sky gives a frame besides its tables, sampled from the atmosphere: the
// rays of shaders/sky_tables.frag's values row, which the GL renderer draws on the GPU.
struct physical_sky_samples {
    glm::vec3 sun_by_height[sun_heights];  // the sun on the clouds (frame_constants::sun_by_height)
    glm::vec3 sun_band_middle;             // the sun at the band's middle: the drawn disc
    glm::vec3 sun_camera;                  // the sun at the camera: the ground's
    glm::vec3 zenith, horizon;             // the sky at the zenith, and 2 degrees up (mean of 8 azimuths)
};
// The samples on the CPU (12 sun and 9 sky marches), for the scene's sun.
physical_sky_samples physical_sky_samples_cpu(const scene& s);
// The physical sky made elsewhere (on the GPU): its samples and its sky-view tables at the
// camera (the background, the ground's sky light) and at the layer's top (the clouds' sky light).
struct physical_sky_inputs {
    physical_sky_samples samples;
    std::shared_ptr<const sky_view_table> at_camera, at_top;
};
// The frame's constants with the physical sky from `sky` (the scene's sky must be physical):
// the same fields as make_frame_constants(s) gives from the CPU's.
frame_constants make_frame_constants(const scene& s, const physical_sky_inputs& sky);

// The altitudes (bottom, top) outside which the scene's field has no density: the cloud
// type's height_range_for_type, or with the detailed shape the union over the types the
// weather map can give (cloud_type +- type_spread / 2).
glm::vec2 cloud_band(const scene& s);
// "classic" or "detailed".
const char* name(cloud_shape c);
// "artistic" or "physical", and back (none for any other name).
const char* name(sky_model m);
std::optional<sky_model> sky_model_named(const std::string& name);
const char* name(light_sources l);
std::optional<light_sources> light_sources_named(const std::string& name);

// The unit view direction through the centre of pixel (x, y) of a width x height image (y = 0
// the bottom row): the shader's ray (clouds.frag main), shared by the CPU renderer, the
// volume tracer's camera and the convergence report's horizon band.
glm::vec3 pixel_direction(const frame_constants& k, int x, int y, int width, int height);

// "phase=mie,lighting=diffusion,octaves=4,powder=off,light=march,light-steps=32,
// integration=naive,steps=128,reach=band" (any subset, applied over `v`). Returns an empty
// string on success, else the message for the user (a removed switch's names where it was
// measured).
std::string apply_variant_spec(const std::string& spec, variant& v);
// The same notation back, every field.
std::string variant_spec(const variant& v);
// The variant and the scene's permutation switches as one key,
// "<variant_spec>/<shape>/sun-disc=on,haze=on,shadows=on,terrain=off,": what a compiled-in clouds.frag
// permutation, and what is drawn for it (the temporal scheme's shadow map), is for; the
// composite's switches (dither) are not in it.
std::string permutation_key(const variant& v, const scene& s);
const char* name(phase_model p);
const char* name(light_mode l);
const char* name(reach_mode r);
const char* name(step_schedule s);
const char* name(integration_mode i);
const char* name(lighting_model l);
const char* name(diffusion_table t);
// Mean cosine g of a phase model with the frame's parameters (the diffusion model's g):
// closed forms for HG, dual-lobe HG, Cornette-Shanks and the Mie fit (HG plus Draine).
float phase_mean_cosine(const frame_constants& k, phase_model p);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_SCENE_HPP
