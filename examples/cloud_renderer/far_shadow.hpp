// far_shadow.hpp: the clouds' shadow from beyond the light march, for a low sun.
//
// A sun a few degrees up or down reaches a cloud along a path that stays in the layer for tens
// to hundreds of kilometres: with the sun 2 degrees below the horizon, the light that reaches
// the top of a 4-9 km layer dips to 5.1 km and climbs out again 440 km away, and every cloud on
// that path shades it. The light march ends at light_reach (30 km by default); what lies beyond
// is the far field, here statistical: the mean transmittance of the rest of the sun's path
// through the scene's own density field, averaged over where the path starts horizontally.
// Its geometry depends only on the start's altitude and the sun's zenith cosine there, and the
// field repeats horizontally (the weather map's period), so a table by those two holds it:
//   - the march's end: where the light march stops (the band's end or light_reach, as
//     cloud_layer_segment and the march compute it);
//   - the rest: every stretch of the path inside the band after that (it may dip below the
//     band and come back into it), marched in far_shadow_step steps with the full density
//     field; 0 where the path meets the ground (the planet's shadow);
//   - the mean of e^(-tau), not e^(-mean tau): broken clouds let light through their gaps.
// Nodes: altitude uniform over the band (cloud_band), the sun's zenith cosine uniform over
// [mu_lo, mu_hi]: below mu_lo every path from the band meets the ground (0), above mu_hi the
// light march reaches the band's end (1). Lookup bilinear and clamped, as clouds.frag's
// cr_far_shadow reads the R32F image (x altitude, y cosine) with texelFetch.
// What it leaves out: the correlation between the near and far paths (the table is a mean).
// The GPU form: clouds.frag's pass 4 (cr_far_shadow_texel), the same nodes, starts and steps,
// which the GL renderer and the web demo draw (gl_renderer.cpp's ensure_far_shadow); the CPU
// renderer reads far_shadow()'s table.
#ifndef CLOUD_RENDERER_FAR_SHADOW_HPP
#define CLOUD_RENDERER_FAR_SHADOW_HPP

#include "physical_sky.hpp"
#include "scene.hpp"
#include "textures.hpp"

#include <glm/vec3.hpp>

#include <vector>

namespace cloud_renderer {

struct far_shadow_table {
    int n_alt = 16, n_mu = 48;
    float alt_lo = 0.0f, alt_hi = 1.0f;  // metres: the band
    float mu_lo = -1.0f, mu_hi = 1.0f;   // the sun's zenith cosine at the start
    float reach = 0.0f;                  // where the light march ends, metres along the sun's path
    std::vector<float> texels;           // n_alt x n_mu, row-major (row: cosine)
};

// Metres per step of the far field's march, and horizontal start positions per node (a side of
// the stratified grid over the field's period).
inline constexpr float far_shadow_step = 400.0f;
inline constexpr int far_shadow_grid = 12;

// The table's nodes for scene s with the light march ending at `reach`: its size and range,
// texels empty (what far_shadow fills on the CPU, clouds.frag's pass 4 on the GPU).
far_shadow_table far_shadow_nodes(const scene& s, float reach);

// What the table depends on besides the textures: the geometry, the sun in direction sun_dir,
// the field's parameters and the reach (not the wind: the table is a mean over the field's
// period). far_shadow() and the GL renderer's GPU table key by it, each with its textures.
std::vector<float> far_shadow_scene_key(const scene& s, const glm::vec3& sun_dir, float reach);

// The table for scene s (its band, geometry and density field) and the sun in direction
// sun_dir (frame_constants::sun_dir), with the light march ending at `reach` (light_reach);
// made once per scene, sun and reach and kept in `tables` (physical_sky.hpp's cpu_sky_tables).
std::shared_ptr<const far_shadow_table> far_shadow(const scene& s, const glm::vec3& sun_dir, const cloud_textures& t, float reach,
                                                   cpu_sky_tables& tables = shared_cpu_sky_tables());

// The far field's transmittance for a sample at `altitude` with the sun at zenith cosine mu
// there; bilinear between the table's nodes, clamped to its ends. A NaN reads node 0.
float far_shadow_lookup(const far_shadow_table& t, float altitude, float mu);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_FAR_SHADOW_HPP
