// cloudmath/glsl/shadow_map.glsl: GLSL twin of cloudmath/shadow_map.hpp: the Beer shadow map's
// texel built by a march along the sunlight, the optical depth and transmittance it gives at a
// depth, and the projection of a point into the sun-aligned map.
// Use: CmBeerShadowAccumulator acc = cm_beer_shadow_accumulator();
//      cm_beer_shadow_add_step(acc, t, ds, sigma_t);  ...  out_texel = cm_beer_shadow_texel(acc);
//      vec3 uvd = cm_shadow_map_project(p, origin, right, up, toward_sun, half_extent);
//      float T = cm_beer_shadow_transmittance(texture(shadow_map, uvd.xy).xyz, uvd.z);
#ifndef CM_SHADOW_MAP_GLSL
#define CM_SHADOW_MAP_GLSL

#include "core.glsl"

// front > back while the march has met no extinction; covered: the steps' length with extinction.
struct CmBeerShadowAccumulator {
    float front;
    float back;
    float optical_depth;
    float covered;
};

CmBeerShadowAccumulator cm_beer_shadow_accumulator() { return CmBeerShadowAccumulator(1.0, 0.0, 0.0, 0.0); }

// Adds the step [t, t + ds) of extinction sigma_t; steps without extinction change nothing.
void cm_beer_shadow_add_step(inout CmBeerShadowAccumulator acc, float t, float ds, float sigma_t) {
    if (!(sigma_t > 0.0) || !(ds > 0.0)) return;
    if (acc.front > acc.back) acc.front = t;
    acc.back = t + ds;
    acc.optical_depth += sigma_t * ds;
    acc.covered += ds;
}

// (front depth, mean extinction over back - front, total optical depth); empty: 0. Steps
// shorter than the rounding of t (back == front): over their own length (finite, not +Inf).
vec3 cm_beer_shadow_texel(CmBeerShadowAccumulator acc) {
    if (acc.front > acc.back) return vec3(0.0);
    float column = acc.back > acc.front ? acc.back - acc.front : acc.covered;
    return vec3(acc.front, acc.optical_depth / column, acc.optical_depth);
}

// min(max(depth - front, 0) mean_extinction, total).
float cm_beer_shadow_optical_depth(vec3 texel, float depth) {
    float d = depth - texel.x;
    if (d != d) return d;
    float tau = max(d, 0.0) * texel.y;
    return tau < texel.z ? tau : texel.z;
}

float cm_beer_shadow_transmittance(vec3 texel, float depth) { return exp(-cm_beer_shadow_optical_depth(texel, depth)); }

// (u, v) across the 2 half_extent square around origin, depth along the light from the plane.
vec3 cm_shadow_map_project(vec3 p, vec3 origin, vec3 right, vec3 up, vec3 toward_sun, float half_extent) {
    vec3 q = p - origin;
    float s = 0.5 / half_extent;
    return vec3(0.5 + dot(q, right) * s, 0.5 + dot(q, up) * s, -dot(q, toward_sun));
}

#endif  // CM_SHADOW_MAP_GLSL
