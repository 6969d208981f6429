// cloudmath/texture_lod.hpp: explicit texture level of detail for a ray march: the width of a
// pixel's footprint at a distance, and the mip level whose texels match it. A march that
// samples a noise volume far away with level 0 aliases (the sparkle and grain of distant
// clouds, and a cache miss per sample on a GPU); the level that matches the footprint filters
// what the pixel cannot show anyway.
//
// Use:      #include <cloudmath/texture_lod.hpp>
//           float w = cloudmath::pixel_footprint(t, tan_half_fov, float(image_height));
//           float lod = cloudmath::texture_lod(w, tile_metres / float(texture_size));
//           // GLSL: textureLod(u_detail, q / tile, lod) (a loop has no implicit derivatives)
// Why explicit: inside a ray-march loop implicit derivatives are undefined (non-uniform
//           control flow) and, where defined, measure the screen-space change of the texture
//           coordinate between neighbouring pixels' samples at different depths, not the
//           footprint at this sample.
// GLSL twin: cloudmath/glsl/texture_lod.glsl.
#ifndef CLOUDMATH_TEXTURE_LOD_HPP
#define CLOUDMATH_TEXTURE_LOD_HPP

#include <cmath>

namespace cloudmath {

// pixel_footprint(distance, tan_half_fov, image_height): the width covered by one pixel of a
// pinhole camera (vertical field of view 2 atan(tan_half_fov) over image_height pixels) at
// `distance` along its ray: distance 2 tan_half_fov / image_height. The small-angle width
// at the image centre (off-axis pixels are up to 1 / cos^2 of their angle wider: 1.33 at the
// edge of a 60-degree view). Negative distances give negative widths (texture_lod maps them
// to level 0).
template <class T>
[[nodiscard]] constexpr T pixel_footprint(T distance, T tan_half_fov, T image_height) noexcept {
    return distance * (T(2) * tan_half_fov / image_height);
}

// texture_lod(footprint, texel_size): the mip level whose texels are as wide as the footprint,
// log2(footprint / texel_size) (OpenGL's lambda = log2(rho) with rho in level-0 texels), and
// 0 where the footprint is no wider than a texel (magnification), not positive, or NaN. Both
// in the same unit (texel_size = the world width of one level-0 texel: tile / size). The
// caller's sampler clamps to the last level.
template <class T>
[[nodiscard]] inline T texture_lod(T footprint, T texel_size) noexcept {
    const T ratio = footprint / texel_size;
    return ratio > T(1) ? std::log2(ratio) : T(0);
}

}  // namespace cloudmath

#endif  // CLOUDMATH_TEXTURE_LOD_HPP
