// frame_block.hpp: clouds.frag's uniform block CrFrame as a C++ struct of the same std140
// layout: the frame's constants, filled once per pass from the scene and frame_constants
// (gl_renderer.cpp's fill_frame_block) and uploaded as one buffer that every pass reads. Each
// glm::vec3 is followed by a float that fills its 16 bytes, as std140 packs them; vec3 arrays
// take 16 bytes an element (glm::vec4 here, w unused). The GL renderer checks every member's
// offset and the block's size against the linked program (check_frame_block), so a member
// added to one side alone fails at link with its name.
#ifndef CLOUD_RENDERER_FRAME_BLOCK_HPP
#define CLOUD_RENDERER_FRAME_BLOCK_HPP

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>

namespace cloud_renderer {

struct frame_block {
    glm::vec3 forward;
    float tan_half_fov;
    glm::vec3 right;
    float cam_altitude;
    glm::vec3 up;
    float planet_radius;
    glm::vec3 sun_dir;
    float layer_bottom;
    glm::vec3 sun_radiance;
    float layer_top;
    glm::vec3 ambient_top;
    float sun_angular_radius;
    glm::vec3 ambient_bottom;
    float aureole;
    glm::vec3 sky_zenith;
    float coverage;
    glm::vec3 sky_horizon;
    float cloud_type;
    glm::vec3 ground;
    float extinction;
    glm::vec3 shadow_origin;
    float albedo;
    glm::vec3 shadow_right;
    float max_distance;
    glm::vec3 shadow_up;
    float shadow_half_extent;
    glm::vec3 haze_table_size;
    float haze_table_distance;
    glm::vec4 far_shadow_range;
    glm::vec4 terrain_boxes[4];
    glm::vec4 sun_by_height[8];
    glm::vec2 resolution, band;
    glm::vec2 wind, far_shadow_size;
    glm::uvec2 update_offset;
    std::uint32_t frame;
    float exposure;
    float base_tile, detail_tile, weather_tile, weather_wide_tile;
    float curl_tile, curl_strength, type_spread, top_rounding;
    float density_scale, phase_g, phase_g_back, phase_w;
    float droplet_diameter, ms_a, ms_b, ms_c;
    float phase_mean_cosine, cone_step, cone_spread, cone_far_distance;
    float cone_far_length, light_march_max, min_transmittance, march_near_distance;
    float far_shadow_reach, far_shadow_period;
    float pad[2];  // std140 rounds the block up to 16 bytes
};
static_assert(sizeof(frame_block) % 16 == 0, "std140: a block is a whole number of vec4");
static_assert(offsetof(frame_block, far_shadow_range) % 16 == 0 && offsetof(frame_block, terrain_boxes) % 16 == 0 &&
                  offsetof(frame_block, sun_by_height) % 16 == 0 && offsetof(frame_block, resolution) % 8 == 0,
              "std140: vec4 and arrays on 16 bytes, vec2 on 8");

// Every member under its GLSL name (u_ and the C++ name), with its offset: the layout
// check_frame_block compares with the program's.
#define CLOUD_RENDERER_FRAME_BLOCK_MEMBERS(X)                                                                      \
    X(forward) X(tan_half_fov) X(right) X(cam_altitude) X(up) X(planet_radius) X(sun_dir) X(layer_bottom)           \
    X(sun_radiance) X(layer_top) X(ambient_top) X(sun_angular_radius) X(ambient_bottom) X(aureole) X(sky_zenith)    \
    X(coverage) X(sky_horizon) X(cloud_type) X(ground) X(extinction) X(shadow_origin) X(albedo) X(shadow_right)     \
    X(max_distance) X(shadow_up) X(shadow_half_extent) X(haze_table_size) X(haze_table_distance)                   \
    X(far_shadow_range) X(terrain_boxes) X(sun_by_height) X(resolution) X(band) X(wind) X(far_shadow_size)         \
    X(update_offset) X(frame) X(exposure) X(base_tile) X(detail_tile) X(weather_tile) X(weather_wide_tile)         \
    X(curl_tile) X(curl_strength) X(type_spread) X(top_rounding) X(density_scale) X(phase_g) X(phase_g_back)        \
    X(phase_w) X(droplet_diameter) X(ms_a) X(ms_b) X(ms_c) X(phase_mean_cosine) X(cone_step) X(cone_spread)        \
    X(cone_far_distance) X(cone_far_length) X(light_march_max) X(min_transmittance) X(march_near_distance)         \
    X(far_shadow_reach) X(far_shadow_period)

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_FRAME_BLOCK_HPP
