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
    const T t1 = detail::exactly_equal(q, T(0)) ? T(0) : c / q;
    return t0 < t1 ? glm::vec<2, T>(t0, t1) : glm::vec<2, T>(t1, t0);
}

// Error-free transformations (Dekker 1971; Knuth, TAOCP vol. 2, 4.2.2): a * b = p + e and
// a + b = s + e exactly, in round-to-nearest arithmetic and without an FMA (so that the GLSL
// twin can do the same). The split constant 2^ceil(digits / 2) + 1 cuts a number into two
// halves whose products are exact. Under -ffast-math the compiler may simplify the error
// terms away: then e = 0 and the callers fall back to the plain products' accuracy.
template <class T>
inline void two_product(T a, T b, T& p, T& e) noexcept {
    const T split = std::ldexp(T(1), (std::numeric_limits<T>::digits + 1) / 2) + T(1);
    p = a * b;
    const T as = a * split, bs = b * split;
    const T ah = as - (as - a), al = a - ah;
    const T bh = bs - (bs - b), bl = b - bh;
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

template <class T>
inline void two_sum(T a, T b, T& s, T& e) noexcept {
    s = a + b;
    const T bb = s - a;
    e = (a - (s - bb)) + (b - bb);
}

// |f|^2 - r^2 with every product's and sum's rounding error added back (a compensated dot
// product, Ogita, Rump & Oishi, "Accurate sum and dot product", 2005): a few ulp of the
// result even when |f| and r agree to 7 digits, as a camera near a planet-size sphere does
// in float (there the plain form loses a few 1e6 m^2 out of c ~ 2e10 m^2: metres of
// distance). When a split overflows (components beyond max / 4097 in float) the plain form.
template <class T, glm::qualifier Q>
inline T norm2_minus_square(const glm::vec<3, T, Q>& f, T r) noexcept {
    T s, err, p, e, es;
    two_product(f.x, f.x, s, err);
    two_product(f.y, f.y, p, e);
    two_sum(s, p, s, es);
    err += e + es;
    two_product(f.z, f.z, p, e);
    two_sum(s, p, s, es);
    err += e + es;
    two_product(r, r, p, e);
    two_sum(s, -p, s, es);
    err += es - e;
    const T c = s + err;
    if (abs(c) <= std::numeric_limits<T>::max()) return c;  // false for Inf and NaN
    return glm::dot(f, f) - r * r;
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
// c = |f|^2 - radius^2 (f = origin - center) by a compensated sum of exact products, so a
// camera metres from a planet-size sphere keeps its altitude's digits. The discriminant:
// near the sphere (|c| < radius^2: the origin within sqrt(2) radius of the centre) as
// b^2 - c with b^2 exact, which does not cancel there; far from a small sphere, where b^2
// and |f|^2 cancel instead, as radius^2 - |f - (f.d) d|^2 (Haines, Guenther &
// Akenine-Moeller, "Precision improvements for ray/sphere intersection", Ray Tracing Gems
// ch. 7, 2019). Roots by the stable quadratic. Returns (-1, -1) when the line misses.
// Measured in float, a camera 1.8 m above a 6371 km sphere at 64 places on it and a sphere
// 1500 m above the ground, rays from the zenith to the horizon, against long double on the
// same float inputs: worst distance error 0.20 m, against 14.0 m for the textbook quadratic
// and for Haines' discriminant with the plain c (tests/test_geometry.cpp prints them).
// Planet-scale users should still prefer ray_sphere_intersect_altitude (0.03 m): a
// position 6.4e6 m from the centre is itself rounded by up to 0.25 m in float.
template <class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<2, T, Q> ray_sphere_intersect(const glm::vec<3, T, Q>& origin,
                                                            const glm::vec<3, T, Q>& dir,
                                                            const glm::vec<3, T, Q>& center,
                                                            T radius) noexcept {
    const glm::vec<3, T, Q> f = origin - center;
    const T b = glm::dot(f, dir);
    const T c = detail::norm2_minus_square(f, radius);
    T disc;
    if (detail::abs(c) < radius * radius) {
        T bb, bb_error;
        detail::two_product(b, b, bb, bb_error);
        disc = (bb - c) + bb_error;
    } else {
        const glm::vec<3, T, Q> perp = f - b * dir;  // part of f perpendicular to the ray
        disc = radius * radius - glm::dot(perp, perp);
    }
    if (disc < T(0)) return glm::vec<2, T, Q>(T(-1));
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

// point_altitude(p, camera_altitude, planet_radius): altitude of the point p given relative
// to a camera `camera_altitude` above the planet, in the camera's local frame with +y up (the
// radial direction through the camera): altitude_along_ray along p's direction at distance
// |p|, so a point 100 km away keeps the centimetres that |p_planet| - R loses in float. The
// camera itself (p = 0) is at camera_altitude. For another up axis, pass p rotated so that
// up is +y (or call altitude_along_ray with dot(p, up) / |p|).
template <class T, glm::qualifier Q>
[[nodiscard]] inline T point_altitude(const glm::vec<3, T, Q>& p, T camera_altitude, T planet_radius) noexcept {
    const T t = glm::length(p);
    return t > T(0) ? altitude_along_ray(camera_altitude, p.y / t, planet_radius, t) : camera_altitude;
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
