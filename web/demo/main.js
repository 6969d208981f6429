// The demo page: parity of the cm_ functions (GPU against JavaScript) and the example
// renderer's clouds, both from the cloudmath-glsl package's generated sources; the same clouds
// from clouds.wgsl on WebGPU beside them (webgpu.js), compared pixel by pixel.
// window.cloudmathDemo holds the results (read by web/test/browser.mjs).
import { modules, resolve } from '../dist/index.js';
import { cases, defaultBudget, floor } from './parity.js';
import { scenePresets, variants, msPresets, frameConstants, phaseMeanCosine, terrainBoxes } from './scene.js';
import { cloudsFrag, compositeFrag } from './clouds_frag.js';
import { skyTablesFrag } from './sky_tables_frag.js';
import { imageStats, compareImages, shiftImage } from './image.js';
import { initWebGPU, createClouds, renderClouds, setPhysicalTables } from './webgpu.js';
import { createPhysicalSky, bakePhysicalSky, farShadowParams, farShadowSize, hazeSize, hazeDistance } from './physical_sky.js';

const demo = (window.cloudmathDemo = { ready: false, error: null, parity: [], image: null, frames: [],
  webgpu: { available: false, reason: 'not tried yet', adapter: null, frameMs: null, frames: [], image: null, comparison: null, busy: false } });
const params = new URLSearchParams(location.search);
const baseSize = Number(params.get('base') || 64);  // base noise volume edge (the desktop renderer: 128)
const status = (text) => { document.getElementById('status').textContent = text; };
// The names of clouds.frag's permutation switches (its CR_PARAM lines: compiled in as
// constants) and of all its uniforms (those, its uniform lines and its block CrFrame's members).
const cloudsFragSwitches = [...cloudsFrag.matchAll(/^CR_PARAM\(\w+,\s*(\w+)\)/gm)].map((m) => m[1]);
const cloudsFragUniforms = new Set(cloudsFragSwitches);
for (const m of cloudsFrag.matchAll(/^uniform\s+\w+\s+([^;]+);/gm)) for (const n of m[1].split(',')) cloudsFragUniforms.add(n.trim().replace(/\[\d+\]$/, ''));
const cloudsFragBlock = /uniform CrFrame \{([\s\S]*?)\};/.exec(cloudsFrag)[1].replace(/\/\/.*$/gm, '');
for (const m of cloudsFragBlock.matchAll(/\w+\s+([^;]+);/g)) for (const n of m[1].split(',')) cloudsFragUniforms.add(n.trim().replace(/\[\d+\]$/, ''));
// composite.frag's switches (the dither), compiled into its program, not clouds.frag's.
const compositeSwitches = [...compositeFrag.matchAll(/^CR_PARAM\(\w+,\s*(\w+)\)/gm)].map((m) => m[1]);
// A permutation's constants: `const int name = value;` for each switch name (unset: 0), compiled
// in as the desktop host does (gl_renderer.cpp's permutation_block).
const constantLines = (names, values) => names.map((name) => `const int ${name} = ${Math.trunc(values[name] ?? 0)};\n`).join('');

const canvas = document.getElementById('view');
const gl = canvas.getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
const header = '#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp sampler3D;\n';
const vertexSource = '#version 300 es\nvoid main() { vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0); gl_Position = vec4(p, 0.0, 1.0); }\n';

function compile(type, source, what) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`${what}: ${gl.getShaderInfoLog(s)}`);
  return s;
}
function program(fragmentSource, what) {
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl.VERTEX_SHADER, vertexSource, what + ' (vertex)'));
  gl.attachShader(p, compile(gl.FRAGMENT_SHADER, fragmentSource, what));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(`${what}: ${gl.getProgramInfoLog(p)}`);
  return p;
}
const drawTriangle = () => gl.drawArrays(gl.TRIANGLES, 0, 3);

// ------------------------------------------------------------------------------------------
// Parity: inputs in an RGBA32F texture (one texel each), results in an RGBA32F target.
function runParity() {
  if (!gl.getExtension('EXT_color_buffer_float')) throw new Error('EXT_color_buffer_float is missing: no float render target');
  const rows = [];
  for (const c of cases) {
    const n = c.inputs.length;
    const data = new Float32Array(n * 4);
    c.inputs.forEach((a, i) => data.set(a, 4 * i));
    const input = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, input);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, n, 1, 0, gl.RGBA, gl.FLOAT, data);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    const target = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, target);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, n, 1, 0, gl.RGBA, gl.FLOAT, null);
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
    const source = header + modules[c.module] +
      `\nuniform sampler2D u_in;\nout vec4 o;\nvoid main() {\n  vec4 a = texelFetch(u_in, ivec2(gl_FragCoord.xy), 0);\n  o = vec4(${c.expr}, 0.0, 0.0, 0.0);\n}\n`;
    const p = program(source, c.fn);
    gl.useProgram(p);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, input);
    gl.uniform1i(gl.getUniformLocation(p, 'u_in'), 0);
    gl.viewport(0, 0, n, 1);
    drawTriangle();
    const out = new Float32Array(n * 4);
    gl.readPixels(0, 0, n, 1, gl.RGBA, gl.FLOAT, out);
    let worst = 0, nonFinite = 0, worstAt = null;
    c.inputs.forEach((a, i) => {
      const got = out[4 * i], want = c.ref(a);
      if (!Number.isFinite(got)) { nonFinite++; return; }
      const err = Math.abs(got - want) / Math.max(Math.abs(want), c.floor ?? floor);
      if (err > worst) { worst = err; worstAt = a; }
    });
    const budget = c.budget || defaultBudget;
    rows.push({ fn: c.fn, values: n, maxError: worst, budget, nonFinite, worstAt, pass: worst <= budget && nonFinite === 0 });
    gl.deleteFramebuffer(fbo); gl.deleteTexture(input); gl.deleteTexture(target); gl.deleteProgram(p);
  }
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  const body = document.querySelector('#parity tbody');
  for (const r of rows) {
    const tr = document.createElement('tr');
    tr.className = r.pass ? 'pass' : 'fail';
    for (const v of [r.fn, r.values, r.maxError.toExponential(1), r.budget.toExponential(0), r.nonFinite]) {
      const td = document.createElement('td'); td.textContent = v; tr.appendChild(td);
    }
    body.appendChild(tr);
  }
  return rows;
}

// ------------------------------------------------------------------------------------------
// Noise textures, baked on the GPU with cloudmath's noise functions: the texel formulas of
// include/cloudmath/noise_bake.hpp (bake_base_texel, bake_detail_texel, bake_weather_texel),
// seed 0, with the renderer's cells (4, 2, 4), quantised to RGBA8 by the render target.
const bakeSource = header + modules.noise + `
uniform int u_kind;   // 0 base, 1 detail, 2 weather
uniform int u_size, u_cells, u_layer;
out vec4 o;
uint channelSeed(uint channel) { return cm_noise_hash(0u) + channel * 0x10000000u; }
float coord(int i) { return (float(i) + 0.5) * float(u_cells) / float(u_size); }
void main() {
  ivec2 ij = ivec2(gl_FragCoord.xy);
  vec3 p = vec3(coord(ij.x), coord(ij.y), coord(u_layer));
  int c = u_cells;
  if (u_kind == 0) {
    o = vec4(cm_perlin_worley(p, c, channelSeed(0u)), cm_worley_fbm_nubis(p * 2.0, 2 * c, channelSeed(1u)),
             cm_worley_fbm_nubis(p * 4.0, 4 * c, channelSeed(2u)), cm_worley_fbm_nubis(p * 8.0, 8 * c, channelSeed(3u)));
  } else if (u_kind == 1) {
    o = vec4(cm_worley_fbm_nubis(p, c, channelSeed(4u)), cm_worley_fbm_nubis(p * 2.0, 2 * c, channelSeed(5u)),
             cm_worley_fbm_nubis(p * 4.0, 4 * c, channelSeed(6u)), 1.0);
  } else {
    vec2 q = p.xy;
    o = vec4(cm_saturate(0.5 + cm_perlin_fbm(q, c, 4, 2, 0.5, channelSeed(8u))),
             cm_saturate(0.5 + cm_perlin_fbm(q, c, 2, 2, 0.5, channelSeed(9u))),
             cm_saturate(0.5 + cm_perlin_fbm(q, c, 3, 2, 0.5, channelSeed(10u))), 1.0);
  }
}
`;

function bakeTextures(keepTexels) {
  const p = program(bakeSource, 'noise bake');
  gl.useProgram(p);
  const u = (n) => gl.getUniformLocation(p, n);
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  function make(kind, size, cells, depth) {
    const target = depth > 1 ? gl.TEXTURE_3D : gl.TEXTURE_2D;
    const t = gl.createTexture();
    gl.bindTexture(target, t);
    if (depth > 1) gl.texStorage3D(target, 1, gl.RGBA8, size, size, size);
    else gl.texStorage2D(target, 1, gl.RGBA8, size, size);
    for (const [k, v] of [[gl.TEXTURE_MIN_FILTER, gl.LINEAR], [gl.TEXTURE_MAG_FILTER, gl.LINEAR],
      [gl.TEXTURE_WRAP_S, gl.REPEAT], [gl.TEXTURE_WRAP_T, gl.REPEAT], [gl.TEXTURE_WRAP_R, gl.REPEAT]]) gl.texParameteri(target, k, v);
    gl.uniform1i(u('u_kind'), kind);
    gl.uniform1i(u('u_size'), size);
    gl.uniform1i(u('u_cells'), cells);
    gl.viewport(0, 0, size, size);
    for (let z = 0; z < depth; ++z) {
      if (depth > 1) gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, t, 0, z);
      else gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, t, 0);
      gl.uniform1i(u('u_layer'), z);
      drawTriangle();
      if (texels) {  // the same texels for WebGPU: read each layer back
        texels[kind] ??= { size, depth, data: new Uint8Array(size * size * depth * 4) };
        gl.readPixels(0, 0, size, size, gl.RGBA, gl.UNSIGNED_BYTE, texels[kind].data.subarray(z * size * size * 4, (z + 1) * size * size * 4));
      }
    }
    return t;
  }
  const texels = keepTexels ? [] : null;
  const textures = { base: make(0, baseSize, 4, baseSize), detail: make(1, 32, 2, 32), weather: make(2, 256, 4, 1) };
  if (texels) textures.texels = { base: texels[0], detail: texels[1], weather: texels[2] };
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));  // waits for the bake
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.deleteFramebuffer(fbo);
  // The Beer shadow map's stand-in: one float texel, never read with shadows off.
  textures.noShadow = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, textures.noShadow);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, 1, 1, 0, gl.RGBA, gl.FLOAT, new Float32Array(4));
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  return textures;
}

// ------------------------------------------------------------------------------------------
// The cloud pass: clouds.frag with the package's resolver for its #include "cloudmath.glsl",
// one program per permutation as engines ship it (the desktop renderer's default): the
// switches (CR_PARAM) compiled in as constants, so the compiler keeps only the variant's own
// paths; a program is compiled the first time its permutation is drawn.
let clouds = null, textures = null, target = null;
// The physical sky's baker, its last bake (key: scene and sun), its last far shadow (key: the
// bake's, the coverage and the reach) and the tables WebGPU reads (a new object when either changes).
const physicalSky = { sky: null, baked: null, key: null, farKey: null, tables: null };
const cloudPrograms = new Map();
function useClouds(values) {
  // The physical sky is a permutation as well (the desktop host's #define CR_PHYSICAL_SKY).
  const constants = (values.u_physical_sky ? '#define CR_PHYSICAL_SKY 1\n' : '') +
    constantLines(cloudsFragSwitches, values);
  if (!cloudPrograms.has(constants))
    cloudPrograms.set(constants, program(header + '#define CR_PARAM(type, name)\n' + constants + resolve(cloudsFrag), 'clouds.frag'));
  clouds = cloudPrograms.get(constants);
}
// A frame's targets, as the desktop renderer's: clouds.frag's pass 3 (what lies behind the layer,
// RGBA32F, and the scene's depth, R32F) and pass 0 (the layer: premultiplied radiance and
// opacity, RGBA32F, and the cloud's depth, R32F), then composite.frag's display image (RGBA8).
function frameTarget(formats) {
  const t = { fbo: gl.createFramebuffer(), tex: formats.map(() => gl.createTexture()) };
  gl.bindFramebuffer(gl.FRAMEBUFFER, t.fbo);
  formats.forEach((format, i) => {
    gl.bindTexture(gl.TEXTURE_2D, t.tex[i]);
    gl.texStorage2D(gl.TEXTURE_2D, 1, format, canvas.width, canvas.height);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, gl.TEXTURE_2D, t.tex[i], 0);
  });
  gl.drawBuffers(formats.map((_, i) => gl.COLOR_ATTACHMENT0 + i));
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error('a frame target is incomplete');
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  return t;
}
function setupClouds(values) {
  useClouds(values);
  target = { background: frameTarget([gl.RGBA32F, gl.R32F]), layer: frameTarget([gl.RGBA32F, gl.R32F]), display: frameTarget([gl.RGBA8]) };
}

// composite.frag's program for the values' composite switches (the dither), compiled on first use.
const compositePrograms = new Map();
function useComposite(values) {
  const constants = constantLines(compositeSwitches, values);
  if (!compositePrograms.has(constants))
    compositePrograms.set(constants, program(header + '#define CR_PARAM(type, name)\n' + constants + resolve(compositeFrag), 'composite.frag'));
  return compositePrograms.get(constants);
}

// The cloud pass's uniform values by their GLSL names (clouds.frag's uniforms; the WebGPU
// pass sets the same values into clouds.wgsl's CrUniforms members of the same names). Unset
// uniforms are 0 in both.
function cloudUniforms(state) {
  const s = { ...scenePresets.find((x) => x.name === state.scene) };
  s.sunElevation = state.sunElevation;
  s.coverage = state.coverage;
  const f = frameConstants(s);
  // The physical sky (state.sky): its tables baked on the GPU for this scene and sun (kept
  // until either changes), the sky's values from them; the exposure from EV100.
  let physical = null;
  if (state.sky === 'physical') {
    const key = JSON.stringify([s.name, s.sunElevation]);
    if (!physicalSky.baked || physicalSky.key !== key) {
      physicalSky.baked = bakePhysicalSky(gl, physicalSky.sky, s, f.sunDir);
      physicalSky.key = key;
      demo.sky = physicalSky.baked;
    }
    physical = physicalSky.baked;
  }
  const v = variants[state.variant];
  const [msA, msB, msC, msN] = msPresets[state.ms];
  return {
    u_phase_model: v.phase, u_lighting: v.lighting, u_octaves: state.ms === 'production' ? v.octaves : msN, u_powder: v.powder,
    u_light_mode: v.light, u_behind_mode: v.behind, u_phase_mean_cosine: phaseMeanCosine(f, v.phase),
    u_light_steps: v.lightSteps, u_integration: v.integration, u_refine: v.refine,
    u_view_steps: v.viewSteps, u_schedule: v.schedule, u_sun_disc: v.sun, u_haze: v.haze, u_dither: v.dither, u_terrain: s.terrain ? 1 : 0,
    u_occluded_ambient: v.ambient, u_reach: v.reach, u_shadows: v.shadows, u_pass: 0,
    u_shape: 0,  // the classic density field: the demo bakes no wide weather map or curl texture
    u_resolution: [canvas.width, canvas.height],
    u_forward: f.forward, u_right: f.right, u_up: f.up, u_tan_half_fov: f.tanHalfFov,
    u_cam_altitude: s.cameraAltitude, u_planet_radius: s.planetRadius, u_layer_bottom: s.layerBottom, u_layer_top: s.layerTop,
    u_sun_dir: f.sunDir, u_sun_radiance: f.sunRadiance, u_ambient_top: f.ambientTop, u_ambient_bottom: f.ambientBottom,
    u_sky_zenith: f.skyZenith, u_sky_horizon: f.skyHorizon, u_ground: f.ground, u_sun_angular_radius: f.sunAngularRadius, u_aureole: 0.05,
    u_coverage: s.coverage, u_cloud_type: s.cloudType, u_extinction: s.extinction, u_albedo: s.albedo, u_max_distance: s.maxDistance,
    u_base_tile: s.baseTile, u_detail_tile: s.detailTile, u_weather_tile: s.weatherTile, u_wind: s.wind,
    u_exposure: s.exposure, u_terrain_boxes: terrainBoxes.flat(),
    u_phase_g: f.phaseG, u_phase_g_back: f.phaseGBack, u_phase_w: f.phaseW, u_droplet_diameter: f.dropletDiameter,
    u_ms_a: msA, u_ms_b: msB, u_ms_c: msC,
    u_cone_step: f.coneStep, u_cone_spread: f.coneSpread, u_cone_far_distance: f.coneFarDistance, u_cone_far_length: f.coneFarLength,
    u_light_march_max: f.lightMarchMax, u_min_transmittance: f.minTransmittance, u_march_near_distance: f.marchNearDistance,
    ...(physical ? {
      u_physical_sky: 1,  // the permutation: clouds.frag's CR_PHYSICAL_SKY (useClouds), clouds.wgsl's override
      u_sun_radiance: physical.sunRadiance, u_sun_by_height: physical.sunByHeight.flat(), u_sky_zenith: physical.skyZenith,
      u_sky_horizon: physical.skyHorizon, u_ground: physical.ground, u_ambient_top: physical.ambientTop,
      u_ambient_bottom: physical.ambientBottom, u_aureole: 0, u_exposure: physical.exposure,
      u_haze_table_size: hazeSize, u_haze_table_distance: hazeDistance, ...farShadowParams(s, physical.band, v, f),
    } : {}),
  };
}

// clouds.frag's uniform block CrFrame as program p lays it out: its size and each member's
// offset, array stride and type (all std140 members are active), read once per program; the
// block bound to binding 0.
let frameUbo = null;
const blockLayouts = new WeakMap();
const GL = WebGL2RenderingContext;  // its constants, whether or not a context was made
const blockTypes = new Map([[GL.FLOAT, { n: 1, view: 'f' }], [GL.FLOAT_VEC2, { n: 2, view: 'f' }], [GL.FLOAT_VEC3, { n: 3, view: 'f' }],
  [GL.FLOAT_VEC4, { n: 4, view: 'f' }], [GL.INT, { n: 1, view: 'i' }], [GL.UNSIGNED_INT, { n: 1, view: 'u' }],
  [GL.UNSIGNED_INT_VEC2, { n: 2, view: 'u' }]]);
function frameBlockLayout(p) {
  if (blockLayouts.has(p)) return blockLayouts.get(p);
  const index = gl.getUniformBlockIndex(p, 'CrFrame');
  if (index === gl.INVALID_INDEX) throw new Error('clouds.frag has no uniform block CrFrame');
  const indices = gl.getActiveUniformBlockParameter(p, index, gl.UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES);
  const offsets = gl.getActiveUniforms(p, indices, gl.UNIFORM_OFFSET);
  const strides = gl.getActiveUniforms(p, indices, gl.UNIFORM_ARRAY_STRIDE);
  const types = gl.getActiveUniforms(p, indices, gl.UNIFORM_TYPE);
  const members = new Map();
  indices.forEach((u, i) => members.set(gl.getActiveUniform(p, u).name.replace(/\[0\]$/, ''), { offset: offsets[i], stride: strides[i], type: types[i] }));
  gl.uniformBlockBinding(p, index, 0);
  const layout = { size: gl.getActiveUniformBlockParameter(p, index, gl.UNIFORM_BLOCK_DATA_SIZE), members };
  blockLayouts.set(p, layout);
  return layout;
}

// Makes clouds.frag's program for `values` current with every uniform set and the textures
// bound (the physical sky's far shadow: farShadow, the table or, while it is drawn, a stand-in).
function bindClouds(values, farShadow) {
  useClouds(values);
  gl.useProgram(clouds);
  // The frame's constants go into clouds.frag's uniform block CrFrame, at the offsets the
  // program reports (std140), one buffer on binding 0; a value for no member is an error.
  const layout = frameBlockLayout(clouds);
  const data = new ArrayBuffer(layout.size);
  const views = { f: new Float32Array(data), i: new Int32Array(data), u: new Uint32Array(data) };
  for (const [name, v] of Object.entries(values)) {
    if (name === 'u_physical_sky' || compositeSwitches.includes(name)) continue;  // compiled in (useClouds, useComposite)
    const m = layout.members.get(name);
    if (m === undefined) { if (!cloudsFragUniforms.has(name)) throw new Error(`clouds.frag declares no uniform ${name}`); continue; }
    const kind = blockTypes.get(m.type);
    if (kind === undefined) throw new Error(`clouds.frag: CrFrame member ${name} has type 0x${m.type.toString(16)}, which bindClouds() does not set`);
    const xs = typeof v === 'number' ? [v] : Array.from(v).flat();
    for (let e = 0; e * kind.n < xs.length; ++e)
      for (let c = 0; c < kind.n; ++c) views[kind.view][(m.offset + e * m.stride) / 4 + c] = xs[e * kind.n + c];
  }
  if (!frameUbo) frameUbo = gl.createBuffer();
  gl.bindBuffer(gl.UNIFORM_BUFFER, frameUbo);
  gl.bufferData(gl.UNIFORM_BUFFER, data, gl.DYNAMIC_DRAW);
  gl.bindBufferBase(gl.UNIFORM_BUFFER, 0, frameUbo);
  // u_shadow_map, u_weather_wide and u_curl get units of their own (a 1 x 1 texture: shadows
  // are off and the shape is classic), so that no unit holds two texture types.
  const units = [['u_base', gl.TEXTURE_3D, textures.base], ['u_detail', gl.TEXTURE_3D, textures.detail], ['u_weather', gl.TEXTURE_2D, textures.weather],
                 ['u_shadow_map', gl.TEXTURE_2D, textures.noShadow], ['u_weather_wide', gl.TEXTURE_2D, textures.noShadow],
                 ['u_curl', gl.TEXTURE_2D, textures.noShadow]];
  if (values.u_physical_sky)
    units.push(['u_haze_table', gl.TEXTURE_2D, physicalSky.sky.haze], ['u_sky_view', gl.TEXTURE_2D, physicalSky.sky.skyView],
               ['u_far_shadow', gl.TEXTURE_2D, farShadow]);
  units.forEach(([name, kind, tex], i) => { gl.activeTexture(gl.TEXTURE0 + i); gl.bindTexture(kind, tex); gl.uniform1i(gl.getUniformLocation(clouds, name), i); });
}

// The far shadow for the physical sky's `values` (clouds.frag's pass 4 into the 16 x 48 table,
// read back for WebGPU), drawn again when the scene, sun, coverage or light reach change.
function ensureFarShadow(values) {
  const key = JSON.stringify([physicalSky.key, values.u_coverage, values.u_far_shadow_reach]);
  if (physicalSky.farKey === key) return;
  const t0 = performance.now();
  bindClouds({ ...values, u_pass: 4 }, physicalSky.sky.farShadow);
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, physicalSky.sky.farTable, 0);
  gl.viewport(0, 0, ...farShadowSize);
  drawTriangle();
  const data = new Float32Array(farShadowSize[0] * farShadowSize[1] * 4);
  gl.readPixels(0, 0, ...farShadowSize, gl.RGBA, gl.FLOAT, data);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.deleteFramebuffer(fbo);
  physicalSky.farKey = key;
  demo.farShadow = { ms: performance.now() - t0, table: Array.from(data.filter((_, i) => i % 4 === 0)) };
  const b = physicalSky.baked.tables;
  physicalSky.tables = { haze: b.haze, skyView: b.skyView, farShadow: { width: farShadowSize[0], height: farShadowSize[1], data } };
}

function render(values) {
  if (values.u_physical_sky) ensureFarShadow(values);
  const farShadow = values.u_physical_sky ? physicalSky.sky.farTable : null;
  const composite = useComposite(values);
  const pixels = new Uint8Array(canvas.width * canvas.height * 4);
  gl.viewport(0, 0, canvas.width, canvas.height);
  useClouds({ ...values, u_pass: 3 });  // both programs compiled before the timing
  useClouds(values);
  const t0 = performance.now();
  // The background (clouds.frag's pass 3), the layer (pass 0), then the composite.
  bindClouds({ ...values, u_pass: 3 }, farShadow);
  gl.bindFramebuffer(gl.FRAMEBUFFER, target.background.fbo);
  drawTriangle();
  bindClouds(values, farShadow);
  gl.bindFramebuffer(gl.FRAMEBUFFER, target.layer.fbo);
  drawTriangle();
  gl.useProgram(composite);
  gl.uniform1f(gl.getUniformLocation(composite, 'u_exposure'), values.u_exposure);
  gl.uniform1ui(gl.getUniformLocation(composite, 'u_frame'), values.u_frame ?? 0);
  [['u_layer', target.layer.tex[0]], ['u_background', target.background.tex[0]]].forEach(([name, tex], i) => {
    gl.activeTexture(gl.TEXTURE9 + i); gl.bindTexture(gl.TEXTURE_2D, tex); gl.uniform1i(gl.getUniformLocation(composite, name), 9 + i); });
  gl.bindFramebuffer(gl.FRAMEBUFFER, target.display.fbo);
  drawTriangle();
  gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);  // waits for the frame
  const ms = performance.now() - t0;
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, target.display.fbo);
  gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
  gl.blitFramebuffer(0, 0, canvas.width, canvas.height, 0, 0, canvas.width, canvas.height, gl.COLOR_BUFFER_BIT, gl.NEAREST);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  return { ms, pixels, stats: imageStats(pixels) };
}

// ------------------------------------------------------------------------------------------
// WebGPU: clouds.wgsl beside clouds.frag. Frames are drawn one at a time; a change made while
// one is in flight draws the latest state next. Each frame is compared with the WebGL2 frame
// of the same uniform values.
let gpuClouds = null, gpuNext = null, gpuDone = Promise.resolve(), lastFrame = null;
const gpuStatus = (text) => { document.getElementById('webgpuStatus').textContent = text; };
const psnrText = (c) => (c.psnrDb === Infinity ? 'inf' : c.psnrDb.toFixed(1));
const showComparison = (c) => `PSNR ${psnrText(c)} dB, mean |difference| ${c.meanAbsDiff.toFixed(3)}, ` +
  `largest ${c.maxAbsDiff} of 255 (opacity ${c.alphaMaxAbsDiff}), ${(100 * c.differingPixelFraction).toFixed(2)} % of the pixels differ`;

async function setupWebGPU() {
  const w = demo.webgpu;
  const gpu = await initWebGPU();
  if (!gpu.device) { w.reason = gpu.reason; gpuStatus(`WebGPU is not available: ${gpu.reason}. The WebGL2 image is unaffected.`); return; }
  w.adapter = gpu.name;
  gpu.device.lost.then((info) => { w.error = `WebGPU device lost: ${info.message}`; gpuStatus(w.error); });
  w.fallbackAdapter = gpu.fallback;
  gpuStatus(`compiling clouds.wgsl on ${gpu.name}...`);
  const t0 = performance.now();
  gpuClouds = await createClouds(gpu, document.getElementById('viewGpu'), textures.texels, params.get('present') === '2d');
  w.presentation = gpuClouds.context ? 'WebGPU canvas context' : '2D canvas (read-back image, ?present=2d)';
  w.compileMs = performance.now() - t0;
  w.compilerMessages = gpuClouds.warnings;
  w.available = true;
  w.reason = null;
}

// The physical sky's baker, made the first time the physical sky is drawn (the artistic sky
// needs neither the table nor its program): the refined multiple-scattering table
// (web/demo/sky_table.bin) and the bake program (physical_sky.js).
async function loadPhysicalSky() {
  if (physicalSky.sky) return;
  status('the physical sky: its table...');
  const response = await fetch('sky_table.bin');
  if (!response.ok) throw new Error(`sky_table.bin: HTTP ${response.status}`);
  physicalSky.sky = createPhysicalSky(gl, header, resolve(skyTablesFrag), program, await response.arrayBuffer());
}

// The physical sky's tables for WebGPU: the bake a frame was drawn with (its job's), uploaded
// once per bake, right before that frame (frames run one at a time: a frame in flight keeps
// the tables it was encoded with).
function uploadPhysicalTables(values, tables) {
  if (!values.u_physical_sky || !gpuClouds || gpuClouds.physicalTables === tables) return;
  setPhysicalTables(gpuClouds, tables);
  gpuClouds.physicalTables = tables;
}

function drawWebGPU(values, glPixels) {
  const w = demo.webgpu;
  if (!gpuClouds) return Promise.resolve();
  const job = { values, glPixels, tables: physicalSky.tables };
  if (w.busy) { gpuNext = job; return gpuDone; }
  w.busy = true;
  gpuDone = (async () => {
    for (let j = job; j; j = gpuNext, gpuNext = null) {
      uploadPhysicalTables(j.values, j.tables);
      const r = await renderClouds(gpuClouds, j.values);
      w.frames.push(r.ms);
      w.frameMs = r.ms;
      w.image = imageStats(r.pixels);
      w.comparison = compareImages(j.glPixels, r.pixels);
      gpuStatus(`${canvas.width} x ${canvas.height} on ${w.adapter}: ${r.ms.toFixed(1)} ms per frame (submit to mapped readback); ` +
        `against WebGL2: ${showComparison(w.comparison)}`);
    }
  })().catch((e) => { w.error = String(e && e.message || e); gpuStatus('WebGPU error: ' + w.error); console.error(e); })
    .finally(() => { w.busy = false; });
  return gpuDone;
}

// For web/test/browser.mjs, to show that the comparison can fail: the current WebGL2 frame
// against a WebGPU frame with some uniform values changed, or against itself shifted.
window.cloudmathDemoTools = {
  async perturbed(overrides) {
    await gpuDone;
    const r = await renderClouds(gpuClouds, { ...lastFrame.values, ...overrides }, false);
    return { overrides, image: imageStats(r.pixels), comparison: compareImages(lastFrame.pixels, r.pixels) };
  },
  shifted(dx) { return compareImages(lastFrame.pixels, shiftImage(lastFrame.pixels, canvas.width, dx)); },
};

// ------------------------------------------------------------------------------------------
function fillSelect(id, names, value) {
  const el = document.getElementById(id);
  for (const n of names) { const o = document.createElement('option'); o.value = o.textContent = n; el.appendChild(o); }
  el.value = value;
  return el;
}

async function main() {
  if (!gl) throw new Error('WebGL2 is not available');
  const dbg = gl.getExtension('WEBGL_debug_renderer_info');
  demo.renderer = dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  document.getElementById('device').textContent = `Renderer: ${demo.renderer}; ${navigator.userAgent}`;
  // Let the page finish loading before the long synchronous GL work (a software renderer
  // takes tens of seconds for the parity shaders, the bake and the cloud shader).
  await new Promise((resolve) => setTimeout(resolve, 0));
  status('parity...');
  demo.parity = runParity();
  status('baking noise textures...');
  let t0 = performance.now();
  textures = bakeTextures(!!navigator.gpu);  // keeps the texels for WebGPU
  gl.finish();
  demo.bakeMs = performance.now() - t0;
  const state = { scene: params.get('scene') || 'cumulus', variant: params.get('variant') || 'default', ms: params.get('ms') || 'production',
                  sky: params.get('sky') || 'physical' };  // the desktop renderer's default sky
  if (!['artistic', 'physical'].includes(state.sky)) throw new Error(`unknown sky ${state.sky} (artistic or physical)`);
  if (state.sky === 'physical') await loadPhysicalSky();
  const preset = () => scenePresets.find((x) => x.name === state.scene);
  state.sunElevation = Number(params.get('sun') ?? preset().sunElevation);
  state.coverage = Number(params.get('coverage') ?? preset().coverage);
  status('compiling the cloud shader...');
  t0 = performance.now();
  setupClouds(cloudUniforms(state));
  demo.compileMs = performance.now() - t0;
  const sun = document.getElementById('sun'), coverage = document.getElementById('coverage');
  const draw = () => {
    sun.value = state.sunElevation; coverage.value = state.coverage;
    document.getElementById('sunValue').textContent = `${state.sunElevation} deg`;
    document.getElementById('coverageValue').textContent = state.coverage.toFixed(2);
    const values = cloudUniforms(state);
    demo.exposure = values.u_exposure;
    const r = render(values);
    lastFrame = { values, pixels: r.pixels };
    demo.image = r.stats;
    demo.frames.push(r.ms);
    document.getElementById('timing').textContent = `${canvas.width} x ${canvas.height}: ${r.ms.toFixed(1)} ms per frame ` +
      `(draw to readPixels, after a warm-up draw); base volume ${baseSize}^3 baked in ${demo.bakeMs.toFixed(0)} ms`;
    drawWebGPU(values, r.pixels);  // asynchronous: demo.webgpu.busy until it is drawn and compared
  };
  fillSelect('scene', scenePresets.map((x) => x.name), state.scene).onchange = (e) => {
    state.scene = e.target.value; state.sunElevation = preset().sunElevation; state.coverage = preset().coverage; draw(); };
  fillSelect('variant', Object.keys(variants), state.variant).onchange = (e) => { state.variant = e.target.value; draw(); };
  fillSelect('ms', Object.keys(msPresets), state.ms).onchange = (e) => { state.ms = e.target.value; draw(); };
  fillSelect('sky', ['artistic', 'physical'], state.sky).onchange = async (e) => {
    try {
      if (e.target.value === 'physical') await loadPhysicalSky();
      state.sky = e.target.value;
      draw();
    } catch (err) { demo.error = String(err && err.message || err); status('error: ' + demo.error); }
  };
  sun.oninput = () => { state.sunElevation = Number(sun.value); draw(); };
  coverage.oninput = () => { state.coverage = Number(coverage.value); draw(); };
  render(cloudUniforms(state));  // warm-up: the driver finishes compiling at the first draw
  draw();

  // WebGPU beside it; any failure there leaves the WebGL2 part as it is.
  status('WebGPU: clouds.wgsl...');
  try {
    await setupWebGPU();
    if (gpuClouds) {
      uploadPhysicalTables(lastFrame.values, physicalSky.tables);
      const warm = await renderClouds(gpuClouds, lastFrame.values);  // warm-up, as for WebGL2
      demo.webgpu.warmUpMs = warm.ms;
      await drawWebGPU(lastFrame.values, lastFrame.pixels);
    }
  } catch (e) {
    demo.webgpu.error = String(e && e.message || e);
    gpuStatus('WebGPU error: ' + demo.webgpu.error);
    console.error(e);
  }
  const failed = demo.parity.filter((r) => !r.pass).length;
  const w = demo.webgpu;
  status(`ready: ${demo.parity.length} parity cases, ${failed} over budget; clouds drawn; WebGPU ` +
    (w.error ? 'failed' : w.available ? `drawn, PSNR ${w.comparison ? psnrText(w.comparison) : '?'} dB against WebGL2` : 'not available'));
  demo.ready = true;
}

main().catch((e) => { demo.error = String(e && e.message || e); status('error: ' + demo.error); console.error(e); });
