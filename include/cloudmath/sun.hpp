// cloudmath/sun.hpp: the Sun's disc as a light source seen directly: its angular size, the
// solid angle of a cone, and the disc's limb-darkened radiance for a given irradiance.
//
// Use:      #include <cloudmath/sun.hpp>
//           glm::vec3 sky = ...;  // the sky without the sun
//           sky += sun_color * cloudmath::sun_disc_radiance(1.0f, dot(view_dir, sun_dir),
//                                                           cloudmath::sun_angular_radius<float>(), 0.6f);
// Units:    `irradiance` is what the sun delivers to a surface facing it (the same number a
//           lighting model multiplies by the phase function); the disc's radiance is that over
//           its solid angle, about 14,700 times larger for the real Sun.
// Why:      a sun disc drawn as "irradiance times a constant" is thousands of times too dim,
//           and one drawn wider than 0.53 degrees is too big; both show in every HDR pipeline.
// Source:   solid angle 2 pi (1 - cos r); linear limb darkening I = I0 (1 - u (1 - cos psi))
//           (Milne 1921; u about 0.6 in the visible, Cox, "Allen's Astrophysical Quantities",
//           2000), normalised so the disc delivers the irradiance.
// GLSL twin: cloudmath/glsl/sun.glsl.
#ifndef CLOUDMATH_SUN_HPP
#define CLOUDMATH_SUN_HPP

#include <cmath>

#include "core.hpp"

namespace cloudmath {

// The Sun's mean angular radius seen from the Earth: 4.6524e-3 rad (0.26656 degrees; its mean
// apparent diameter is 31.99 arcminutes, varying by +-1.7% over the year).
template <class T>
[[nodiscard]] constexpr T sun_angular_radius() noexcept {
    return T(4.6524e-3L);
}

// cone_solid_angle(r) = 2 pi (1 - cos r), the solid angle of a cone of half-angle r (radians),
// written 4 pi sin^2(r / 2) so small cones keep full precision (1 - cos r cancels in float
// below r = 3e-4). Domain 0 <= r <= pi.
template <class T>
[[nodiscard]] inline T cone_solid_angle(T angular_radius) noexcept {
    const T s = std::sin(angular_radius * T(0.5));
    return T(4) * pi_v<T> * s * s;
}

// sun_disc_radiance(irradiance, cos_angle, angular_radius, limb_darkening): the radiance of
// a sun disc toward a direction at angle theta from its centre (cos_angle = dot(view, sun)),
// 0 outside the disc. Linear limb darkening: I = I0 (1 - u (1 - cos psi)) with
// cos psi = sqrt(1 - sin^2 theta / sin^2 r), and I0 = irradiance / (cone_solid_angle(r) (1 - u/3))
// so that the disc's radiance integrated over its solid angle is the irradiance (to 0.06 r^2
// relative for r up to 0.91 rad, 1.3e-6 at the Sun's radius; beyond 0.91 rad the bound
// grows past 0.06 r^2). sin^2 theta is (1 - c)(1 + c), exact for c near 1.
// limb_darkening is clamped to [0, 1] (0: a flat disc); angular_radius in (0, pi/2). In
// float, cos_angle resolves the real Sun's radius in about 180 steps (1 - cos r = 1.08e-5
// against its spacing of 6e-8): enough for a disc a few pixels wide; a renderer that zooms
// onto the limb should pass a cosine computed in double or from a cross product.
template <class T>
[[nodiscard]] inline T sun_disc_radiance(T irradiance, T cos_angle, T angular_radius, T limb_darkening) noexcept {
    const T c = detail::clamp(cos_angle, T(-1), T(1));
    const T sin_r = std::sin(angular_radius);
    const T one_minus_c = T(1) - c;  // exact for c near 1 (Sterbenz)
    const T x2 = one_minus_c * (T(2) - one_minus_c) / (sin_r * sin_r);  // (sin theta / sin r)^2
    if (!(x2 <= T(1)) || c <= T(0)) return T(0);
    const T u = saturate(limb_darkening);
    const T peak = irradiance / (cone_solid_angle(angular_radius) * (T(1) - u / T(3)));
    return peak * (T(1) - u + u * std::sqrt(T(1) - x2));
}

}  // namespace cloudmath

#endif  // CLOUDMATH_SUN_HPP
