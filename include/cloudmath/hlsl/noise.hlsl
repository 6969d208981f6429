// cloudmath/hlsl/noise.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/noise.hlsl: GLSL twin of cloudmath/noise.hpp: tileable improved Perlin
// (2D, 3D, analytic derivatives), Worley, fBm, Nubis Worley fBm, Perlin-Worley, curl noise.
// p in lattice cells; period = cells per tile (int >= 1); seed a uint (overloads without it
// use 0). The hashes are uint arithmetic and match the C++ bit for bit; in GLSL ES fragment
// shaders declare `precision highp int;` so that uint has 32 bits.
#ifndef CM_NOISE_HLSL
#define CM_NOISE_HLSL

#include "core.hlsl"

// 32-bit mixer ("lowbias32" constants), identical to cloudmath::noise_hash.
uint cm_noise_hash(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}
uint cm_noise_hash(uint x, uint y, uint z, uint seed) {
    return cm_noise_hash(x + cm_noise_hash(y + cm_noise_hash(z + cm_noise_hash(seed))));
}

// Low-discrepancy sequences in 32-bit fixed point (Roberts 2018), bit-identical to the C++:
// R1 (golden ratio), R2 (plastic number), and a pixel's march offset for a frame.
float cm_low_discrepancy_r1(uint n) { return float((0x80000000u + n * 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0); }
float2 cm_low_discrepancy_r2(uint n) {
    return float2(float((0x80000000u + n * 0xc13fa9a9u) >> 8u), float((0x80000000u + n * 0x91e10da6u) >> 8u)) * (1.0 / 16777216.0);
}
float cm_frame_jitter(uint pixel_hash, uint frame) {
    return float((pixel_hash + frame * 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0);
}
// The index-th sample's offset of a pixel's frame (R1 over frames, R-sequence over indices).
float cm_sample_jitter(uint pixel_hash, uint frame, uint index) {
    return cm_frame_jitter(pixel_hash + index * 0xc13fa9a9u, frame);
}
// Triangular noise in (-1, 1) from one hash (add / 255 before an 8-bit store).
float cm_triangular_dither(uint h) { return (float(h & 0xffffu) - float(h >> 16u)) * (1.0 / 65536.0); }

// i modulo n in [0, n) with % on non-negative operands only.
int cmi_wrap_cell(int i, int n) { return i >= 0 ? i % n : n - 1 - ((-(i + 1)) % n); }
// floor(p) as ints clamped to +-2^30, and periods saturated at 2^30, as in noise.hpp: no
// overflow for coordinates or octave counts outside the documented domain.
int3 cmi_floor_to_cell(float3 p) {
    return int3(clamp(floor(p), float3(-1073741824.0, -1073741824.0, -1073741824.0), float3(1073741824.0, 1073741824.0, 1073741824.0)));
}
int cmi_grow_period(int period, int factor) { return period > 1073741824 / factor ? 1073741824 : period * factor; }
// The top 24 bits of a hash in [0, 1), exact (noise.hpp's hash_to_unit).
float cm_hash_to_unit(uint h) { return float(h >> 8u) * (1.0 / 16777216.0); }
float cmi_fade(float t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
float cmi_fade_derivative(float t) { return 30.0 * t * t * (t - 1.0) * (t - 1.0); }

static const float3 CMI_GRADIENTS3[16] = {float3(1.0, 1.0, 0.0), float3(-1.0, 1.0, 0.0), float3(1.0, -1.0, 0.0), float3(-1.0, -1.0, 0.0), float3(1.0, 0.0, 1.0), float3(-1.0, 0.0, 1.0), float3(1.0, 0.0, -1.0), float3(-1.0, 0.0, -1.0), float3(0.0, 1.0, 1.0), float3(0.0, -1.0, 1.0), float3(0.0, 1.0, -1.0), float3(0.0, -1.0, -1.0), float3(1.0, 1.0, 0.0), float3(-1.0, 1.0, 0.0), float3(0.0, -1.0, 1.0), float3(0.0, -1.0, -1.0)};
static const float2 CMI_GRADIENTS2[8] = {float2(1.0, 0.0), float2(-1.0, 0.0), float2(0.0, 1.0), float2(0.0, -1.0), float2(0.70710678, 0.70710678), float2(-0.70710678, 0.70710678), float2(0.70710678, -0.70710678), float2(-0.70710678, -0.70710678)};
float3 cmi_gradient3(uint h) { return CMI_GRADIENTS3[int(h & 15u)]; }
float2 cmi_gradient2(uint h) { return CMI_GRADIENTS2[int(h & 7u)]; }

#define CMI_PERLIN3_SCALE 0.96592582628906829 // cos 15 deg: raw extremes +-1.0352764
#define CMI_PERLIN2_SCALE 1.41421356237309505 // sqrt 2: raw extremes +-0.70710678

// (value, d/dx, d/dy, d/dz) of improved Perlin noise, before the clamp of cm_perlin_noise.
float4 cm_perlin_noise_derivatives(float3 p, int period, uint seed) {
    int n = max(period, 1);
    int3 i = cmi_floor_to_cell(p);
    float3 q = p - floor(p);
    float x = q.x;
    float y = q.y;
    float z = q.z;
    uint x0 = uint(cmi_wrap_cell(i.x, n));
    uint y0 = uint(cmi_wrap_cell(i.y, n));
    uint z0 = uint(cmi_wrap_cell(i.z, n));
    uint x1 = uint(cmi_wrap_cell(i.x + 1, n));
    uint y1 = uint(cmi_wrap_cell(i.y + 1, n));
    uint z1 = uint(cmi_wrap_cell(i.z + 1, n));
    float3 g000 = cmi_gradient3(cm_noise_hash(x0, y0, z0, seed));
    float3 g100 = cmi_gradient3(cm_noise_hash(x1, y0, z0, seed));
    float3 g010 = cmi_gradient3(cm_noise_hash(x0, y1, z0, seed));
    float3 g110 = cmi_gradient3(cm_noise_hash(x1, y1, z0, seed));
    float3 g001 = cmi_gradient3(cm_noise_hash(x0, y0, z1, seed));
    float3 g101 = cmi_gradient3(cm_noise_hash(x1, y0, z1, seed));
    float3 g011 = cmi_gradient3(cm_noise_hash(x0, y1, z1, seed));
    float3 g111 = cmi_gradient3(cm_noise_hash(x1, y1, z1, seed));
    float v000 = g000.x * x + g000.y * y + g000.z * z;
    float v100 = g100.x * (x - 1.0) + g100.y * y + g100.z * z;
    float v010 = g010.x * x + g010.y * (y - 1.0) + g010.z * z;
    float v110 = g110.x * (x - 1.0) + g110.y * (y - 1.0) + g110.z * z;
    float v001 = g001.x * x + g001.y * y + g001.z * (z - 1.0);
    float v101 = g101.x * (x - 1.0) + g101.y * y + g101.z * (z - 1.0);
    float v011 = g011.x * x + g011.y * (y - 1.0) + g011.z * (z - 1.0);
    float v111 = g111.x * (x - 1.0) + g111.y * (y - 1.0) + g111.z * (z - 1.0);
    float u = cmi_fade(x);
    float v = cmi_fade(y);
    float w = cmi_fade(z);
    float du = cmi_fade_derivative(x);
    float dv = cmi_fade_derivative(y);
    float dw = cmi_fade_derivative(z);
    float k0 = v000;
    float k1 = v100 - v000;
    float k2 = v010 - v000;
    float k3 = v001 - v000;
    float k4 = v000 - v100 - v010 + v110;
    float k5 = v000 - v010 - v001 + v011;
    float k6 = v000 - v100 - v001 + v101;
    float k7 = -v000 + v100 + v010 - v110 + v001 - v101 - v011 + v111;
    float value = k0 + k1 * u + k2 * v + k3 * w + k4 * u * v + k5 * v * w + k6 * w * u + k7 * u * v * w;
    float3 gk1 = g100 - g000;
    float3 gk2 = g010 - g000;
    float3 gk3 = g001 - g000;
    float3 gk4 = g000 - g100 - g010 + g110;
    float3 gk5 = g000 - g010 - g001 + g011;
    float3 gk6 = g000 - g100 - g001 + g101;
    float3 gk7 = -g000 + g100 + g010 - g110 + g001 - g101 - g011 + g111;
    float3 grad = g000 + gk1 * u + gk2 * v + gk3 * w + gk4 * (u * v) + gk5 * (v * w) + gk6 * (w * u) + gk7 * (u * v * w);
    grad.x += du * (k1 + k4 * v + k6 * w + k7 * v * w);
    grad.y += dv * (k2 + k4 * u + k5 * w + k7 * u * w);
    grad.z += dw * (k3 + k5 * v + k6 * u + k7 * u * v);
    return float4(value, grad) * CMI_PERLIN3_SCALE;
}
float4 cm_perlin_noise_derivatives(float3 p, int period) { return cm_perlin_noise_derivatives(p, period, 0u); }

float cm_perlin_noise(float3 p, int period, uint seed) {
    return clamp(cm_perlin_noise_derivatives(p, period, seed).x, -1.0, 1.0);
}
float cm_perlin_noise(float3 p, int period) { return cm_perlin_noise(p, period, 0u); }

float cm_perlin_noise(float2 p, int period, uint seed) {
    int n = max(period, 1);
    int2 i = cmi_floor_to_cell(float3(p, 0.0)).xy;
    float2 q = p - floor(p);
    uint x0 = uint(cmi_wrap_cell(i.x, n));
    uint y0 = uint(cmi_wrap_cell(i.y, n));
    uint x1 = uint(cmi_wrap_cell(i.x + 1, n));
    uint y1 = uint(cmi_wrap_cell(i.y + 1, n));
    float2 g00 = cmi_gradient2(cm_noise_hash(x0, y0, 0u, seed));
    float2 g10 = cmi_gradient2(cm_noise_hash(x1, y0, 0u, seed));
    float2 g01 = cmi_gradient2(cm_noise_hash(x0, y1, 0u, seed));
    float2 g11 = cmi_gradient2(cm_noise_hash(x1, y1, 0u, seed));
    float v00 = g00.x * q.x + g00.y * q.y;
    float v10 = g10.x * (q.x - 1.0) + g10.y * q.y;
    float v01 = g01.x * q.x + g01.y * (q.y - 1.0);
    float v11 = g11.x * (q.x - 1.0) + g11.y * (q.y - 1.0);
    float u = cmi_fade(q.x);
    float v = cmi_fade(q.y);
    float a = v00 + u * (v10 - v00);
    float b = v01 + u * (v11 - v01);
    return clamp((a + v * (b - a)) * CMI_PERLIN2_SCALE, -1.0, 1.0);
}
float cm_perlin_noise(float2 p, int period) { return cm_perlin_noise(p, period, 0u); }

// Distance to the nearest feature point (one per cell, 27-cell search, which is not exact in
// rare configurations: see noise.hpp), in [0, sqrt 3].
float cm_worley_f1(float3 p, int period, uint seed) {
    int n = max(period, 1);
    int3 i = cmi_floor_to_cell(p);
    float3 q = p - floor(p);
    float best = 3.0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                uint h = cm_noise_hash(uint(cmi_wrap_cell(i.x + dx, n)), uint(cmi_wrap_cell(i.y + dy, n)), uint(cmi_wrap_cell(i.z + dz, n)), seed);
                uint h2 = cm_noise_hash(h);
                uint h3 = cm_noise_hash(h2);
                float ox = float(dx) + cm_hash_to_unit(h) - q.x;
                float oy = float(dy) + cm_hash_to_unit(h2) - q.y;
                float oz = float(dz) + cm_hash_to_unit(h3) - q.z;
                float d2 = ox * ox + oy * oy + oz * oz;
                best = d2 < best ? d2 : best;
            }
    return sqrt(best);
}
float cm_worley_f1(float3 p, int period) { return cm_worley_f1(p, period, 0u); }

// 1 - F1 / sqrt(3) in [0, 1].
float cm_worley_noise(float3 p, int period, uint seed) {
    return cm_saturate(1.0 - cm_worley_f1(p, period, seed) * 0.57735026918962576);
}
float cm_worley_noise(float3 p, int period) { return cm_worley_noise(p, period, 0u); }

// fBm: octave i has amplitude gain^i, frequency and period times lacunarity^i, seed + i;
// divided by the sum of amplitudes. octaves and lacunarity below 1 are treated as 1; gain is
// clamped to [0, 1], so the sum of amplitudes is at least 1 (no division by 0 for negative
// gains, no overflow for large ones) and the result stays in the base noise's range.
// One loop for the three fBm twins (GLSL has no callables): kind 0 is 3D Perlin, 1 is 2D
// Perlin on p.xy, 2 is Worley; the callers pass constants, which drivers fold.
float cmi_fbm(float3 p, int period, int octaves, int lacunarity, float gain, uint seed, int kind) {
    int count = max(octaves, 1);
    int lac = max(lacunarity, 1);
    int per = max(period, 1);
    float g = clamp(gain, 0.0, 1.0);
    float sum = 0.0;
    float norm = 0.0;
    float amplitude = 1.0;
    float frequency = 1.0;
    for (int i = 0; i < count; ++i) {
        float3 q = p * frequency;
        uint s = seed + uint(i);
        float octave = kind == 0 ? cm_perlin_noise(q, per, s) : (kind == 1 ? cm_perlin_noise(q.xy, per, s) : cm_worley_noise(q, per, s));
        sum += amplitude * octave;
        norm += amplitude;
        amplitude *= g;
        frequency *= float(lac);
        per = cmi_grow_period(per, lac);
    }
    return sum / norm;
}

float cm_perlin_fbm(float3 p, int period, int octaves, int lacunarity, float gain, uint seed) {
    return cmi_fbm(p, period, octaves, lacunarity, gain, seed, 0);
}
float cm_perlin_fbm(float3 p, int period, int octaves) { return cm_perlin_fbm(p, period, octaves, 2, 0.5, 0u); }

float cm_perlin_fbm(float2 p, int period, int octaves, int lacunarity, float gain, uint seed) {
    return cmi_fbm(float3(p, 0.0), period, octaves, lacunarity, gain, seed, 1);
}
float cm_perlin_fbm(float2 p, int period, int octaves) { return cm_perlin_fbm(p, period, octaves, 2, 0.5, 0u); }

float cm_worley_fbm(float3 p, int period, int octaves, int lacunarity, float gain, uint seed) {
    return cmi_fbm(p, period, octaves, lacunarity, gain, seed, 2);
}
float cm_worley_fbm(float3 p, int period, int octaves) { return cm_worley_fbm(p, period, octaves, 2, 0.5, 0u); }

// 0.625 W(p) + 0.25 W(2p) + 0.125 W(4p), periods doubling (Schneider 2015).
float cm_worley_fbm_nubis(float3 p, int period, uint seed) {
    int n = max(period, 1);
    return 0.625 * cm_worley_noise(p, n, seed) + 0.25 * cm_worley_noise(p * 2.0, cmi_grow_period(n, 2), seed + 1u) + 0.125 * cm_worley_noise(p * 4.0, cmi_grow_period(n, 4), seed + 2u);
}
float cm_worley_fbm_nubis(float3 p, int period) { return cm_worley_fbm_nubis(p, period, 0u); }

// Perlin fBm (3 octaves, in [0, 1]) dilated by the Nubis Worley fBm (Schneider 2015).
float cm_perlin_worley(float3 p, int period, uint seed) {
    float perlin = cm_perlin_fbm(p, period, 3, 2, 0.5, seed) * 0.5 + 0.5;
    float worley = cm_worley_fbm_nubis(p, period, seed + 101u);
    return cmi_remap_unit(perlin, worley - 1.0, 1.0); // cm_remap_clamped(..., 0.0, 1.0)
}
float cm_perlin_worley(float3 p, int period) { return cm_perlin_worley(p, period, 0u); }

// Curl of the potential (Perlin seed, seed + 1, seed + 2), divergence-free (Bridson 2007).
float3 cm_curl_noise(float3 p, int period, uint seed) {
    float4 a = cm_perlin_noise_derivatives(p, period, seed);
    float4 b = cm_perlin_noise_derivatives(p, period, seed + 1u);
    float4 c = cm_perlin_noise_derivatives(p, period, seed + 2u);
    return float3(c.z - b.w, a.w - c.y, b.y - a.z);
}
float3 cm_curl_noise(float3 p, int period) { return cm_curl_noise(p, period, 0u); }

float2 cm_curl_noise(float2 p, int period, uint seed) {
    float4 d = cm_perlin_noise_derivatives(float3(p, 0.0), period, seed);
    return float2(d.z, -d.y);
}
float2 cm_curl_noise(float2 p, int period) { return cm_curl_noise(p, period, 0u); }

#endif // CM_NOISE_HLSL
