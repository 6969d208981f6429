// tools/reference/transport/cloud_medium.hpp: the example renderer's cloud scene
// (examples/cloud_renderer: scene.hpp presets, cloud_density.hpp field and sky) as a
// medium and a light for the volume path tracer (volume_tracer.hpp), so that the truth
// renders the very same clouds as the real-time image.
//
// Scene definition (what the truth computes, and where it follows the renderer):
//   - geometry: the renderer's camera frame in metres (scene.hpp), in double; the planet
//     (radius planet_radius) is an opaque ground, the medium is the layer between
//     layer_bottom and layer_top with sigma_t = extinction * density, the density being
//     cloud_density::density (float, as the renderer evaluates it);
//   - albedo scene.albedo (0.99), phase a parameter (default the renderer's dual-lobe HG
//     of make_frame_constants: dual_hg:0.8,-0.25,0.2);
//   - the sun: a directional source of perpendicular irradiance sun_radiance (the renderer
//     multiplies sun_radiance by the phase function), by next-event estimation with the
//     transmittance to the layer top (0 when the shadow ray hits the planet);
//   - the sky: a path leaving the layer upward picks up sky_radiance(dir) WITHOUT the drawn
//     sun disc (the sun is the directional source above; the disc would count it twice) but
//     WITH the 0.05 HG(mu, 0.75) aureole, which is part of the sky's radiance for every ray
//     that escapes, primary or scattered; with the physical sky, the sky-view table at the
//     layer's top, where every such path leaves (physical_sky.hpp: the atmosphere's sky seen
//     from there, its glow toward the sun included); a path that reaches the ground picks up
//     the ground colour (an emitter, not a reflector);
//   - camera rays: the renderer's pixel-centre directions (one per pixel, no
//     anti-aliasing, as the renderer); a camera ray's first flight meets the clouds only on
//     the renderer's view stretch, the layer segment cut at max_distance (35 km) from its
//     start, and behind it sees the renderer's background() exactly (ground, sky, aureole,
//     sun disc). Scattered paths see the whole layer.
//
// Majorants: density <= apply_coverage(base_cloud * height_gradient, coverage), since the
// detail erosion only removes density (erode(c, e) <= c for e in [0, 0.2]), and that bound
// is monotonic in the base cloud (itself increasing in the base texture's R and decreasing
// in its G, B, A) and in coverage (increasing in the weather map's R). The texture fields
// repeat every weather_tile metres (the base tile divides it), so a grid over one period x
// the layer's altitude holds an upper bound per cell, from the extreme texels that the
// GL_LINEAR reads of the cell can touch (one texel of margin) and the height gradient's
// maximum over the cell's altitudes (plus its Lipschitz bound over the sampling step), with
// a relative margin of 1e-4 for float rounding. Rays are cut into stretches of one cell
// width whose bound is the largest of the cells their x, z and altitude ranges overlap
// (altitude along a straight ray is convex: its range is from the ends and the closest
// approach). Empty stretches are skipped.
// The detailed shape (cloud_renderer::cloud_shape::detailed): the same bound with the wide
// weather map (period weather_wide_tile, cells of at least 1/480 of it), a height gradient
// bounded by 1 wherever cloud_band reaches (any type and top the weather map can give), the
// coverage's fall with height dropped (it only lowers density) and density_scale applied
// before the saturation; the curl only moves the detail, which only erodes.
#ifndef CLOUDMATH_TOOLS_CLOUD_MEDIUM_HPP
#define CLOUDMATH_TOOLS_CLOUD_MEDIUM_HPP

#include <string>
#include <vector>

#include "cloud_density.hpp"
#include "volume_tracer.hpp"

namespace cloudmath::reference::volume {

class cloud_medium final : public medium {
public:
    // Keeps a copy of the scene; the textures must outlive the medium. cell_size: the
    // majorant grid's horizontal cell (metres, rounded to divide the period); layers: its
    // cells across the layer's height.
    cloud_medium(const cloud_renderer::scene& s, const cloud_renderer::cloud_textures& t,
                 double cell_size = 250.0, int layers = 25);
    cloud_medium(const cloud_medium&) = delete;
    cloud_medium& operator=(const cloud_medium&) = delete;

    [[nodiscard]] double extinction(const vec3& p) const override;
    [[nodiscard]] medium_exit exit(const vec3& p, const vec3& d) const override;
    void majorants(const vec3& p, const vec3& d, double t_min, double t_max,
                   const majorant_visitor& visit) const override;

    // Altitude of the camera-relative point p (double precision).
    [[nodiscard]] double altitude(const vec3& p) const;
    // The renderer's density (float) at p.
    [[nodiscard]] double density(const vec3& p) const;
    // Upper bound of the density over texture-space x in [x0, x1], z in [z0, z1] (the
    // camera-relative coordinates plus the wind) and altitudes [alt0, alt1].
    [[nodiscard]] double density_bound(double x0, double x1, double z0, double z1, double alt0,
                                       double alt1) const;
    [[nodiscard]] const cloud_renderer::scene& scene_data() const { return scene_; }

private:
    cloud_renderer::scene scene_;
    cloud_renderer::cloud_density field_;
    double period_ = 0.0, cell_ = 0.0, layer_height_ = 0.0;
    int cells_ = 1, layers_ = 1;
    std::vector<float> bound_;  // [(k * cells_ + j) * cells_ + i]: layer k, z cell j, x cell i
    [[nodiscard]] float cell_bound(int i, int j, int k) const;
};

// The renderer's light: its sun and its sky and ground for escaped paths (see above).
[[nodiscard]] lighting make_cloud_lighting(const cloud_renderer::scene& s);
// "dual_hg:G0,G1,W" of the renderer's make_frame_constants.
[[nodiscard]] std::string renderer_phase_spec(const cloud_renderer::scene& s);
// One camera ray per pixel (row 0 at the bottom, x fastest), with the renderer's view
// stretch and background.
[[nodiscard]] std::vector<camera_ray> make_camera_rays(const cloud_renderer::scene& s, int width,
                                                       int height);

}  // namespace cloudmath::reference::volume

#endif  // CLOUDMATH_TOOLS_CLOUD_MEDIUM_HPP
