// The physical sky for the WebGL2 demo (the desktop renderer's sky_model::physical): what
// examples/cloud_renderer/scene.cpp's compute_physical_sky and physical_sky.cpp make on the CPU,
// made here on the GPU with cloudmath's GLSL twins (cm_atmosphere_sky_radiance,
// cm_atmosphere_inscatter, cm_atmosphere_sun_illuminance) reading the refined
// multiple-scattering table through CM_ATMOSPHERE_TABLE:
//   - the sky-view tables (64 x 64 nodes: the azimuth from the sun's in x, the zenith cosine,
//     crowded at the horizon, in y) at the camera (the background) and at the layer's top (the
//     sky light on the clouds from above);
//   - the aerial-perspective table (16 distances x 16 azimuths by 32 elevations);
//   - the sun by height in the layer, at the band's middle and at the camera, the zenith and the
//     horizon's mean (9 sky rays), read back;
// then, in JavaScript from the read-back tables, the upper hemisphere's mean radiance and
// irradiance (physical_sky.cpp's upper_hemisphere), the ground and the EV100 exposure.
// The table, made once per atmosphere on the CPU (1.4 s), is web/demo/sky_table.bin:
// `cloudmath_atmosphere_lut --write-table web/demo/sky_table.bin` (ctest web.sky_table_fresh).
// The far shadow toward a low sun (far_shadow.hpp, which the desktop marches on the CPU) is
// drawn by clouds.frag itself (its pass 4, farShadowParams below give its range) over the
// demo's own noise textures. The tables are read back for WebGPU too (clouds.wgsl's
// u_physical_sky reads the same texels).

export const sunLux = 128000;  // physical_sky.hpp's sun_lux: a white 128 klux sun
export const skyViewSize = [64, 64];  // physical_sky.hpp's sky_view_table: n_az, n_el
export const hazeSize = [16, 16, 32];  // ... haze_table: n_d, n_az, n_el
export const hazeDistance = 160000;  // ... its max_distance (m)
const tableSize = 32, tableParts = 21;  // the table's layout (cloudmath_atmosphere_lut --write-table)
const sunHeights = 8;  // scene.hpp's sun_heights
export const farShadowSize = [16, 48];  // far_shadow.hpp's far_shadow_table: n_alt, n_mu
// The values row (u_kind 2): the sun at sunHeights heights, at the band's middle and at the
// camera, the zenith, the horizon at 8 azimuths, the band.
const valueCount = sunHeights + 12;

// One fragment shader for every table (u_kind), one texel per fragment.
function bakeSource(header, library) {
  return header + `vec3 sky_table(int part, int x, int y);
#define CM_ATMOSPHERE_TABLE sky_table
${library}
uniform highp sampler2D u_table;  // the parts stacked: part p at rows ${tableSize} p .. ${tableSize} p + ${tableSize - 1}
uniform int u_kind;               // 0 a sky-view table, 1 the aerial-perspective table, 2 the sky's values
uniform ivec3 u_size;             // sky view: n_az, n_el; haze: n_d, n_az, n_el
uniform float u_altitude;         // the table's altitude (m)
uniform vec3 u_sun;               // the sun at azimuth 0 (tables) or as it is (values)
uniform float u_max_distance, u_layer_bottom, u_layer_top, u_cloud_type;
out vec4 o;
vec3 sky_table(int part, int x, int y) { return texelFetch(u_table, ivec2(x, y + ${tableSize} * part), 0).rgb; }
// physical_sky.cpp's node_direction.
vec3 node_direction(int az, int el, int n_az, int n_el) {
  float s = 2.0 * float(el) / float(n_el - 1) - 1.0;
  float mu = s < 0.0 ? -s * s : s * s;
  float sin_zenith = sqrt(max(1.0 - mu * mu, 0.0));
  float phi = CM_PI * float(az) / float(n_az - 1);
  return vec3(sin_zenith * cos(phi), mu, sin_zenith * sin(phi));
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  CmAtmosphere air = cm_earth_atmosphere();
  // The renderer's table (physical_air): every part of the refined LUT, no ground irradiance.
  CmAtmosphereTable table = CmAtmosphereTable(${tableSize}, ${tableSize}, 3, 0);
  const float lux = ${sunLux.toFixed(1)};
  if (u_kind == 0) {
    o = vec4(lux * cm_atmosphere_sky_radiance(air, table, u_altitude, node_direction(p.x, p.y, u_size.x, u_size.y), u_sun, 32, 32), 1.0);
  } else if (u_kind == 1) {
    int k = p.x % u_size.x, az = p.x / u_size.x;
    float x = float(k) / float(u_size.x - 1);
    vec3 L = k == 0 ? vec3(0.0)
                    : lux * cm_atmosphere_inscatter(air, table, u_altitude, node_direction(az, p.y, u_size.y, u_size.z), u_sun,
                                                    u_max_distance * x * x, 16, 16).radiance;
    o = vec4(L, 1.0);
  } else if (p.x < ${sunHeights}) {  // the sun on the clouds by height in the layer
    float altitude = u_layer_bottom + (u_layer_top - u_layer_bottom) * float(p.x) / ${(sunHeights - 1).toFixed(1)};
    o = vec4(cm_atmosphere_sun_illuminance(air, altitude, u_sun.y, vec3(lux)), 1.0);
  } else if (p.x == ${sunHeights}) {  // ... at the middle of the type's band (scene.cpp's cloud_band): the drawn disc
    vec2 band = cm_height_range_for_type(u_cloud_type) * (u_layer_top - u_layer_bottom) + u_layer_bottom;
    o = vec4(cm_atmosphere_sun_illuminance(air, 0.5 * (band.x + band.y), u_sun.y, vec3(lux)), 1.0);
  } else if (p.x == ${sunHeights + 1}) {  // ... at the camera (the ground)
    o = vec4(cm_atmosphere_sun_illuminance(air, u_altitude, u_sun.y, vec3(lux)), 1.0);
  } else if (p.x == ${sunHeights + 2}) {  // the zenith
    o = vec4(lux * cm_atmosphere_sky_radiance(air, table, u_altitude, vec3(0.0, 1.0, 0.0), u_sun, 32, 32), 1.0);
  } else if (p.x == ${sunHeights + 11}) {  // the type's band (scene.cpp's cloud_band, classic field): the far shadow's range
    o = vec4(cm_height_range_for_type(u_cloud_type) * (u_layer_top - u_layer_bottom) + u_layer_bottom, 0.0, 1.0);
  } else {  // the horizon 2 degrees up at azimuth 45 (p.x - ${sunHeights + 3}) degrees
    float az = float(p.x - ${sunHeights + 3}) * 45.0 * CM_PI / 180.0, e = 2.0 * CM_PI / 180.0;
    o = vec4(lux * cm_atmosphere_sky_radiance(air, table, u_altitude, vec3(cos(az) * cos(e), sin(e), sin(az) * cos(e)), u_sun, 32, 32), 1.0);
  }
}
`;
}

// physical_sky.cpp's sky_coordinates: (azimuth from the sun's / pi, 0.5 + 0.5 sign(mu) sqrt|mu|).
function skyCoordinates(dir, sun) {
  const mu = Math.min(Math.max(dir[1], -1), 1);
  const h = Math.hypot(dir[0], dir[2]), hs = Math.hypot(sun[0], sun[2]);
  const cosPhi = h > 1e-6 && hs > 1e-6 ? Math.min(Math.max((dir[0] * sun[0] + dir[2] * sun[2]) / (h * hs), -1), 1) : 1;
  return [Math.acos(cosPhi) / Math.PI, 0.5 + 0.5 * Math.sign(mu) * Math.sqrt(Math.abs(mu))];
}

// physical_sky.cpp's sky_view_lookup on a read-back RGBA table.
function skyViewLookup(texels, dir, sun) {
  const [nAz, nEl] = skyViewSize;
  const c = skyCoordinates(dir, sun);
  const x = c[0] * (nAz - 1), y = c[1] * (nEl - 1);
  const a0 = Math.min(Math.max(Math.floor(x), 0), nAz - 2), e0 = Math.min(Math.max(Math.floor(y), 0), nEl - 2);
  const fa = Math.min(Math.max(x - a0, 0), 1), fe = Math.min(Math.max(y - e0, 0), 1);
  const at = (a, e, k) => texels[4 * (e * nAz + a) + k];
  return [0, 1, 2].map((k) => (at(a0, e0, k) * (1 - fa) + at(a0 + 1, e0, k) * fa) * (1 - fe) +
                              (at(a0, e0 + 1, k) * (1 - fa) + at(a0 + 1, e0 + 1, k) * fa) * fe);
}

// physical_sky.cpp's upper_hemisphere: the mean radiance over the upper hemisphere and the
// irradiance on a horizontal plane, a 64 x 64 quadrature over (zenith cosine, azimuth).
export function upperHemisphere(texels, sun) {
  const n = 64, mean = [0, 0, 0], irradiance = [0, 0, 0];
  for (let j = 0; j < n; ++j)
    for (let i = 0; i < n; ++i) {
      const c = (j + 0.5) / n, s = Math.sqrt(1 - c * c), phi = (i + 0.5) / n * Math.PI;
      const L = skyViewLookup(texels, [s * Math.cos(phi), c, s * Math.sin(phi)], sun);
      for (let k = 0; k < 3; ++k) { mean[k] += L[k]; irradiance[k] += L[k] * c; }
    }
  return { mean: mean.map((x) => x / (n * n)), irradiance: irradiance.map((x) => x * 2 * Math.PI / (n * n)) };
}

const luminance = (c) => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];

// The baker: its program and the table's texture, made once. gl needs EXT_color_buffer_float;
// library: cloudmath's atmosphere and density modules, resolved (the package's resolve());
// compile(source, what): a linked program for the demo's full-screen triangle.
export function createPhysicalSky(gl, header, library, compile, tableBytes) {
  if (tableBytes.byteLength !== tableSize * tableSize * tableParts * 12)
    throw new Error(`sky_table.bin holds ${tableBytes.byteLength} bytes, not ${tableSize * tableSize * tableParts * 12}: regenerate it`);
  const values = new Float32Array(tableBytes);
  const table = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, table);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGB32F, tableSize, tableSize * tableParts, 0, gl.RGB, gl.FLOAT, values);
  for (const k of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, k, gl.NEAREST);
  const program = compile(bakeSource(header, library), 'the physical sky bake');
  const floatTexture = (w, h) => {
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, w, h);
    for (const k of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, k, gl.NEAREST);
    return t;
  };
  // The far shadow's stand-in while its table is drawn (clouds.frag's pass 4 binds one but
  // does not read it): 2 x 2 texels of 1.
  const farShadow = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, farShadow);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.R32F, 2, 2, 0, gl.RED, gl.FLOAT, new Float32Array([1, 1, 1, 1]));
  for (const k of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, k, gl.NEAREST);
  return { table, program, farShadow,
    skyView: floatTexture(...skyViewSize), skyTop: floatTexture(...skyViewSize),
    haze: floatTexture(hazeSize[0] * hazeSize[1], hazeSize[2]), values: floatTexture(valueCount, 1),
    farTable: floatTexture(...farShadowSize) };
}

// Bakes the tables for scene s (the demo's scene preset with its state: altitudes, the layer,
// the cloud type) and sun direction sunDir (frame constants), reads back what the frame's
// uniforms need and returns them with the bake's time. The tables stay in sky.skyView and
// sky.haze until the next bake.
export function bakePhysicalSky(gl, sky, s, sunDir) {
  const t0 = performance.now();
  const sunAtZero = [Math.sqrt(Math.max(1 - sunDir[1] * sunDir[1], 0)), sunDir[1], 0];
  const camera = Math.max(s.cameraAltitude, 0);
  gl.useProgram(sky.program);
  const u = (n) => gl.getUniformLocation(sky.program, n);
  gl.activeTexture(gl.TEXTURE0);
  gl.bindTexture(gl.TEXTURE_2D, sky.table);
  gl.uniform1i(u('u_table'), 0);
  gl.uniform1f(u('u_max_distance'), hazeDistance);
  gl.uniform1f(u('u_layer_bottom'), s.layerBottom);
  gl.uniform1f(u('u_layer_top'), s.layerTop);
  gl.uniform1f(u('u_cloud_type'), s.cloudType);
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  const draw = (tex, w, h, kind, size, altitude, sun, readBack) => {
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, tex, 0);
    gl.viewport(0, 0, w, h);
    gl.uniform1i(u('u_kind'), kind);
    gl.uniform3i(u('u_size'), ...size);
    gl.uniform1f(u('u_altitude'), altitude);
    gl.uniform3fv(u('u_sun'), sun);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    if (!readBack) return null;
    const out = new Float32Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.FLOAT, out);
    return out;
  };
  const below = draw(sky.skyView, ...skyViewSize, 0, [...skyViewSize, 0], camera, sunAtZero, true);
  const above = draw(sky.skyTop, ...skyViewSize, 0, [...skyViewSize, 0], s.layerTop, sunAtZero, true);
  const haze = draw(sky.haze, hazeSize[0] * hazeSize[1], hazeSize[2], 1, hazeSize, camera, sunAtZero, true);
  const v = draw(sky.values, valueCount, 1, 2, [0, 0, 0], camera, sunDir, true);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.deleteFramebuffer(fbo);
  const texel = (i) => [v[4 * i], v[4 * i + 1], v[4 * i + 2]];
  const sunByHeight = Array.from({ length: sunHeights }, (_, i) => texel(i));
  const skyZenith = texel(sunHeights + 2);
  const skyHorizon = [0, 1, 2].map((k) => Array.from({ length: 8 }, (_, i) => texel(sunHeights + 3 + i)[k]).reduce((a, b) => a + b) / 8);
  const top = upperHemisphere(above, sunAtZero), low = upperHemisphere(below, sunAtZero);
  const sunGround = texel(sunHeights + 1);
  const albedo = 0.1;  // Earth's ground (earth_atmosphere's ground_albedo)
  const ground = [0, 1, 2].map((k) => albedo / Math.PI * (sunGround[k] * Math.max(sunDir[1], 0) + low.irradiance[k]));
  // EV100 that exposes the sky's mean luminance to middle grey (scene.cpp), and its exposure.
  const ev100 = Math.log2(Math.max(0.5 * (luminance(skyZenith) + luminance(skyHorizon)), 1e-3) * 100 / 12.5);
  return {
    sunRadiance: texel(sunHeights), sunByHeight, skyZenith, skyHorizon, ground, ambientTop: top.mean, ambientBottom: ground,
    band: texel(sunHeights + 11).slice(0, 2),
    ev100, exposure: 1 / (1.2 * Math.pow(2, ev100)), ms: performance.now() - t0,
    // The tables as read back, for WebGPU (webgpu.js's setPhysicalTables, with the far shadow's).
    tables: { haze: { width: hazeSize[0] * hazeSize[1], height: hazeSize[2], data: haze },
              skyView: { width: skyViewSize[0], height: skyViewSize[1], data: below } },
  };
}

// The far shadow's table (far_shadow.cpp's make_table): its range for the scene s, the band
// (the bake's), the variant v (scene.js's variants) and frame constants f (scene.js's
// frameConstants): the march's end (scene.cpp's light_reach), the sun's zenith cosines from
// where every path from the band's top meets the ground to where the march reaches the band's
// end, and the field's period (the classic field's weather tile).
export function farShadowParams(s, band, v, f) {
  const reach = v.light === 0 ? f.coneFarDistance + 0.5 * f.coneFarLength : 30000;
  const R = s.planetRadius, top = R + band[1];
  const muLo = -Math.sqrt(Math.max(1 - (R / top) * (R / top), 0));
  const muHi = Math.min((band[1] - band[0]) / Math.max(reach, 1), 1);
  return { u_far_shadow_size: farShadowSize, u_far_shadow_range: [band[0], band[1], muLo, muHi], u_far_shadow_reach: reach,
           u_far_shadow_period: s.weatherTile };
}
