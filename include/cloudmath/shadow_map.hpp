// cloudmath/shadow_map.hpp: a Beer shadow map for clouds: per texel of a sun-aligned
// orthographic map, three numbers from one march along the sunlight (where the cloud starts,
// its mean extinction, its total optical depth) give the optical depth toward the sun at any
// depth behind the map plane: cloud shadows on the ground, and an estimate of the optical
// depth along the sun's whole chord for the lighting model.
//
// Use:      #include <cloudmath/shadow_map.hpp>
//           // Building texel (u, v): march along the sunlight from the map plane.
//           cloudmath::beer_shadow_accumulator<float> acc;
//           for (each step [t, t + ds) with extinction sigma_t) acc.add_step(t, ds, sigma_t);
//           glm::vec3 texel = acc.texel();            // store (front, mean extinction, depth)
//           // Looking up a point p (camera-relative):
//           glm::vec3 uvd = cloudmath::shadow_map_project(p, origin, right, up, toward_sun, half_extent);
//           float T = cloudmath::beer_shadow_transmittance(texel_at(uvd.x, uvd.y), uvd.z);
// Model:    the optical depth at depth d is min(max(d - front, 0) mean_extinction, total): zero
//           in front of the cloud, linear through it, the whole column behind it. Exact for one
//           homogeneous cloud per texel; for several clouds or varying density, exact in
//           front of the first and behind the last, and within the column it spreads the total
//           evenly (the error the tests bound). Source: the Beer shadow map of
//           three-geospatial's clouds (shadow.frag: front depth, mean extinction, maximum
//           optical depth per texel; REFERENCES.md, "Beer shadow map").
// Units:    depths and ds in metres along the sunlight (any unit, consistently); sigma_t per
//           that unit.
// GLSL twin: cloudmath/glsl/shadow_map.glsl.
#ifndef CLOUDMATH_SHADOW_MAP_HPP
#define CLOUDMATH_SHADOW_MAP_HPP

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace cloudmath {

// What one march along the sunlight through a texel has met: the depth where extinction
// started (front), where the last step with extinction ended (back), the optical depth
// between and the length of the steps with extinction (covered). front > back while nothing
// has been met.
template <class T>
struct beer_shadow_accumulator {
    T front = T(1);
    T back = T(0);
    T optical_depth = T(0);
    T covered = T(0);

    // Adds the step [t, t + ds) of extinction sigma_t (steps in order of increasing t).
    // Steps without extinction (sigma_t <= 0 or NaN) change nothing.
    void add_step(T t, T ds, T sigma_t) noexcept {
        if (!(sigma_t > T(0)) || !(ds > T(0))) return;
        if (front > back) front = t;
        back = t + ds;
        optical_depth += sigma_t * ds;
        covered += ds;
    }

    // The texel to store: (front depth, mean extinction, total optical depth). Mean
    // extinction is the total over back - front (the column's length, gaps included), so that
    // the linear model reaches the total at `back` (to within the rounding of the quotient and
    // of the lookup's product: at most two ulp short there, one ulp in about 5% of marches). Where
    // the steps are shorter than the rounding of t (ds below half an ulp of t: back == front),
    // the total over the steps' own length: the mean extinction stays finite (it was +Inf,
    // and the whole column was returned in front of the cloud). Empty: (0, 0, 0), no shadow.
    [[nodiscard]] glm::vec<3, T> texel() const noexcept {
        if (front > back) return glm::vec<3, T>(T(0));
        const T column = back > front ? back - front : covered;
        return glm::vec<3, T>(front, optical_depth / column, optical_depth);
    }
};

// beer_shadow_optical_depth(texel, depth): the optical depth toward the sun at `depth` along
// the sunlight, min(max(depth - front, 0) mean_extinction, total) for texel = (front,
// mean_extinction, total). Never negative, never above the total; NaN depth gives NaN.
template <class T>
[[nodiscard]] inline T beer_shadow_optical_depth(const glm::vec<3, T>& texel, T depth) noexcept {
    const T d = depth - texel.x;
    if (d != d) return d;
    const T tau = (d > T(0) ? d : T(0)) * texel.y;
    return tau < texel.z ? tau : texel.z;
}

// beer_shadow_transmittance(texel, depth) = exp(-beer_shadow_optical_depth(texel, depth)).
template <class T>
[[nodiscard]] inline T beer_shadow_transmittance(const glm::vec<3, T>& texel, T depth) noexcept {
    return std::exp(-beer_shadow_optical_depth(texel, depth));
}

// shadow_map_project(p, origin, right, up, toward_sun, half_extent): where point p lies in a
// sun-aligned orthographic map: (u, v) in [0, 1] across the map's 2 half_extent square
// centred on `origin`, and the depth along the sunlight from the map plane through `origin`
// (normal toward_sun; positive behind the plane as the light travels). right, up, toward_sun:
// an orthonormal basis. Outside the map u or v leave [0, 1]; the caller decides (usually: no
// shadow).
template <class T>
[[nodiscard]] inline glm::vec<3, T> shadow_map_project(const glm::vec<3, T>& p, const glm::vec<3, T>& origin,
                                                       const glm::vec<3, T>& right, const glm::vec<3, T>& up,
                                                       const glm::vec<3, T>& toward_sun, T half_extent) noexcept {
    const glm::vec<3, T> q = p - origin;
    const T s = T(0.5) / half_extent;
    return glm::vec<3, T>(T(0.5) + glm::dot(q, right) * s, T(0.5) + glm::dot(q, up) * s, -glm::dot(q, toward_sun));
}

}  // namespace cloudmath

#endif  // CLOUDMATH_SHADOW_MAP_HPP
