// cloudmath/wgsl/geometry.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/geometry.glsl: GLSL twin of cloudmath/geometry.hpp: ray/sphere roots and
// planet-scale cloud-layer segments in the altitude form, accurate in float at Earth radius
// (c = (h - H)(2R + h + H) and a cancellation-free discriminant; see geometry.hpp).
// Results are vec2(t_near, t_far); vec2(-1) when the line misses.

// Roots of t^2 + 2 b t + c = 0 with disc = b^2 - c >= 0, sorted; stable q form.
fn cmi_stable_quadratic_roots(b: f32, c: f32, disc: f32) -> vec2f {
    let sq: f32 = sqrt(disc);
    let q: f32 = select((sq - b), -(b + sq), b >= 0.0);
    let t1: f32 = select(0.0, c / q, q != 0.0);
    return select(vec2f(t1, q), vec2f(q, t1), q < t1);
}

// A secant crossing the sphere ahead of the origin (a tangent contact does not count).
fn cmi_enters_ahead(roots: vec2f) -> bool { return roots.x >= 0.0 && roots.y > roots.x; }

// Error-free a * b = p + e (returned as vec2(p, e)) and a + b = s + e (Dekker's split,
// no FMA needed; geometry.hpp's two_product and two_sum). The split needs a * 4097 rounded
// before the subtraction: a compiler that fuses as - (as - a) into fma(a, 4097, -...) loses
// the exactness (measured: the HLSL twin through spirv-opt, 1.4e-5 off). CM_PRECISE (core.glsl)
// forbids that where the language can: `precise` in HLSL, and in GLSL 4.00+ if you define it so.
fn cmi_two_product(a: f32, b: f32) -> vec2f {
    let p: f32 = a * b;
    let as_: f32 = a * 4097.0;
    let bs: f32 = b * 4097.0;
    let ah: f32 = as_ - (as_ - a);
    let al: f32 = a - ah;
    let bh: f32 = bs - (bs - b);
    let bl: f32 = b - bh;
    let e: f32 = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return vec2f(p, e);
}
fn cmi_two_sum(a: f32, b: f32) -> vec2f {
    let s: f32 = a + b;
    let bb: f32 = s - a;
    let e: f32 = (a - (s - bb)) + (b - bb);
    return vec2f(s, e);
}

// |f|^2 - r^2 with the rounding errors of its products and sums added back; the plain form
// when a split overflows.
fn cmi_norm2_minus_square(f: vec3f, r: f32) -> f32 {
    let x: vec2f = cmi_two_product(f.x, f.x);
    let y: vec2f = cmi_two_product(f.y, f.y);
    let z: vec2f = cmi_two_product(f.z, f.z);
    let rr: vec2f = cmi_two_product(r, r);
    var s: vec2f = cmi_two_sum(x.x, y.x);
    var err: f32 = x.y + y.y + s.y;
    s = cmi_two_sum(s.x, z.x);
    err += z.y + s.y;
    s = cmi_two_sum(s.x, -rr.x);
    err += s.y - rr.y;
    let c: f32 = s.x + err;
    return select(dot(f, f) - r * r, c, abs(c) <= 3.402823466e38);
}

// Unit dir; c compensated, the discriminant b^2 - c near the sphere and Haines et al.'s
// r^2 - |f - (f.d) d|^2 far from it (geometry.hpp).
fn cm_ray_sphere_intersect(origin: vec3f, dir: vec3f, center: vec3f, radius: f32) -> vec2f {
    let f: vec3f = origin - center;
    let b: f32 = dot(f, dir);
    let c: f32 = cmi_norm2_minus_square(f, radius);
    var disc: f32;
    if (abs(c) < radius * radius) {
        let bb: vec2f = cmi_two_product(b, b);
        disc = (bb.x - c) + bb.y;
    } else {
        let perp: vec3f = f - b * dir;
        disc = radius * radius - dot(perp, perp);
    }
    if (disc < 0.0) { return vec2f(-1.0); }
    return cmi_stable_quadratic_roots(b, c, disc);
}

fn cm_ray_sphere_intersect_altitude(altitude: f32, cos_zenith: f32, planet_radius: f32, sphere_altitude: f32) -> vec2f {
    let mu: f32 = clamp(cos_zenith, -1.0, 1.0);
    let h: f32 = altitude;
    let H: f32 = sphere_altitude;
    let R: f32 = planet_radius;
    let r: f32 = R + h;
    let s: f32 = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    let disc: f32 = ((H - h) + r * mu * mu / (1.0 + s)) * ((R + H) + r * s);
    if (disc < 0.0) { return vec2f(-1.0); }
    let b: f32 = r * mu;
    let c: f32 = (h - H) * (2.0 * R + h + H);
    return cmi_stable_quadratic_roots(b, c, disc);
}

fn cm_cloud_layer_segment(altitude: f32, cos_zenith: f32, planet_radius: f32, layer_bottom: f32, layer_top: f32) -> vec2f {
    let none: vec2f = vec2f(-1.0);
    let h: f32 = max(altitude, 0.0);
    let bottom: f32 = min(layer_bottom, layer_top);
    let top: f32 = max(layer_bottom, layer_top);
    let to_top: vec2f = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, top);
    let to_bottom: vec2f = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, bottom);
    let to_ground: vec2f = cm_ray_sphere_intersect_altitude(h, cos_zenith, planet_radius, 0.0);
    var t_start: f32;
    var t_end: f32;
    if (h < bottom) {
        t_start = to_bottom.y;
        t_end = to_top.y;
    } else if (h <= top) {
        t_start = 0.0;
        t_end = select(to_top.y, to_bottom.x, cmi_enters_ahead(to_bottom));
    } else {
        if (!cmi_enters_ahead(to_top)) { return none; }
        t_start = to_top.x;
        t_end = select(to_top.y, to_bottom.x, cmi_enters_ahead(to_bottom));
    }
    if (cmi_enters_ahead(to_ground)) {
        if (to_ground.x <= t_start) { return none; }
        t_end = min(t_end, to_ground.x);
    }
    return vec2f(t_start, t_end);
}

fn cm_altitude_along_ray(altitude: f32, cos_zenith: f32, planet_radius: f32, t: f32) -> f32 {
    let mu: f32 = clamp(cos_zenith, -1.0, 1.0);
    let R: f32 = planet_radius;
    let r: f32 = R + altitude;
    let excess: f32 = altitude * (2.0 * R + altitude) + t * (2.0 * r * mu + t);
    let radius: f32 = sqrt(max(R * R + excess, 0.0));
    return excess / (radius + R);
}

// Altitude of p given relative to the camera (+y up at the camera); the camera at p = 0.
fn cm_point_altitude(p: vec3f, camera_altitude: f32, planet_radius: f32) -> f32 {
    let t: f32 = length(p);
    if (t > 0.0) {
        return cm_altitude_along_ray(camera_altitude, p.y / t, planet_radius, t);
    }
    return camera_altitude;
}

fn cm_height_fraction(altitude: f32, layer_bottom: f32, layer_top: f32) -> f32 {
    return cmi_remap_unit(altitude, layer_bottom, layer_top); // cm_remap_clamped(..., 0.0, 1.0)
}
