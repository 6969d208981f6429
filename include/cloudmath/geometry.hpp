// cloudmath/geometry.hpp: ray/sphere intersection, planet-scale cloud-layer segments and
// height fractions, accurate in float at Earth radius.
//
// Use:      #include <cloudmath/geometry.hpp>
//           glm::vec2 seg = cloudmath::cloud_layer_segment(cam_alt, dir.y, 6371e3f, 1500.f, 4000.f);
//           if (seg.y > seg.x) march from seg.x to seg.y;
// Units:    distances in any consistent unit (metres in the examples). Directions are unit
//           vectors. cos_zenith is the cosine between the ray and the local up direction
//           (the radial direction through the ray origin); it is clamped to [-1, 1].
// Results:  glm::vec<2, T>(t_near, t_far), distances along the ray, t_near <= t_far; the
//           sentinel (-1, -1) means the line misses. A sphere behind the ray origin gives
//           negative distances; test t_far >= 0 for "in front". NaN inputs give NaN
//           distances (IEEE builds; unspecified under -ffast-math).
// Accuracy: why the altitude forms exist. At R = 6371 km, the textbook quadratic in float
//           computes c = |o|^2 - r^2 from two numbers near 4e13 and loses tens of metres;
//           the altitude form takes c = (h - H)(2R + h + H) from the altitudes directly,
//           writes the discriminant as a product without cancellation (derived below) and
//           takes the small root as c / q (stable quadratic). Measured maximum relative
//           error of the first positive root in float: a few 1e-7 (tests/test_geometry.cpp)
//           against 2e-4 to 1e-3 for the textbook form.
// GLSL twin: cloudmath/glsl/geometry.glsl.
#ifndef CLOUDMATH_GEOMETRY_HPP
#define CLOUDMATH_GEOMETRY_HPP

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "core.hpp"

namespace cloudmath {

namespace detail {

// Roots of t^2 + 2 b t + c = 0 given disc = b^2 - c >= 0, as (smaller, larger).
// q = -(b + sign(b) sqrt(disc)) never cancels; the other root is c / q. When q == 0 both
// b and disc are 0, so c is 0 too and the double root is 0.
template <class T>
inline glm::vec<2, T> stable_quadratic_roots(T b, T c, T disc) noexcept {
    const T sq = std::sqrt(disc);
    const T q = b >= T(0) ? -(b + sq) : (sq - b);
    const T t0 = q;
    const T t1 = q != T(0) ? c / q : T(0);
    return t0 < t1 ? glm::vec<2, T>(t0, t1) : glm::vec<2, T>(t1, t0);
}

// True when the roots describe a ray that crosses the sphere ahead of the origin (a secant
// with its first point at t >= 0); tangent contacts (equal roots) do not count, so a
// horizontal ray that grazes a sphere at the origin is not stopped by it.
template <class T>
constexpr bool enters_ahead(const glm::vec<2, T>& roots) noexcept {
    return roots.x >= T(0) && roots.y > roots.x;
}

}  // namespace detail

// ---------------------------------------------------------------------------------------
// ray_sphere_intersect(origin, dir, center, radius) for a unit dir.
// Discriminant as radius^2 - |f - (f.d) d|^2 (Haines, Guenther & Akenine-Moeller, "Precision
// improvements for ray/sphere intersection", Ray Tracing Gems ch. 7, 2019), roots by the
// stable quadratic. Returns (-1, -1) when the line misses. For planet-scale spheres in
// float, prefer ray_sphere_intersect_altitude: the inputs themselves (a position 6.4e6 m
// from the centre) carry metres of rounding that no formula can recover.
template <class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<2, T, Q> ray_sphere_intersect(const glm::vec<3, T, Q>& origin,
                                                            const glm::vec<3, T, Q>& dir,
                                                            const glm::vec<3, T, Q>& center,
                                                            T radius) noexcept {
    const glm::vec<3, T, Q> f = origin - center;
    const T b = glm::dot(f, dir);
    const glm::vec<3, T, Q> perp = f - b * dir;  // part of f perpendicular to the ray
    const T disc = radius * radius - glm::dot(perp, perp);
    if (disc < T(0)) return glm::vec<2, T, Q>(T(-1));
    const T c = glm::dot(f, f) - radius * radius;
    const glm::vec<2, T> r = detail::stable_quadratic_roots(b, c, disc);
    return glm::vec<2, T, Q>(r.x, r.y);
}

// ---------------------------------------------------------------------------------------
// ray_sphere_intersect_altitude(altitude, cos_zenith, planet_radius, sphere_altitude):
// distances from a point `altitude` above a planet of radius R, along a ray with zenith
// cosine mu, to the sphere of radius R + H (H = sphere_altitude). With r = R + h:
//   |p(t)|^2 = r^2 + 2 t r mu + t^2 = (R + H)^2  ->  t^2 + 2 b t + c = 0,
//   b = r mu,  c = r^2 - (R + H)^2 = (h - H)(2R + h + H)           (no cancellation),
//   b^2 - c = (R + H)^2 - (r s)^2 with s = sqrt(1 - mu^2)
//           = [(H - h) + r mu^2 / (1 + s)] [(R + H) + r s]         (since 1 - s = mu^2/(1+s)).
// The second factor is a sum of positive terms; the first is too whenever the sphere is
// above the point (H >= h), and otherwise cancels only in exactly computed small terms.
// (-1, -1) when the ray's line misses the sphere.
template <class T>
[[nodiscard]] inline glm::vec<2, T> ray_sphere_intersect_altitude(T altitude, T cos_zenith,
                                                                  T planet_radius,
                                                                  T sphere_altitude) noexcept {
    const T mu = detail::clamp(cos_zenith, T(-1), T(1));
    const T h = altitude;
    const T H = sphere_altitude;
    const T R = planet_radius;
    const T r = R + h;
    const T s = std::sqrt(detail::max((T(1) - mu) * (T(1) + mu), T(0)));
    const T disc = ((H - h) + r * mu * mu / (T(1) + s)) * ((R + H) + r * s);
    if (disc < T(0)) return glm::vec<2, T>(T(-1));
    const T b = r * mu;
    const T c = (h - H) * (T(2) * R + h + H);
    return detail::stable_quadratic_roots(b, c, disc);
}

// ---------------------------------------------------------------------------------------
// cloud_layer_segment(altitude, cos_zenith, planet_radius, layer_bottom, layer_top):
// (t_start, t_end) of the first stretch of the ray inside the spherical shell between
// R + layer_bottom and R + layer_top, for a ray starting below, inside or above it, and
// stopped by the ground (the sphere of radius R).
//   below:  from leaving the bottom sphere to leaving the top sphere; nothing if the ray
//           hits the ground first.
//   inside: from 0 to hitting the bottom sphere, or to leaving the top sphere.
//   above:  from entering the top sphere to hitting the bottom sphere, or to leaving the
//           top sphere again (a ray that only clips the top of the layer).
// When there is no such stretch, t_end <= t_start (the sentinel (-1, -1) where the ray
// never reaches the layer). Tangent rays that touch a sphere in a single point pass it.
// Bad input: altitude below 0 is treated as 0 (on the ground); layer_bottom > layer_top
// are swapped; a layer of zero thickness gives an empty stretch. A NaN in any argument
// (IEEE builds) gives NaN or the sentinel, never a non-empty stretch: t_end > t_start is
// false, so a march loop over the result does nothing.
template <class T>
[[nodiscard]] inline glm::vec<2, T> cloud_layer_segment(T altitude, T cos_zenith,
                                                        T planet_radius, T layer_bottom,
                                                        T layer_top) noexcept {
    const glm::vec<2, T> none(T(-1));
    const T h = detail::max(altitude, T(0));
    const T bottom = detail::min(layer_bottom, layer_top);
    const T top = detail::max(layer_bottom, layer_top);
    const glm::vec<2, T> to_top = ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, top);
    const glm::vec<2, T> to_bottom =
        ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, bottom);
    const glm::vec<2, T> to_ground =
        ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, T(0));

    T t_start, t_end;
    if (h < bottom) {
        t_start = to_bottom.y;  // inside the bottom sphere: its far root is the only positive one
        t_end = to_top.y;
    } else if (h <= top) {
        t_start = T(0);
        t_end = detail::enters_ahead(to_bottom) ? to_bottom.x : to_top.y;
    } else {
        if (!detail::enters_ahead(to_top)) return none;
        t_start = to_top.x;
        t_end = detail::enters_ahead(to_bottom) ? to_bottom.x : to_top.y;
    }
    if (detail::enters_ahead(to_ground)) {
        if (to_ground.x <= t_start) return none;
        t_end = detail::min(t_end, to_ground.x);
    }
    return glm::vec<2, T>(t_start, t_end);
}

// altitude_along_ray(altitude, cos_zenith, planet_radius, t): altitude of the point at
// distance t along the ray, without the cancellation of |p| - R in float:
//   |p(t)|^2 - R^2 = h (2R + h) + t (2 r mu + t),  altitude = (|p|^2 - R^2) / (|p| + R).
// Use it for height fractions while marching a planet-scale layer.
template <class T>
[[nodiscard]] inline T altitude_along_ray(T altitude, T cos_zenith, T planet_radius,
                                          T t) noexcept {
    const T mu = detail::clamp(cos_zenith, T(-1), T(1));
    const T R = planet_radius;
    const T r = R + altitude;
    const T excess = altitude * (T(2) * R + altitude) + t * (T(2) * r * mu + t);
    const T radius = std::sqrt(detail::max(R * R + excess, T(0)));
    return excess / (radius + R);
}

// height_fraction(altitude, layer_bottom, layer_top) = saturate((altitude - bottom) /
// (top - bottom)): 0 at the bottom of the layer, 1 at the top. A layer of zero thickness
// gives the step of remap_clamped (0 below, 1 at and above). Domain: every finite input
// (no overflow for huge altitudes, as remap_clamped); the result is in [0, 1].
template <class T>
[[nodiscard]] constexpr T height_fraction(T altitude, T layer_bottom, T layer_top) noexcept {
    return detail::remap_unit(altitude, layer_bottom, layer_top);  // remap_clamped(..., 0, 1)
}

}  // namespace cloudmath

#endif  // CLOUDMATH_GEOMETRY_HPP
