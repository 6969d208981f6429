// cloudmath/wgsl/noise.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/noise.glsl: GLSL twin of cloudmath/noise.hpp: tileable improved Perlin
// (2D, 3D, analytic derivatives), Worley, fBm, Nubis Worley fBm, Perlin-Worley, curl noise.
// p in lattice cells; period = cells per tile (int >= 1); seed a uint (overloads without it
// use 0). The hashes are uint arithmetic and match the C++ bit for bit; in GLSL ES fragment
// shaders declare `precision highp int;` so that uint has 32 bits.

// 32-bit mixer ("lowbias32" constants), identical to cloudmath::noise_hash.
fn cm_noise_hash(x_in: u32) -> u32 {
    var x: u32 = x_in;
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}
fn cm_noise_hash_uuuu(x: u32, y: u32, z: u32, seed: u32) -> u32 {
    return cm_noise_hash(x + cm_noise_hash(y + cm_noise_hash(z + cm_noise_hash(seed))));
}

// Low-discrepancy sequences in 32-bit fixed point (Roberts 2018), bit-identical to the C++:
// R1 (golden ratio), R2 (plastic number), and a pixel's march offset for a frame.
fn cm_low_discrepancy_r1(n: u32) -> f32 { return f32((0x80000000u + n * 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0); }
fn cm_low_discrepancy_r2(n: u32) -> vec2f {
    return vec2f(f32((0x80000000u + n * 0xc13fa9a9u) >> 8u), f32((0x80000000u + n * 0x91e10da6u) >> 8u)) * (1.0 / 16777216.0);
}
fn cm_frame_jitter(pixel_hash: u32, frame: u32) -> f32 {
    return f32((pixel_hash + frame * 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0);
}
// The index-th sample's offset of a pixel's frame (R1 over frames, R-sequence over indices).
fn cm_sample_jitter(pixel_hash: u32, frame: u32, index: u32) -> f32 {
    return cm_frame_jitter(pixel_hash + index * 0xc13fa9a9u, frame);
}
// Triangular noise in (-1, 1) from one hash (add / 255 before an 8-bit store).
fn cm_triangular_dither(h: u32) -> f32 { return (f32(h & 0xffffu) - f32(h >> 16u)) * (1.0 / 65536.0); }

// i modulo n in [0, n) with % on non-negative operands only.
fn cmi_wrap_cell(i: i32, n: i32) -> i32 { return select(n - 1 - ((-(i + 1)) % n), i % n, i >= 0); }
// floor(p) as ints clamped to +-2^30, and periods saturated at 2^30, as in noise.hpp: no
// overflow for coordinates or octave counts outside the documented domain.
fn cmi_floor_to_cell(p: vec3f) -> vec3i {
    return vec3i(clamp(floor(p), vec3f(-1073741824.0), vec3f(1073741824.0)));
}
fn cmi_grow_period(period: i32, factor: i32) -> i32 {
    return select(period * factor, 1073741824, period > 1073741824 / factor);
}
// The top 24 bits of a hash in [0, 1), exact (noise.hpp's hash_to_unit).
fn cm_hash_to_unit(h: u32) -> f32 { return f32(h >> 8u) * (1.0 / 16777216.0); }
fn cmi_fade(t: f32) -> f32 { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
fn cmi_fade_derivative(t: f32) -> f32 { return 30.0 * t * t * (t - 1.0) * (t - 1.0); }

var<private> CMI_GRADIENTS3: array<vec3f, 16> = array<vec3f, 16>(vec3f(1.0, 1.0, 0.0), vec3f(-1.0, 1.0, 0.0), vec3f(1.0, -1.0, 0.0), vec3f(-1.0, -1.0, 0.0), vec3f(1.0, 0.0, 1.0), vec3f(-1.0, 0.0, 1.0), vec3f(1.0, 0.0, -1.0), vec3f(-1.0, 0.0, -1.0), vec3f(0.0, 1.0, 1.0), vec3f(0.0, -1.0, 1.0), vec3f(0.0, 1.0, -1.0), vec3f(0.0, -1.0, -1.0), vec3f(1.0, 1.0, 0.0), vec3f(-1.0, 1.0, 0.0), vec3f(0.0, -1.0, 1.0), vec3f(0.0, -1.0, -1.0));
var<private> CMI_GRADIENTS2: array<vec2f, 8> = array<vec2f, 8>(vec2f(1.0, 0.0), vec2f(-1.0, 0.0), vec2f(0.0, 1.0), vec2f(0.0, -1.0), vec2f(0.70710678, 0.70710678), vec2f(-0.70710678, 0.70710678), vec2f(0.70710678, -0.70710678), vec2f(-0.70710678, -0.70710678));
fn cmi_gradient3(h: u32) -> vec3f { return CMI_GRADIENTS3[i32(h & 15u)]; }
fn cmi_gradient2(h: u32) -> vec2f { return CMI_GRADIENTS2[i32(h & 7u)]; }

const CMI_PERLIN3_SCALE = 0.96592582628906829; // cos 15 deg: raw extremes +-1.0352764
const CMI_PERLIN2_SCALE = 1.41421356237309505; // sqrt 2: raw extremes +-0.70710678

// (value, d/dx, d/dy, d/dz) of improved Perlin noise, before the clamp of cm_perlin_noise.
fn cm_perlin_noise_derivatives(p: vec3f, period: i32, seed: u32) -> vec4f {
    let n: i32 = max(period, 1);
    let i: vec3i = cmi_floor_to_cell(p);
    let q: vec3f = p - floor(p);
    let x: f32 = q.x;
    let y: f32 = q.y;
    let z: f32 = q.z;
    let x0: u32 = u32(cmi_wrap_cell(i.x, n));
    let y0: u32 = u32(cmi_wrap_cell(i.y, n));
    let z0: u32 = u32(cmi_wrap_cell(i.z, n));
    let x1: u32 = u32(cmi_wrap_cell(i.x + 1, n));
    let y1: u32 = u32(cmi_wrap_cell(i.y + 1, n));
    let z1: u32 = u32(cmi_wrap_cell(i.z + 1, n));
    let g000: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y0, z0, seed));
    let g100: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y0, z0, seed));
    let g010: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y1, z0, seed));
    let g110: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y1, z0, seed));
    let g001: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y0, z1, seed));
    let g101: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y0, z1, seed));
    let g011: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x0, y1, z1, seed));
    let g111: vec3f = cmi_gradient3(cm_noise_hash_uuuu(x1, y1, z1, seed));
    let v000: f32 = g000.x * x + g000.y * y + g000.z * z;
    let v100: f32 = g100.x * (x - 1.0) + g100.y * y + g100.z * z;
    let v010: f32 = g010.x * x + g010.y * (y - 1.0) + g010.z * z;
    let v110: f32 = g110.x * (x - 1.0) + g110.y * (y - 1.0) + g110.z * z;
    let v001: f32 = g001.x * x + g001.y * y + g001.z * (z - 1.0);
    let v101: f32 = g101.x * (x - 1.0) + g101.y * y + g101.z * (z - 1.0);
    let v011: f32 = g011.x * x + g011.y * (y - 1.0) + g011.z * (z - 1.0);
    let v111: f32 = g111.x * (x - 1.0) + g111.y * (y - 1.0) + g111.z * (z - 1.0);
    let u: f32 = cmi_fade(x);
    let v: f32 = cmi_fade(y);
    let w: f32 = cmi_fade(z);
    let du: f32 = cmi_fade_derivative(x);
    let dv: f32 = cmi_fade_derivative(y);
    let dw: f32 = cmi_fade_derivative(z);
    let k0: f32 = v000;
    let k1: f32 = v100 - v000;
    let k2: f32 = v010 - v000;
    let k3: f32 = v001 - v000;
    let k4: f32 = v000 - v100 - v010 + v110;
    let k5: f32 = v000 - v010 - v001 + v011;
    let k6: f32 = v000 - v100 - v001 + v101;
    let k7: f32 = -v000 + v100 + v010 - v110 + v001 - v101 - v011 + v111;
    let value: f32 = k0 + k1 * u + k2 * v + k3 * w + k4 * u * v + k5 * v * w + k6 * w * u + k7 * u * v * w;
    let gk1: vec3f = g100 - g000;
    let gk2: vec3f = g010 - g000;
    let gk3: vec3f = g001 - g000;
    let gk4: vec3f = g000 - g100 - g010 + g110;
    let gk5: vec3f = g000 - g010 - g001 + g011;
    let gk6: vec3f = g000 - g100 - g001 + g101;
    let gk7: vec3f = -g000 + g100 + g010 - g110 + g001 - g101 - g011 + g111;
    var grad: vec3f = g000 + gk1 * u + gk2 * v + gk3 * w + gk4 * (u * v) + gk5 * (v * w) + gk6 * (w * u) + gk7 * (u * v * w);
    grad.x += du * (k1 + k4 * v + k6 * w + k7 * v * w);
    grad.y += dv * (k2 + k4 * u + k5 * w + k7 * u * w);
    grad.z += dw * (k3 + k5 * v + k6 * u + k7 * u * v);
    return vec4f(value, grad) * CMI_PERLIN3_SCALE;
}
fn cm_perlin_noise_derivatives_v3i(p: vec3f, period: i32) -> vec4f {
    return cm_perlin_noise_derivatives(p, period, 0u);
}

fn cm_perlin_noise(p: vec3f, period: i32, seed: u32) -> f32 {
    return clamp(cm_perlin_noise_derivatives(p, period, seed).x, -1.0, 1.0);
}
fn cm_perlin_noise_v3i(p: vec3f, period: i32) -> f32 { return cm_perlin_noise(p, period, 0u); }

fn cm_perlin_noise_v2iu(p: vec2f, period: i32, seed: u32) -> f32 {
    let n: i32 = max(period, 1);
    let i: vec2i = cmi_floor_to_cell(vec3f(p, 0.0)).xy;
    let q: vec2f = p - floor(p);
    let x0: u32 = u32(cmi_wrap_cell(i.x, n));
    let y0: u32 = u32(cmi_wrap_cell(i.y, n));
    let x1: u32 = u32(cmi_wrap_cell(i.x + 1, n));
    let y1: u32 = u32(cmi_wrap_cell(i.y + 1, n));
    let g00: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x0, y0, 0u, seed));
    let g10: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x1, y0, 0u, seed));
    let g01: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x0, y1, 0u, seed));
    let g11: vec2f = cmi_gradient2(cm_noise_hash_uuuu(x1, y1, 0u, seed));
    let v00: f32 = g00.x * q.x + g00.y * q.y;
    let v10: f32 = g10.x * (q.x - 1.0) + g10.y * q.y;
    let v01: f32 = g01.x * q.x + g01.y * (q.y - 1.0);
    let v11: f32 = g11.x * (q.x - 1.0) + g11.y * (q.y - 1.0);
    let u: f32 = cmi_fade(q.x);
    let v: f32 = cmi_fade(q.y);
    let a: f32 = v00 + u * (v10 - v00);
    let b: f32 = v01 + u * (v11 - v01);
    return clamp((a + v * (b - a)) * CMI_PERLIN2_SCALE, -1.0, 1.0);
}
fn cm_perlin_noise_v2i(p: vec2f, period: i32) -> f32 { return cm_perlin_noise_v2iu(p, period, 0u); }

// Distance to the nearest feature point (one per cell, 27-cell search, which is not exact in
// rare configurations: see noise.hpp), in [0, sqrt 3].
fn cm_worley_f1(p: vec3f, period: i32, seed: u32) -> f32 {
    let n: i32 = max(period, 1);
    let i: vec3i = cmi_floor_to_cell(p);
    let q: vec3f = p - floor(p);
    var best: f32 = 3.0;
    for (var dz: i32 = -1; dz <= 1; dz++) {
        for (var dy: i32 = -1; dy <= 1; dy++) {
            for (var dx: i32 = -1; dx <= 1; dx++) {
                let h: u32 = cm_noise_hash_uuuu(u32(cmi_wrap_cell(i.x + dx, n)), u32(cmi_wrap_cell(i.y + dy, n)), u32(cmi_wrap_cell(i.z + dz, n)), seed);
                let h2: u32 = cm_noise_hash(h);
                let h3: u32 = cm_noise_hash(h2);
                let ox: f32 = f32(dx) + cm_hash_to_unit(h) - q.x;
                let oy: f32 = f32(dy) + cm_hash_to_unit(h2) - q.y;
                let oz: f32 = f32(dz) + cm_hash_to_unit(h3) - q.z;
                let d2: f32 = ox * ox + oy * oy + oz * oz;
                best = select(best, d2, d2 < best);
            }
        }
    }
    return sqrt(best);
}
fn cm_worley_f1_v3i(p: vec3f, period: i32) -> f32 { return cm_worley_f1(p, period, 0u); }

// 1 - F1 / sqrt(3) in [0, 1].
fn cm_worley_noise(p: vec3f, period: i32, seed: u32) -> f32 {
    return cm_saturate(1.0 - cm_worley_f1(p, period, seed) * 0.57735026918962576);
}
fn cm_worley_noise_v3i(p: vec3f, period: i32) -> f32 { return cm_worley_noise(p, period, 0u); }

// fBm: octave i has amplitude gain^i, frequency and period times lacunarity^i, seed + i;
// divided by the sum of amplitudes. octaves and lacunarity below 1 are treated as 1; gain is
// clamped to [0, 1], so the sum of amplitudes is at least 1 (no division by 0 for negative
// gains, no overflow for large ones) and the result stays in the base noise's range.
// One loop for the three fBm twins (GLSL has no callables): kind 0 is 3D Perlin, 1 is 2D
// Perlin on p.xy, 2 is Worley; the callers pass constants, which drivers fold.
fn cmi_fbm(p: vec3f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32, kind: i32) -> f32 {
    let count: i32 = max(octaves, 1);
    let lac: i32 = max(lacunarity, 1);
    var per: i32 = max(period, 1);
    let g: f32 = clamp(gain, 0.0, 1.0);
    var sum: f32 = 0.0;
    var norm: f32 = 0.0;
    var amplitude: f32 = 1.0;
    var frequency: f32 = 1.0;
    for (var i: i32 = 0; i < count; i++) {
        let q: vec3f = p * frequency;
        let s: u32 = seed + u32(i);
        var octave: f32;
        if (kind == 0) {
            octave = cm_perlin_noise(q, per, s);
        } else if (kind == 1) {
            octave = cm_perlin_noise_v2iu(q.xy, per, s);
        } else {
            octave = cm_worley_noise(q, per, s);
        }
        sum += amplitude * octave;
        norm += amplitude;
        amplitude *= g;
        frequency *= f32(lac);
        per = cmi_grow_period(per, lac);
    }
    return sum / norm;
}

fn cm_perlin_fbm(p: vec3f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32) -> f32 {
    return cmi_fbm(p, period, octaves, lacunarity, gain, seed, 0);
}
fn cm_perlin_fbm_v3ii(p: vec3f, period: i32, octaves: i32) -> f32 {
    return cm_perlin_fbm(p, period, octaves, 2, 0.5, 0u);
}

fn cm_perlin_fbm_v2iiifu(p: vec2f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32) -> f32 {
    return cmi_fbm(vec3f(p, 0.0), period, octaves, lacunarity, gain, seed, 1);
}
fn cm_perlin_fbm_v2ii(p: vec2f, period: i32, octaves: i32) -> f32 {
    return cm_perlin_fbm_v2iiifu(p, period, octaves, 2, 0.5, 0u);
}

fn cm_worley_fbm(p: vec3f, period: i32, octaves: i32, lacunarity: i32, gain: f32, seed: u32) -> f32 {
    return cmi_fbm(p, period, octaves, lacunarity, gain, seed, 2);
}
fn cm_worley_fbm_v3ii(p: vec3f, period: i32, octaves: i32) -> f32 {
    return cm_worley_fbm(p, period, octaves, 2, 0.5, 0u);
}

// 0.625 W(p) + 0.25 W(2p) + 0.125 W(4p), periods doubling (Schneider 2015).
fn cm_worley_fbm_nubis(p: vec3f, period: i32, seed: u32) -> f32 {
    let n: i32 = max(period, 1);
    return 0.625 * cm_worley_noise(p, n, seed) + 0.25 * cm_worley_noise(p * 2.0, cmi_grow_period(n, 2), seed + 1u) + 0.125 * cm_worley_noise(p * 4.0, cmi_grow_period(n, 4), seed + 2u);
}
fn cm_worley_fbm_nubis_v3i(p: vec3f, period: i32) -> f32 { return cm_worley_fbm_nubis(p, period, 0u); }

// Perlin fBm (3 octaves, in [0, 1]) dilated by the Nubis Worley fBm (Schneider 2015).
fn cm_perlin_worley(p: vec3f, period: i32, seed: u32) -> f32 {
    let perlin: f32 = cm_perlin_fbm(p, period, 3, 2, 0.5, seed) * 0.5 + 0.5;
    let worley: f32 = cm_worley_fbm_nubis(p, period, seed + 101u);
    return cmi_remap_unit(perlin, worley - 1.0, 1.0); // cm_remap_clamped(..., 0.0, 1.0)
}
fn cm_perlin_worley_v3i(p: vec3f, period: i32) -> f32 { return cm_perlin_worley(p, period, 0u); }

// Curl of the potential (Perlin seed, seed + 1, seed + 2), divergence-free (Bridson 2007).
fn cm_curl_noise(p: vec3f, period: i32, seed: u32) -> vec3f {
    let a: vec4f = cm_perlin_noise_derivatives(p, period, seed);
    let b: vec4f = cm_perlin_noise_derivatives(p, period, seed + 1u);
    let c: vec4f = cm_perlin_noise_derivatives(p, period, seed + 2u);
    return vec3f(c.z - b.w, a.w - c.y, b.y - a.z);
}
fn cm_curl_noise_v3i(p: vec3f, period: i32) -> vec3f { return cm_curl_noise(p, period, 0u); }

fn cm_curl_noise_v2iu(p: vec2f, period: i32, seed: u32) -> vec2f {
    let d: vec4f = cm_perlin_noise_derivatives(vec3f(p, 0.0), period, seed);
    return vec2f(d.z, -d.y);
}
fn cm_curl_noise_v2i(p: vec2f, period: i32) -> vec2f { return cm_curl_noise_v2iu(p, period, 0u); }
