// cloudmath/hlsl/geometry.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/geometry.hlsl: GLSL twin of cloudmath/geometry.hpp: ray/sphere roots and
// planet-scale cloud-layer segments in the altitude form, accurate in float at Earth radius
// (c = (h - H)(2R + h + H) and a cancellation-free discriminant; see geometry.hpp).
// Results are vec2(t_near, t_far); vec2(-1) when the line misses.
#ifndef CM_GEOMETRY_HLSL
#define CM_GEOMETRY_HLSL

#include "core.hlsl"

// Roots of t^2 + 2 b t + c = 0 with disc = b^2 - c >= 0, sorted; stable q form.
float2 cmi_stable_quadratic_roots(float b, float c, float disc) {
    float sq = sqrt(disc);
    float q = b >= 0.0 ? -(b + sq) : (sq - b);
    float t1 = q != 0.0 ? c / q : 0.0;
    return q < t1 ? float2(q, t1) : float2(t1, q);
}

// A secant crossing the sphere ahead of the origin (a tangent contact does not count).
bool cmi_enters_ahead(float2 roots) { return roots.x >= 0.0 && roots.y > roots.x; }

// Error-free a * b = p + e (returned as vec2(p, e)) and a + b = s + e (Dekker's split,
// no FMA needed; geometry.hpp's two_product and two_sum). The split needs a * 4097 rounded
// before the subtraction: a compiler that fuses as - (as - a) into fma(a, 4097, -...) loses
// the exactness (measured: the HLSL twin through spirv-opt, 1.4e-5 off). CM_PRECISE (core.hlsl)
// forbids that where the language can: `precise` in HLSL, and in GLSL 4.00+ if you define it so.
float2 cmi_two_product(float a, float b) {
    CM_PRECISE float p = a * b;
    CM_PRECISE float as = a * 4097.0;
    CM_PRECISE float bs = b * 4097.0;
    CM_PRECISE float ah = as - (as - a);
    CM_PRECISE float al = a - ah;
    CM_PRECISE float bh = bs - (bs - b);
    CM_PRECISE float bl = b - bh;
    CM_PRECISE float e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return float2(p, e);
}
float2 cmi_two_sum(float a, float b) {
    CM_PRECISE float s = a + b;
    CM_PRECISE float bb = s - a;
    CM_PRECISE float e = (a - (s - bb)) + (b - bb);
    return float2(s, e);
}

// |f|^2 - r^2 with the rounding errors of its products and sums added back; the plain form
// when a split overflows.
float cmi_norm2_minus_square(float3 f, float r) {
    float2 x = cmi_two_product(f.x, f.x);
    float2 y = cmi_two_product(f.y, f.y);
    float2 z = cmi_two_product(f.z, f.z);
    float2 rr = cmi_two_product(r, r);
    float2 s = cmi_two_sum(x.x, y.x);
    float err = x.y + y.y + s.y;
    s = cmi_two_sum(s.x, z.x);
    err += z.y + s.y;
    s = cmi_two_sum(s.x, -rr.x);
    err += s.y - rr.y;
    float c = s.x + err;
    return abs(c) <= 3.402823466e38 ? c : dot(f, f) - r * r;
}

// Unit dir; c compensated, the discriminant b^2 - c near the sphere and Haines et al.'s
// r^2 - |f - (f.d) d|^2 far from it (geometry.hpp).
float2 cm_ray_sphere_intersect(float3 origin, float3 dir, float3 center, float radius) {
    float3 f = origin - center;
    float b = dot(f, dir);
    float c = cmi_norm2_minus_square(f, radius);
    float disc;
    if (abs(c) < radius * radius) {
        float2 bb = cmi_two_product(b, b);
        disc = (bb.x - c) + bb.y;
    } else {
        float3 perp = f - b * dir;
        disc = radius * radius - dot(perp, perp);
    }
    if (disc < 0.0) return float2(-1.0, -1.0);
    return cmi_stable_quadratic_roots(b, c, disc);
}

float2 cm_ray_sphere_intersect_altitude(float altitude, float cos_zenith, float planet_radius, float sphere_altitude) {
    float mu = clamp(cos_zenith, -1.0, 1.0);
    float h = altitude;
    float H = sphere_altitude;
    float R = planet_radius;
    float r = R + h;
    float s = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    float disc = ((H - h) + r * mu * mu / (1.0 + s)) * ((R + H) + r * s);
    if (disc < 0.0) return float2(-1.0, -1.0);
    float b = r * mu;
    float c = (h - H) * (2.0 * R + h + H);
    return cmi_stable_quadratic_roots(b, c, disc);
}

float2 cm_cloud_layer_segment(float altitude, float cos_zenith, float planet_radius, float layer_bottom, float layer_top) {
    float2 none = float2(-1.0, -1.0);
    float h = max(altitude, 0.0);
    float bottom = min(layer_bottom, layer_top);
    float top = max(layer_bottom, layer_top);
    float2 to_top = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, top);
    float2 to_bottom = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, bottom);
    float2 to_ground = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, 0.0);
    float t_start;
    float t_end;
    if (h < bottom) {
        t_start = to_bottom.y;
        t_end = to_top.y;
    } else if (h <= top) {
        t_start = 0.0;
        t_end = cmi_enters_ahead(to_bottom) ? to_bottom.x : to_top.y;
    } else {
        if (!cmi_enters_ahead(to_top)) return none;
        t_start = to_top.x;
        t_end = cmi_enters_ahead(to_bottom) ? to_bottom.x : to_top.y;
    }
    if (cmi_enters_ahead(to_ground)) {
        if (to_ground.x <= t_start) return none;
        t_end = min(t_end, to_ground.x);
    }
    return float2(t_start, t_end);
}

float cm_altitude_along_ray(float altitude, float cos_zenith, float planet_radius, float t) {
    float mu = clamp(cos_zenith, -1.0, 1.0);
    float R = planet_radius;
    float r = R + altitude;
    float excess = altitude * (2.0 * R + altitude) + t * (2.0 * r * mu + t);
    float radius = sqrt(max(R * R + excess, 0.0));
    return excess / (radius + R);
}

// Altitude of p given relative to the camera (+y up at the camera); the camera at p = 0.
float cm_point_altitude(float3 p, float camera_altitude, float planet_radius) {
    float t = length(p);
    return t > 0.0 ? cm_altitude_along_ray(camera_altitude, p.y / t, planet_radius, t) : camera_altitude;
}

float cm_height_fraction(float altitude, float layer_bottom, float layer_top) {
    return cmi_remap_unit(altitude, layer_bottom, layer_top); // cm_remap_clamped(..., 0.0, 1.0)
}

#endif // CM_GEOMETRY_HLSL
