// The cloud renderer's density field and sky, as a public class shared by the CPU reference
// (cpu_renderer.cpp) and the volume path tracer of tools/reference (volume_truth), so the
// real-time image and its ground truth draw the very same scene.
//
// Frame and units: those of scene.hpp (camera at the origin, +y up at the camera, metres).
// Texture reads reproduce OpenGL's GL_LINEAR + GL_REPEAT filtering of the UNORM8 texels of
// textures.hpp, as shaders/clouds.frag sees them.
#ifndef CLOUD_RENDERER_CLOUD_DENSITY_HPP
#define CLOUD_RENDERER_CLOUD_DENSITY_HPP

#include "scene.hpp"
#include "textures.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace cloud_renderer {

// texture() of a UNORM8 texture with GL_LINEAR filtering and GL_REPEAT (cloudmath's
// texture_trilinear_repeat / texture_bilinear_repeat), value byte / 255. Texel layout of
// textures.hpp (x fastest, channels interleaved); 2D textures are the z = 0 slice.
struct linear_texture {
    const std::uint8_t* data;
    int size, channels;

    // Texel (x, y, z) channel c in [0, 1]; indices must be in [0, size).
    float texel(int x, int y, int z, int c) const;
    glm::vec4 texel4(int x, int y, int z) const;  // every channel, 0 beyond `channels`
    glm::vec4 sample3(glm::vec3 uvw) const;
    glm::vec4 sample2(glm::vec2 uv) const;
};

// The density field of shaders/clouds.frag (cr_altitude, cr_density). Keeps references to
// the scene and the textures: both must outlive it.
class cloud_density {
public:
    cloud_density(const scene& s, const cloud_textures& t);

    // Altitude (metres above the planet) of the camera-relative point p.
    float altitude(glm::vec3 p) const;
    // Density in [0, 1] at p whose altitude is alt (0 outside the layer); the extinction is
    // scene().extinction times it.
    float density(glm::vec3 p, float alt) const { return density(p, alt, nullptr); }
    float density(glm::vec3 p) const { return density(p, altitude(p)); }
    // The same, adding to *texture_reads the texture() calls the shader makes for it: none
    // outside the layer, the weather map and the base volume inside it, and the detail
    // volume where the base cloud survives coverage (cr_density's early exits).
    float density(glm::vec3 p, float alt, long* texture_reads) const;
    // The base shape alone (cr_base_density): the density before the detail erodes it, an
    // upper bound of density() from the weather map and the base volume only (2 reads inside
    // the layer, none outside).
    float base_density(glm::vec3 p, float alt, long* texture_reads = nullptr) const;
    // The detail's erosion of the base shape `covered` (base_density's value at p): density()
    // is detail_density(p, alt, base_density(p, alt)) (cr_detail_density; the detail volume,
    // and the curl map for the detailed shape, read only where covered > 0).
    float detail_density(glm::vec3 p, float alt, float covered, long* texture_reads = nullptr) const;

    const scene& scene_data() const { return s_; }
    const linear_texture& base() const { return base_; }
    const linear_texture& detail() const { return detail_; }
    const linear_texture& weather() const { return weather_; }
    const linear_texture& weather_wide() const { return weather_wide_; }

private:
    const scene& s_;
    linear_texture base_, detail_, weather_, weather_wide_, curl_;
};

// The sky seen in direction dir (unit, camera frame): the zenith-horizon gradient by dir.y
// and the sun's aureole aureole HG(mu, 0.75) sun_radiance (the artistic sky), or the physical
// sky's sky-view table at the camera (frame_constants::sky_view); with sun_disc, the drawn disc
// on top (sun_disc_radiance: the irradiance sun_radiance over the disc's solid angle,
// limb-darkened, about 18,000 sun_radiance at its centre). No ground test.
glm::vec3 sky_radiance(const frame_constants& k, glm::vec3 dir, bool sun_disc);
// What the camera sees behind the clouds in direction dir (cr_background): the ground colour
// where the ray from the camera hits the planet, else sky_radiance, with the disc if sun_disc.
glm::vec3 background(const scene& s, const frame_constants& k, glm::vec3 dir, bool sun_disc = true);

// The renderer's display transform: 1 - exp(-c exposure), then gamma 1/2.2.
glm::vec3 tonemap(glm::vec3 c, float exposure);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_CLOUD_DENSITY_HPP
