// sun_depth_volume.hpp: the optical depth toward the sun from every point of the view's part
// of the cloud layer, precomputed per sun and scene (research: variant::far_volume, the CPU
// reference only).
//
// A sun a few degrees up reaches a sample through tens of kilometres of the layer; a few light
// steps cannot resolve that path (docs/lighting_research.md, "The depth toward a low sun"). The
// volume holds, at nodes (u, w, altitude), the depth from the node along the sun's straight
// path to where it leaves the band (its first exit: the far shadow table covers what comes
// after). u is the horizontal coordinate toward the sun's azimuth, w across it, both planar
// camera-relative (x, z); altitude is over the curved planet, so the geometry of a low sun on a
// round Earth is exact up to the nodes.
// It is made by a sweep against the light: the slice at the band's exit (its top for a rising
// path, its bottom for a falling one) is 0, and each other node is the integral of the full
// density over its stretch to the next slice toward the sun (midpoint steps) plus the next
// slice's value where the stretch lands (bilinear). Its cost is one density sample per step
// of path per node column, once per sun or weather change.
#ifndef CLOUD_RENDERER_SUN_DEPTH_VOLUME_HPP
#define CLOUD_RENDERER_SUN_DEPTH_VOLUME_HPP

#include "scene.hpp"
#include "textures.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace cloud_renderer {

struct sun_depth_volume {
    int nu = 0, nw = 0, na = 0;
    float spacing = 500.0f;          // metres between nodes across the sun (w); half that in altitude
    float spacing_u = 1000.0f;       // ... and toward it (u)
    float u0 = 0.0f, w0 = 0.0f;      // the first node's u and w
    float alt_lo = 0.0f, alt_hi = 1.0f;
    glm::vec2 eu{1.0f, 0.0f}, ew{0.0f, 1.0f};  // (x, z) of the u and w axes
    bool transmittance = false;      // the nodes hold e^(-depth), the sweep and the lookup
                                     // interpolate transmittances (a mean over nearby paths)
    std::vector<float> depth;        // [a][w][u]
};

// The volume for scene s and the sun in direction sun_dir, nodes `spacing` metres apart across
// the sun (half that in altitude) and spacing_u toward it; made once per scene, sun and
// spacings and kept.
const sun_depth_volume& sun_depth(const scene& s, const glm::vec3& sun_dir, const cloud_textures& t, float spacing,
                                  float spacing_u, bool transmittance);

// The depth toward the sun from the camera-relative point p at altitude alt: trilinear between
// nodes; 0 outside the band or beyond the volume toward the sun, clamped at its other sides.
float sun_depth_lookup(const sun_depth_volume& v, const glm::vec3& p, float alt);

// The next node slice toward the sun from p (altitude alt; planet radius R, camera radius r0 =
// R + camera altitude): x the distance along sun_dir to it, y its index; y < 0 when the path
// leaves the band first (x then the distance to the band's exit, or 0).
glm::vec2 sun_depth_next_slice(const sun_depth_volume& v, const glm::vec3& p, float alt, const glm::vec3& sun_dir, float R,
                               float r0);
// The value of slice a at the camera-relative point p (bilinear in u and w).
float sun_depth_on_slice(const sun_depth_volume& v, int a, const glm::vec3& p);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_SUN_DEPTH_VOLUME_HPP
