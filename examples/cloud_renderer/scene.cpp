#include "scene.hpp"

#include "physical_sky.hpp"

#include "strict_number.hpp"

#include <cloudmath/atmosphere.hpp>
#include <cloudmath/density.hpp>
#include <cloudmath/phase.hpp>
#include <cloudmath/sun.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <vector>

namespace cloud_renderer {
namespace {

constexpr float degrees = 3.14159265358979f / 180.0f;

scene make(const char* name, const char* description, float altitude, float yaw, float pitch, float sun_elevation,
           float sun_azimuth, float coverage, float cloud_type) {
    scene s;
    s.name = name;
    s.description = description;
    s.camera_altitude = altitude;
    s.yaw = yaw;
    s.pitch = pitch;
    s.sun_elevation = sun_elevation;
    s.sun_azimuth = sun_azimuth;
    s.coverage = coverage;
    s.cloud_type = cloud_type;
    return s;
}

// Unit vector of a compass heading and an elevation (frame of scene.hpp).
glm::vec3 direction(float heading_deg, float elevation_deg) {
    const float h = heading_deg * degrees, e = elevation_deg * degrees;
    return {std::cos(e) * std::sin(h), std::sin(e), -std::cos(e) * std::cos(h)};
}

// Parses an integer in [lo, hi] (tools/common/strict_number.hpp: the whole text, decimal);
// false if it is not one.
bool parse_int(const std::string& text, int lo, int hi, int& out) {
    const std::optional<int> v = cloudmath::tools::parse_integer<int>(text);
    if (!v || *v < lo || *v > hi) return false;
    out = *v;
    return true;
}

bool parse_switch(const std::string& text, bool& out) {
    if (text == "on" || text == "1" || text == "true") return out = true, true;
    if (text == "off" || text == "0" || text == "false") return out = false, true;
    return false;
}

// The words of each enum's values, in order (the variant table's and name()'s).
template <class E>
struct value_names;
template <>
struct value_names<phase_model> {
    static constexpr const char* names[] = {"hg", "dual_hg", "cs", "mie"};
};
template <>
struct value_names<lighting_model> {
    static constexpr const char* names[] = {"octaves", "diffusion"};
};
template <>
struct value_names<diffusion_table> {
    static constexpr const char* names[] = {"clouds", "fitted"};
};
template <>
struct value_names<light_mode> {
    static constexpr const char* names[] = {"cone", "march", "map"};
};
template <>
struct value_names<integration_mode> {
    static constexpr const char* names[] = {"analytic", "naive"};
};
template <>
struct value_names<step_schedule> {
    static constexpr const char* names[] = {"uniform", "growing"};
};
template <>
struct value_names<reach_mode> {
    static constexpr const char* names[] = {"far", "band"};
};

// "a, b or c": the words of an error's choices.
std::string or_list(const char* const* words, std::size_t n) {
    std::string out;
    for (std::size_t i = 0; i < n; ++i) out += std::string(i == 0 ? "" : i + 1 == n ? " or " : ", ") + words[i];
    return out;
}

// Where a key's removed values went (appended to its error).
std::string removed_values(const std::string& key) {
    return key == "reach" ? " (capped and map were removed: docs/lighting_research.md, \"Switches removed\")" : "";
}

// One variant value from its text: empty, or the error. An enum takes its value_names, an
// integer the range [lo, hi], a bool its two words (on and off also 1, true, 0, false).
template <class E>
std::string parse_value(const char* key, const std::string& text, int, int, const char*, const char*, E& out) {
    const auto& names = value_names<E>::names;
    for (std::size_t i = 0; i < std::size(names); ++i)
        if (text == names[i]) {
            out = static_cast<E>(i);
            return {};
        }
    return std::string(key) + " must be " + or_list(names, std::size(names)) + ", not '" + text + "'" + removed_values(key);
}
std::string parse_value(const char* key, const std::string& text, int lo, int hi, const char*, const char*, int& out) {
    if (parse_int(text, lo, hi, out)) return {};
    return std::string(key) + " must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not '" + text + "'";
}
std::string parse_value(const char* key, const std::string& text, int, int, const char* off, const char* on, bool& out) {
    const bool on_off = std::string(off) == "off";
    if (on_off ? parse_switch(text, out) : text == on || text == off) {
        if (!on_off) out = text == on;
        return {};
    }
    return std::string(key) + " must be " + (on_off ? "on or off" : std::string(off) + " or " + on) + ", not '" + text + "'";
}

// A variant value's text (variant_spec).
template <class E>
std::string value_text(E e, const char*, const char*) {
    return value_names<E>::names[int(e)];
}
std::string value_text(int x, const char*, const char*) { return std::to_string(x); }
std::string value_text(bool x, const char* off, const char* on) { return x ? on : off; }

// The switches the renderer had and removed (issue 39), each with where its measurement
// stays: a script that still names one gets that instead of "unknown key". The scene's
// switches moved to scene (sun_disc, haze, shadows, dither), the others were fixed at their
// defaults.
const char* removed_switch(const std::string& key) {
    static const char* const keys[][2] = {
        {"cone-samples", "the cone always takes 6 samples (scene.hpp's cone_samples)"},
        {"light-spacing", "the light march's steps are always quadratic (docs/lighting_research.md, \"Switches removed\")"},
        {"light-jitter", "the light march's offsets are always jittered (docs/lighting_research.md, \"Switches removed\")"},
        {"jitter", "the view march's offset is always jittered (docs/lighting_research.md, \"Switches removed\")"},
        {"skip", "empty-space skipping was removed (docs/lighting_research.md, \"Switches removed\")"},
        {"lod", "texture LOD was removed: level 0 everywhere (docs/lighting_research.md, \"Switches removed\")"},
        {"far", "the light's far samples are always on the full density (docs/lighting_research.md, \"Switches removed\")"},
        {"sun", "the sun disc is the scene's (scene::sun_disc; the renderer's --without sun-disc)"},
        {"haze", "aerial perspective is the scene's (scene::haze; the renderer's --without haze)"},
        {"dither", "the dither is the scene's (scene::dither; the renderer's --without dither)"},
        {"shadows", "the ground's cloud shadows are the scene's (scene::shadows; the renderer's --without shadows)"},
    };
    for (const auto& k : keys)
        if (key == k[0]) return k[1];
    return nullptr;
}

}  // namespace

const std::vector<scene>& presets() {
    static const std::vector<scene> all = [] {
        std::vector<scene> v;
        v.push_back(make("ground", "on the ground looking up, sun high", 2, 0, 28, 50, 140, 0.3f, 0.65f));
        v.push_back(make("horizon", "on the ground at the horizon, low sun ahead", 2, 250, 12, 6, 265, 0.3f, 0.7f));
        v.push_back(make("sun_behind", "looking away from a low sun", 2, 70, 15, 15, 250, 0.32f, 0.7f));
        v.push_back(make("inside", "inside the layer, looking across it", 2700, 20, 0, 30, 160, 0.28f, 0.6f));
        v.push_back(make("above", "above the clouds looking down, low sun", 7000, 200, -18, 10, 230, 0.33f, 0.75f));
        v.push_back(make("stratus", "overcast stratus from the ground", 2, 40, 22, 35, 100, 0.6f, 0.0f));
        v.push_back(make("cumulus", "scattered cumulus, sun high", 2, 300, 18, 60, 180, 0.27f, 1.0f));
        scene towering = make("towering", "towering cumulus in a 1.5 to 8 km layer, sun to the side", 2, 130, 14, 40, 215, 0.3f, 1.0f);
        towering.layer_top = 8000.0f;
        towering.max_distance = 60000.0f;
        v.push_back(towering);
        // The low sun of the lighting truth's selection split (docs/lighting_truth.md): a sun 3
        // degrees up, facing it and with it behind the camera, in other parts of the field than
        // `horizon`, so that the choice of a low-sun light is not learned from that evaluation
        // preset.
        v.push_back(make("low_sun_ahead", "on the ground facing a sun 3 degrees up", 2, 100, 8, 3, 95, 0.3f, 0.7f));
        v.push_back(make("low_sun_behind", "on the ground, a sun 3 degrees up behind the camera", 2, 20, 12, 3, 200, 0.3f, 0.7f));
        // Made for the physical sky (sky_model::physical, cloudmath's atmosphere; every preset's
        // default): cumulus at sunrise, the sun 2 degrees up ahead; and just after sunset, the
        // sun 2 degrees below the horizon, lighting from below a layer at 4-9 km (above the 3.9
        // km where the Earth's shadow ends for a sun at -2 degrees).
        v.push_back(make("sunrise", "physical sky: cumulus at sunrise, the sun 2 degrees up ahead", 2, 80, 10, 2, 90, 0.3f, 0.9f));
        scene sunset = make("sunset", "physical sky: just after sunset, the sun 2 degrees down, a 4-9 km layer lit from below", 2, 260, 12, -2,
                            270, 0.3f, 1.0f);
        sunset.layer_bottom = 4000.0f;
        sunset.layer_top = 9000.0f;
        sunset.max_distance = 60000.0f;
        v.push_back(sunset);
        // The terrain (scene::terrain): above a cloud sea, the boxes rising through it, their
        // feet hidden in the clouds, their tops in the sun (docs/integration.md).
        scene mountains = make("mountains", "above a cloud sea, the terrain's boxes rising through it", 4700, 0, -6, 20, 120, 0.5f, 0.5f);
        mountains.terrain = true;
        v.push_back(mountains);
        return v;
    }();
    return all;
}

const scene* find_preset(const std::string& name) {
    for (const scene& s : presets())
        if (s.name == name) return &s;
    return nullptr;
}

namespace {

// The artistic sky: hand-made colours in display units.
void artistic_sky(const scene& s, frame_constants& f) {
    // Sunlight reddens toward the horizon: Beer-Lambert through the Kasten-Young air mass
    // with a per-channel optical depth (a look, not a sky model).
    const float e = s.sun_elevation < -2.0f ? -2.0f : s.sun_elevation;
    const float air_mass = 1.0f / (std::sin(std::fmax(e, 0.0f) * degrees) + 0.50572f * std::pow(e + 6.07995f + 2.0f, -1.6364f));
    const glm::vec3 tau_air(0.06f, 0.13f, 0.30f);
    const glm::vec3 sun = glm::vec3(std::exp(-tau_air.x * air_mass), std::exp(-tau_air.y * air_mass),
                                    std::exp(-tau_air.z * air_mass));
    const float day = glm::clamp((s.sun_elevation + 4.0f) / 14.0f, 0.05f, 1.0f);  // dims the sky at dusk
    f.sun_radiance = sun * 12.0f;
    f.sky_zenith = glm::vec3(0.16f, 0.30f, 0.62f) * day;
    f.sky_horizon = glm::mix(glm::vec3(0.62f, 0.72f, 0.86f), glm::vec3(0.85f, 0.62f, 0.45f), 1.0f - day) * day;
    f.ground = glm::vec3(0.12f, 0.11f, 0.09f) * day;
    f.ambient_top = glm::mix(f.sky_zenith, f.sky_horizon, 0.4f) * 1.1f;
    f.ambient_bottom = f.ground * 1.5f + 0.25f * f.ambient_top;
    f.aureole = 0.05f;
}

// The physical sky's samples (scene.hpp's physical_sky_samples) on the CPU: 12 sun and 9 sky
// marches, the rays of sky_tables.frag's values row.
physical_sky_samples cpu_sky_samples(const scene& s, const glm::vec3& sun_dir, glm::vec2 band) {
    const physical_air& a = earth_air();
    const float camera = std::fmax(s.camera_altitude, 0.0f);
    const auto sky = [&](glm::vec3 dir) { return sun_lux * cloudmath::atmosphere_sky_radiance(a.air, a.ms, camera, dir, sun_dir); };
    const auto sun = [&](float altitude) { return cloudmath::atmosphere_sun_illuminance(a.air, altitude, sun_dir.y, glm::vec3(sun_lux)); };
    physical_sky_samples p{};
    for (int i = 0; i < sun_heights; ++i)
        p.sun_by_height[i] = sun(s.layer_bottom + (s.layer_top - s.layer_bottom) * float(i) / float(sun_heights - 1));
    p.sun_band_middle = sun(0.5f * (band.x + band.y));
    p.sun_camera = sun(camera);
    p.zenith = sky(glm::vec3(0.0f, 1.0f, 0.0f));
    for (int i = 0; i < 8; ++i) {
        const float az = float(i) * 45.0f * degrees;
        p.horizon += sky(glm::vec3(std::cos(az) * std::cos(2.0f * degrees), std::sin(2.0f * degrees),
                                   std::sin(az) * std::cos(2.0f * degrees)));
    }
    p.horizon /= 8.0f;
    return p;
}

// The physical sky's fields of f from its samples and sky-view tables (make_frame_constants).
void apply_physical_sky(frame_constants& f, const physical_sky_samples& p, std::shared_ptr<const sky_view_table> at_camera,
                        const sky_view_table& at_top) {
    // The sun: its illuminance at the band's middle (the drawn disc), and on the clouds by
    // height in the layer.
    f.sun_radiance = p.sun_band_middle;
    std::copy(std::begin(p.sun_by_height), std::end(p.sun_by_height), std::begin(f.sun_by_height));
    // The sky gradient (the exposure's): the zenith, and the horizon (2 degrees up) averaged
    // over 8 azimuths.
    f.sky_zenith = p.zenith;
    f.sky_horizon = p.horizon;
    // The background: the sky-view table at the camera (no gradient, no glow: the table has the
    // sky's own brightening toward the sun).
    f.sky_view = at_camera;
    f.aureole = 0.0f;
    // The sky's light on the clouds from above: the mean radiance of the upper hemisphere seen
    // from the layer's top (the table there: what the whole-cloud truth's paths meet when they
    // leave through the top); and the sky's irradiance on the ground at the camera.
    const sky_hemisphere top = upper_hemisphere(at_top, f.sun_dir);
    const sky_hemisphere below = upper_hemisphere(*at_camera, f.sun_dir);
    // The ground: Lambertian with the air's albedo, lit by the sun at the camera and the sky.
    f.ground = earth_air().air.ground_albedo / 3.14159265f * (p.sun_camera * std::fmax(f.sun_dir.y, 0.0f) + below.irradiance);
    f.ambient_top = top.mean_radiance;
    f.ambient_bottom = f.ground;
}

// apply_physical_sky with the CPU's samples and tables, made once per sun direction and scene
// geometry (the tables: physical_sky_view), all kept in `tables`.
void physical_sky(const scene& s, frame_constants& f, cpu_sky_tables& tables) {
    const std::shared_ptr<const frame_constants> kept = tables.made_once<frame_constants>(
        {s.camera_altitude, s.sun_elevation, f.sun_dir.x, f.sun_dir.y, f.sun_dir.z, f.band.x, f.band.y, s.layer_bottom, s.layer_top},
        [&] {
            frame_constants g = f;
            apply_physical_sky(g, cpu_sky_samples(s, f.sun_dir, f.band),
                               physical_sky_view(std::fmax(s.camera_altitude, 0.0f), f.sun_dir, tables),
                               *physical_sky_view(s.layer_top, f.sun_dir, tables));
            return g;
        });
    const frame_constants& sky = *kept;
    f.sun_radiance = sky.sun_radiance;
    std::copy(std::begin(sky.sun_by_height), std::end(sky.sun_by_height), std::begin(f.sun_by_height));
    f.sky_zenith = sky.sky_zenith;
    f.sky_horizon = sky.sky_horizon;
    f.aureole = sky.aureole;
    f.sky_view = sky.sky_view;
    f.ambient_top = sky.ambient_top;
    f.ambient_bottom = sky.ambient_bottom;
    f.ground = sky.ground;
}

// make_frame_constants' body: the physical sky from `gpu` (its samples and tables made on the
// GPU) or, when null, from the CPU's, kept in `tables`.
frame_constants frame_constants_for(const scene& s, const physical_sky_inputs* gpu, cpu_sky_tables& tables) {
    frame_constants f{};
    const float pitch = s.pitch > 89.0f ? 89.0f : (s.pitch < -89.0f ? -89.0f : s.pitch);
    f.forward = direction(s.yaw, pitch);
    f.right = glm::normalize(glm::vec3(std::cos(s.yaw * degrees), 0.0f, std::sin(s.yaw * degrees)));
    f.up = glm::cross(f.right, f.forward);
    f.tan_half_fov = std::tan(0.5f * s.fov_y * degrees);
    f.sun_dir = direction(s.sun_azimuth, s.sun_elevation);

    f.band = cloud_band(s);
    if (s.sky == sky_model::physical) {
        if (gpu)
            apply_physical_sky(f, gpu->samples, gpu->at_camera, *gpu->at_top);
        else
            physical_sky(s, f, tables);
        // EV100: the scene's, or the one that exposes the sky's mean luminance to middle grey.
        f.ev100 = s.ev100 > -50.0f ? s.ev100
                                   : cloudmath::ev100_from_luminance(
                                         std::fmax(0.5f * (luminance(f.sky_zenith) + luminance(f.sky_horizon)), 1e-3f));
        f.exposure = cloudmath::exposure_from_ev100(f.ev100);
    } else {
        artistic_sky(s, f);
        for (glm::vec3& sun : f.sun_by_height) sun = f.sun_radiance;
        f.ev100 = 0.0f;
        f.exposure = s.exposure;
    }
    f.sun_angular_radius = cloudmath::sun_angular_radius<float>();  // the real Sun: 0.27 degrees
    // The tools' split by source (scene::light), after the exposure, which stays the whole's.
    if (s.sky == sky_model::physical && s.light == light_sources::sun) {
        f.ambient_top = f.ambient_bottom = f.sky_zenith = f.sky_horizon = f.ground = glm::vec3(0.0f);
        f.aureole = 0.0f;
        f.sky_view = nullptr;  // the background: the (black) gradient
    } else if (s.sky == sky_model::physical && s.light == light_sources::sky) {
        f.sun_radiance = glm::vec3(0.0f);
        for (glm::vec3& sun : f.sun_by_height) sun = glm::vec3(0.0f);
    }

    f.phase_g = 0.8f;
    f.phase_g_back = -0.25f;
    f.phase_w = 0.2f;
    f.droplet_diameter = 15.0f;
    f.ms_a = 0.5f;
    f.ms_b = 0.5f;
    f.ms_c = 0.5f;
    f.cone_step = 120.0f;
    f.cone_spread = 0.4f;
    f.cone_far_distance = 1800.0f;
    f.cone_far_length = 900.0f;
    f.light_march_max = 6000.0f;
    f.march_near_distance = 1000.0f;
    f.min_transmittance = 0.01f;

    // The shadow map's frame. The sun's elevation is clamped to 3 degrees for the plane's
    // height (below it the map would stretch over hundreds of kilometres).
    const glm::vec3 ahead = std::fabs(f.forward.x) + std::fabs(f.forward.z) > 1e-4f
                                ? glm::normalize(glm::vec3(f.forward.x, 0.0f, f.forward.z))
                                : glm::vec3(0.0f, 0.0f, -1.0f);
    const glm::vec3 centre = glm::vec3(0.0f, -s.camera_altitude, 0.0f) + ahead * 12000.0f;
    f.shadow_origin = centre + f.sun_dir * ((s.layer_top + 500.0f) / std::fmax(f.sun_dir.y, std::sin(3.0f * degrees)));
    const glm::vec3 across = glm::cross(f.sun_dir, glm::vec3(0.0f, 1.0f, 0.0f));
    f.shadow_right = glm::length(across) > 1e-4f ? glm::normalize(across) : glm::vec3(1.0f, 0.0f, 0.0f);
    f.shadow_up = glm::cross(f.shadow_right, f.sun_dir);
    f.shadow_half_extent = 24000.0f;
    return f;
}

}  // namespace

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

float auto_ev100(const scene& s) { return make_frame_constants(s).ev100; }

glm::vec3 sun_at_height(const frame_constants& k, bool physical, float h) {
    if (!physical) return k.sun_radiance;
    const float x = cloudmath::saturate(h) * float(sun_heights - 1);
    const int i = cloudmath::detail::floor_to_int(x, 0, sun_heights - 2);  // a NaN height reads node 0
    return glm::mix(k.sun_by_height[i], k.sun_by_height[i + 1], x - float(i));
}

float display_exposure(const scene& s) { return make_frame_constants(s).exposure; }

frame_constants make_frame_constants(const scene& s) { return frame_constants_for(s, nullptr, shared_cpu_sky_tables()); }

frame_constants make_frame_constants(const scene& s, cpu_sky_tables& tables) { return frame_constants_for(s, nullptr, tables); }

frame_constants geometry_constants(const scene& s) {
    scene no_sky = s;
    no_sky.sky = sky_model::artistic;
    return frame_constants_for(no_sky, nullptr, shared_cpu_sky_tables());  // no table is made
}

frame_constants make_frame_constants(const scene& s, const physical_sky_inputs& gpu) {
    return frame_constants_for(s, &gpu, shared_cpu_sky_tables());  // no table is made
}

physical_sky_samples physical_sky_samples_cpu(const scene& s) {
    return cpu_sky_samples(s, direction(s.sun_azimuth, s.sun_elevation), cloud_band(s));
}

float light_reach(const variant& v, const frame_constants& k) {
    if (v.light == light_mode::cone) return k.cone_far_distance + 0.5f * k.cone_far_length;
    return light_long_reach;
}

glm::vec3 pixel_direction(const frame_constants& k, int x, int y, int width, int height) {
    const glm::vec2 ndc = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) / glm::vec2(float(width), float(height)) * 2.0f - 1.0f;
    const float aspect = float(width) / float(height);
    return glm::normalize(k.forward + k.right * (ndc.x * aspect * k.tan_half_fov) + k.up * (ndc.y * k.tan_half_fov));
}

glm::vec2 cloud_band(const scene& s) {
    glm::vec2 range = cloudmath::height_range_for_type(s.cloud_type);
    if (s.shape == cloud_shape::detailed) {
        // The range's ends are piecewise linear in the type with a kink at 0.5: its extremes
        // over an interval are at the interval's ends or at 0.5.
        const float lo = glm::clamp(s.cloud_type - 0.5f * s.type_spread, 0.0f, 1.0f);
        const float hi = glm::clamp(s.cloud_type + 0.5f * s.type_spread, 0.0f, 1.0f);
        for (float t : {lo, hi, glm::clamp(0.5f, lo, hi)}) {
            const glm::vec2 r = cloudmath::height_range_for_type(t);
            range = glm::vec2(std::fmin(range.x, r.x), std::fmax(range.y, r.y));
        }
        range.x *= cloudmath::cloud_top_fraction(0.0f);  // a lower top compresses the profile down
    }
    return range * (s.layer_top - s.layer_bottom) + s.layer_bottom;
}

const char* name(cloud_shape c) { return c == cloud_shape::classic ? "classic" : "detailed"; }
const char* name(sky_model m) { return m == sky_model::artistic ? "artistic" : "physical"; }
std::optional<sky_model> sky_model_named(const std::string& n) {
    if (n == "artistic") return sky_model::artistic;
    if (n == "physical") return sky_model::physical;
    return std::nullopt;
}

const char* name(light_sources l) { return l == light_sources::all ? "all" : l == light_sources::sun ? "sun" : "sky"; }
std::optional<light_sources> light_sources_named(const std::string& n) {
    for (const light_sources l : {light_sources::all, light_sources::sun, light_sources::sky})
        if (n == name(l)) return l;
    return std::nullopt;
}

std::string permutation_key(const variant& v, const scene& s) {
    std::string key = variant_spec(v) + "/" + name(s.shape) + "/";
#define CLOUD_RENDERER_SWITCH_KEY(member, item, shader, file) \
    if (switch_shader::file == switch_shader::clouds) key += std::string(item) + (s.member ? "=on," : "=off,");
    CLOUD_RENDERER_SCENE_SWITCHES(CLOUD_RENDERER_SWITCH_KEY)
#undef CLOUD_RENDERER_SWITCH_KEY
    return key;
}

std::vector<shader_constant> scene_constants(const scene& s, switch_shader in) {
    std::vector<shader_constant> out;
    if (in == switch_shader::clouds) out.push_back({"u_shape", static_cast<int>(s.shape)});
#define CLOUD_RENDERER_SWITCH_CONSTANT(member, item, shader, file) \
    if (switch_shader::file == in) out.push_back({shader, s.member ? 1 : 0});
    CLOUD_RENDERER_SCENE_SWITCHES(CLOUD_RENDERER_SWITCH_CONSTANT)
#undef CLOUD_RENDERER_SWITCH_CONSTANT
    return out;
}

bool turn_off_scene_switch(scene& s, const std::string& item) {
#define CLOUD_RENDERER_SWITCH_OFF(member, item_text, shader, file) \
    if (item == item_text) return s.member = false, true;
    CLOUD_RENDERER_SCENE_SWITCHES(CLOUD_RENDERER_SWITCH_OFF)
#undef CLOUD_RENDERER_SWITCH_OFF
    return false;
}

std::string scene_switch_names() {
    std::vector<const char*> items;
#define CLOUD_RENDERER_SWITCH_NAME(member, item, shader, file) items.push_back(item);
    CLOUD_RENDERER_SCENE_SWITCHES(CLOUD_RENDERER_SWITCH_NAME)
#undef CLOUD_RENDERER_SWITCH_NAME
    return or_list(items.data(), items.size());
}

float terrain_distance(const scene& s, glm::vec3 dir, glm::vec3* normal) {
    if (normal) *normal = glm::vec3(0.0f, 1.0f, 0.0f);
    float nearest = -1.0f;
    if (!s.terrain) return nearest;
    // Slabs from the camera (at the origin); a zero component is a tiny one of its sign.
    const glm::vec3 inv = glm::vec3(dir.x < 0.0f ? -1.0f : 1.0f, dir.y < 0.0f ? -1.0f : 1.0f, dir.z < 0.0f ? -1.0f : 1.0f) /
                          glm::max(glm::abs(dir), glm::vec3(1e-8f));
    for (const terrain_box& b : terrain_boxes) {
        const glm::vec3 t0 = glm::vec3(b.x - b.half_width, -s.camera_altitude - 1000.0f, b.z - b.half_width) * inv;
        const glm::vec3 t1 = glm::vec3(b.x + b.half_width, b.top - s.camera_altitude, b.z + b.half_width) * inv;
        const glm::vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
        const float enter = std::max(std::max(near.x, near.y), near.z), leave = std::min(std::min(far.x, far.y), far.z);
        if (enter > 0.0f && enter < leave && (nearest < 0.0f || enter < nearest)) {
            nearest = enter;
            if (normal)
                *normal = enter == near.x ? glm::vec3(-glm::sign(dir.x), 0.0f, 0.0f)
                          : enter == near.y ? glm::vec3(0.0f, -glm::sign(dir.y), 0.0f)
                                            : glm::vec3(0.0f, 0.0f, -glm::sign(dir.z));
        }
    }
    return nearest;
}

const char* name(phase_model p) { return value_names<phase_model>::names[int(p)]; }
const char* name(light_mode l) { return value_names<light_mode>::names[int(l)]; }
const char* name(reach_mode r) { return value_names<reach_mode>::names[int(r)]; }
const char* name(step_schedule s) { return value_names<step_schedule>::names[int(s)]; }
const char* name(integration_mode i) { return value_names<integration_mode>::names[int(i)]; }
const char* name(lighting_model l) { return value_names<lighting_model>::names[int(l)]; }
const char* name(diffusion_table t) { return value_names<diffusion_table>::names[int(t)]; }

float phase_mean_cosine(const frame_constants& k, phase_model p) {
    switch (p) {
    case phase_model::hg: return k.phase_g;
    case phase_model::dual_hg: return (1.0f - k.phase_w) * k.phase_g + k.phase_w * k.phase_g_back;
    case phase_model::cornette_shanks: {
        // Cornette & Shanks 1992: <mu> = 3 g (4 + g^2) / (5 (2 + g^2)).
        const float g = k.phase_g;
        return 3.0f * g * (4.0f + g * g) / (5.0f * (2.0f + g * g));
    }
    case phase_model::mie: break;
    }
    // The fit is (1 - w) HG(g_hg) + w Draine(g_d, alpha); Draine's phase function has the mean
    // cosine g (1 + alpha (3 + 2 g^2) / 5) / (1 + alpha (1 + 2 g^2) / 3) (Draine 2003, ApJ
    // 598, 1017), HG's is g. (A quadrature would have to resolve HG's forward peak, which at
    // g_hg = 0.993 is 1e-5 wide in mu.)
    const cloudmath::mie_approx_parameters<double> m = cloudmath::mie_approx_params(double(k.droplet_diameter));
    const double gd = m.g_draine, a = m.alpha;
    const double draine = gd * (1.0 + a * (3.0 + 2.0 * gd * gd) / 5.0) / (1.0 + a * (1.0 + 2.0 * gd * gd) / 3.0);
    return static_cast<float>((1.0 - m.w_draine) * m.g_hg + m.w_draine * draine);
}

std::string apply_variant_spec(const std::string& spec, variant& v) {
    variant out = v;
    std::stringstream items(spec);
    std::string item;
    while (std::getline(items, item, ',')) {
        if (item.empty()) continue;
        const std::size_t eq = item.find('=');
        if (eq == std::string::npos) return "variant item '" + item + "' is not key=value";
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        bool known = false;
        std::string error;
#define CLOUD_RENDERER_VARIANT_PARSE(member, default_value, key_text, lo, hi, off, on, shader, constant) \
    if (key == key_text) {                                                                           \
        known = true;                                                                                \
        error = parse_value(key_text, value, lo, hi, off, on, out.member);                           \
    }
        CLOUD_RENDERER_VARIANT_TABLE(CLOUD_RENDERER_VARIANT_PARSE)
#undef CLOUD_RENDERER_VARIANT_PARSE
        if (!error.empty()) return error;
        if (known) continue;
        if (const char* where = removed_switch(key)) return "'" + key + "' is no longer a variant switch: " + where;
        std::string keys;
#define CLOUD_RENDERER_VARIANT_KEY(member, default_value, key_text, lo, hi, off, on, shader, constant) \
    keys += std::string(keys.empty() ? "" : ", ") + key_text;
        CLOUD_RENDERER_VARIANT_TABLE(CLOUD_RENDERER_VARIANT_KEY)
#undef CLOUD_RENDERER_VARIANT_KEY
        return "unknown variant key '" + key + "' (known: " + keys + ")";
    }
    v = out;
    return {};
}

std::string variant_spec(const variant& v) {
    std::string spec;
#define CLOUD_RENDERER_VARIANT_PRINT(member, default_value, key_text, lo, hi, off, on, shader, constant) \
    spec += std::string(spec.empty() ? "" : ",") + key_text + "=" + value_text(v.member, off, on);
    CLOUD_RENDERER_VARIANT_TABLE(CLOUD_RENDERER_VARIANT_PRINT)
#undef CLOUD_RENDERER_VARIANT_PRINT
    return spec;
}

std::vector<shader_constant> variant_constants(const variant& v) {
    std::vector<shader_constant> out;
#define CLOUD_RENDERER_VARIANT_CONSTANT(member, default_value, key_text, lo, hi, off, on, shader, constant) \
    if (*shader != '\0') out.push_back({shader, constant});
    CLOUD_RENDERER_VARIANT_TABLE(CLOUD_RENDERER_VARIANT_CONSTANT)
#undef CLOUD_RENDERER_VARIANT_CONSTANT
    return out;
}

}  // namespace cloud_renderer
