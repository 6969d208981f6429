// The WebGPU half of the demo: the example renderer's clouds from clouds.wgsl (the WGSL port of
// clouds.frag) with cloudmath's generated WGSL library (include/cloudmath/wgsl/, from the
// package: dist/index.js's wgslSources), on the noise textures the WebGL2 path baked, with the
// same uniform values. The uniform buffer's layout is read from clouds.wgsl's CrUniforms struct
// (WGSL's alignment rules), so the values are set by their GLSL names, the same list the
// WebGL2 path sets.
import { wgslSources } from '../dist/index.js';
import { cloudsWgsl } from './clouds_wgsl.js';

// One WGSL module (WGSL has no #include; module-scope declarations may come in any order):
// cloudmath.wgsl, the whole library without hooks; the *_hooks.wgsl files whose hooks
// clouds.wgsl defines (cm_cone_extinction, cm_ms_phase, cm_diffusion_phase; each file's header
// names its hooks: "//   fn cm_x(..."), the functions that call them; clouds.wgsl.
const hooksOf = (text) => [...text.matchAll(/^\/\/ {3}fn (cm_\w+)\(/gm)].map((m) => m[1]);
const definesHooks = (text) => hooksOf(text).every((fn) => new RegExp(`^fn ${fn}\\(`, 'm').test(cloudsWgsl));
export const cloudsWgslParts = [
  ['cloudmath.wgsl', wgslSources['cloudmath.wgsl']],
  ...Object.keys(wgslSources).filter((f) => f.endsWith('_hooks.wgsl') && definesHooks(wgslSources[f])).sort()
    .map((f) => [f, wgslSources[f]]),
  ['clouds.wgsl', cloudsWgsl],
];

// Byte alignment and size of the uniform struct's member types (WGSL's host-shareable layout).
const layoutOf = { i32: [4, 4], u32: [4, 4], f32: [4, 4], vec2f: [8, 8], vec2i: [8, 8], vec2u: [8, 8],
  vec3f: [16, 12], vec3i: [16, 12], vec3u: [16, 12], vec4f: [16, 16], vec4i: [16, 16], vec4u: [16, 16] };

// Members of `struct name { ... }` in WGSL source, with their offsets: [{ name, type, offset,
// count, stride }] (count and stride for an array<T, N> member: N elements, each at a multiple
// of 16 bytes, as the uniform address space lays arrays out), size.
export function structLayout(source, name) {
  const m = source.match(new RegExp(`struct\\s+${name}\\s*\\{([\\s\\S]*?)\\n\\}`));
  if (!m) throw new Error(`struct ${name} not found in clouds.wgsl`);
  const body = m[1].replace(/\/\/.*$/gm, '');
  const members = [];
  let offset = 0, maxAlign = 4;
  for (const [, member, arrayOf, count, plain] of body.matchAll(/(\w+)\s*:\s*(?:array<\s*(\w+)\s*,\s*(\d+)\s*>|(\w+))\s*,?/g)) {
    const type = arrayOf || plain;
    if (!layoutOf[type]) throw new Error(`struct ${name}: member ${member} has type ${type}, not a scalar, a vector or an array of them`);
    const [elementAlign, elementSize] = layoutOf[type];
    const align = arrayOf ? Math.max(elementAlign, 16) : elementAlign;
    const stride = arrayOf ? Math.ceil(elementSize / align) * align : 0;
    offset = Math.ceil(offset / align) * align;
    members.push({ name: member, type, offset, count: arrayOf ? Number(count) : 1, stride });
    offset += arrayOf ? stride * Number(count) : elementSize;
    maxAlign = Math.max(maxAlign, align);
  }
  return { members, size: Math.ceil(offset / maxAlign) * maxAlign };
}

// The whole shader: the library files, then clouds.wgsl; with the first line of each part
// so that compiler messages name the file and its line.
function assemble() {
  let source = '', line = 1;
  const starts = [];
  for (const [file, text] of cloudsWgslParts) {
    starts.push({ file, line });
    const t = text.endsWith('\n') ? text : text + '\n';
    source += t;
    line += t.split('\n').length - 1;
  }
  const where = (n) => { const s = [...starts].reverse().find((x) => x.line <= n); return s ? `${s.file}:${n - s.line + 1}` : `line ${n}`; };
  return { source, where };
}

// Adapter and device, or null and the reason.
export async function initWebGPU() {
  if (!navigator.gpu) return { reason: 'navigator.gpu is undefined (this browser has no WebGPU, or it is off)' };
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) return { reason: 'navigator.gpu.requestAdapter() returned null (no WebGPU adapter)' };
  const info = adapter.info || {};
  const name = [info.vendor, info.architecture, info.device, info.description].filter((x) => x).join(' / ') || 'unknown adapter';
  const device = await adapter.requestDevice();
  return { adapter, device, name, fallback: !!adapter.isFallbackAdapter };
}

// The cloud pipeline, its textures (the WebGL2 bake's texels: { base: { size, depth, data } ...})
// and its targets. Throws with the compiler's messages (file:line) when clouds.wgsl or the
// library does not compile.
export async function createClouds(gpu, canvas, texels, present2d = false) {
  const { device } = gpu;
  const errors = [];
  device.addEventListener('uncapturederror', (e) => errors.push(e.error.message));
  const { source, where } = assemble();
  const layout = structLayout(source, 'CrUniforms');
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code: source, label: 'clouds.wgsl' });
  const info = await module.getCompilationInfo();
  const messages = info.messages.map((m) => `${m.type} at ${where(m.lineNum)}:${m.linePos}: ${m.message}`);
  const compileErrors = info.messages.filter((m) => m.type === 'error');
  if (compileErrors.length) {
    await device.popErrorScope();
    throw new Error(`clouds.wgsl does not compile:\n${messages.join('\n')}`);
  }

  const F = GPUShaderStage.FRAGMENT;
  const tex = (binding, viewDimension, sampleType = 'float') => ({ binding, visibility: F, texture: { viewDimension, sampleType } });
  const smp = (binding) => ({ binding, visibility: F, sampler: { type: 'filtering' } });
  const bindGroupLayout = device.createBindGroupLayout({ entries: [
    { binding: 0, visibility: F, buffer: { type: 'uniform' } },
    tex(1, '3d'), smp(2), tex(3, '3d'), smp(4), tex(5, '2d'), smp(6), tex(7, '2d'), smp(8), tex(9, '2d'), smp(10),
    tex(11, '2d', 'unfilterable-float'),
    tex(12, '2d', 'unfilterable-float'), tex(13, '2d', 'unfilterable-float'), tex(14, '2d', 'unfilterable-float'),
  ] });
  // One pipeline per permutation (clouds.wgsl's override constants), made the first time its
  // permutation is drawn (pipelineFor). The composite's (cr_composite) reads group 1 as well:
  // the layer and the background.
  const pipelineLayout = device.createPipelineLayout({ bindGroupLayouts: [bindGroupLayout] });
  const compositeGroupLayout = device.createBindGroupLayout({ entries: [tex(0, '2d', 'unfilterable-float'), tex(1, '2d', 'unfilterable-float')] });
  const compositeLayout = device.createPipelineLayout({ bindGroupLayouts: [bindGroupLayout, compositeGroupLayout] });
  const overrides = [...source.matchAll(/^override\s+(\w+)\s*:/gm)].map((m) => m[1]);

  // The baked noise, texel for texel; samplers as the WebGL2 textures' parameters (linear,
  // repeat, one level).
  const upload = ({ size, depth, data }) => {
    const t = device.createTexture({ size: [size, size, depth], dimension: depth > 1 ? '3d' : '2d', format: 'rgba8unorm',
      usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
    device.queue.writeTexture({ texture: t }, data, { bytesPerRow: size * 4, rowsPerImage: size }, [size, size, depth]);
    return t;
  };
  const base = upload(texels.base), detail = upload(texels.detail), weather = upload(texels.weather);
  // u_weather_wide and u_curl (the detailed shape, off here) and u_shadow_map (shadows off): 1 x 1.
  const none = upload({ size: 1, depth: 1, data: new Uint8Array(4) });
  const noShadow = device.createTexture({ size: [1, 1], format: 'rgba32float', usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
  device.queue.writeTexture({ texture: noShadow }, new Float32Array(4), { bytesPerRow: 16 }, [1, 1]);
  const sampler = device.createSampler({ magFilter: 'linear', minFilter: 'linear', mipmapFilter: 'nearest',
    addressModeU: 'repeat', addressModeV: 'repeat', addressModeW: 'repeat' });
  const uniformBuffer = device.createBuffer({ size: layout.size, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  // The physical sky's tables (setPhysicalTables): 1 x 1 stand-ins until a physical frame.
  const entries = (tables) => [
    { binding: 0, resource: { buffer: uniformBuffer } },
    { binding: 1, resource: base.createView() }, { binding: 2, resource: sampler },
    { binding: 3, resource: detail.createView() }, { binding: 4, resource: sampler },
    { binding: 5, resource: weather.createView() }, { binding: 6, resource: sampler },
    { binding: 7, resource: none.createView() }, { binding: 8, resource: sampler },
    { binding: 9, resource: none.createView() }, { binding: 10, resource: sampler },
    { binding: 11, resource: noShadow.createView() },
    { binding: 12, resource: (tables?.haze || noShadow).createView() }, { binding: 13, resource: (tables?.skyView || noShadow).createView() },
    { binding: 14, resource: (tables?.farShadow || noShadow).createView() },
  ];
  const bindGroup = device.createBindGroup({ layout: bindGroupLayout, entries: entries(null) });

  // A frame's targets, as the WebGL2 path's: cr_fragment's pass 3 (what lies behind the layer,
  // the scene's depth) and pass 0 (the layer, its depth), then cr_composite's display image.
  const { width, height } = canvas;
  const target = (format) => device.createTexture({ size: [width, height], format,
    usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.TEXTURE_BINDING });
  const background = [target('rgba32float'), target('r32float')], layer = [target('rgba32float'), target('r32float')];
  const compositeGroup = device.createBindGroup({ layout: compositeGroupLayout, entries: [
    { binding: 0, resource: layer[0].createView() }, { binding: 1, resource: background[0].createView() }] });
  const color = device.createTexture({ size: [width, height], format: 'rgba8unorm',
    usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC });
  const bytesPerRow = Math.ceil(width * 4 / 256) * 256;
  const readBuffer = device.createBuffer({ size: bytesPerRow * height, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  // The canvas: a WebGPU context (rgba8unorm, premultiplied alpha: what the WebGL2 canvas
  // shows), or with present2d a 2D context showing the read-back image, for browsers whose
  // WebGPU canvas does not present (headless Chromium without --use-vulkan=swiftshader loses
  // its GPU process at getCurrentTexture, taking the WebGL2 context with it).
  let context = null, context2d = null;
  if (present2d) context2d = canvas.getContext('2d');
  else {
    context = canvas.getContext('webgpu');
    context.configure({ device, format: 'rgba8unorm', alphaMode: 'premultiplied', usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_DST });
  }
  const scopeError = await device.popErrorScope();
  if (scopeError) throw new Error(`WebGPU validation: ${scopeError.message}`);
  return { gpu, module, pipelineLayout, compositeLayout, overrides, pipelines: new Map(), bindGroup, uniformBuffer, layout,
    background, layer, compositeGroup, color, readBuffer,
    bytesPerRow, context, context2d, width, height, errors, warnings: messages,
    rebind: (tables) => device.createBindGroup({ layout: bindGroupLayout, entries: entries(tables) }) };
}

// The physical sky's tables for the frames that follow, as the WebGL2 bake read them back:
// { haze, skyView, farShadow }, each { width, height, data: Float32Array of RGBA texels, row 0
// first } (WebGL2's rows run bottom-up in the image, which is texel row 0 in both APIs).
export function setPhysicalTables(c, tables) {
  const { device } = c.gpu;
  const make = ({ width, height, data }) => {
    const t = device.createTexture({ size: [width, height], format: 'rgba32float', usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
    device.queue.writeTexture({ texture: t }, data, { bytesPerRow: width * 16 }, [width, height]);
    return t;
  };
  for (const t of c.physicalTextures || []) t.destroy();
  const made = { haze: make(tables.haze), skyView: make(tables.skyView), farShadow: make(tables.farShadow) };
  c.physicalTextures = Object.values(made);
  c.bindGroup = c.rebind(made);
}

// Packs { u_name: number | number[] } into the uniform struct; a member without a value is 0
// (as an unset GLSL uniform), a value without a member is an error.
export function packUniforms(layout, values) {
  const buffer = new ArrayBuffer(layout.size);
  const dv = new DataView(buffer);
  const byName = new Map(layout.members.map((m) => [m.name, m]));
  for (const name of Object.keys(values)) if (!byName.has(name)) throw new Error(`clouds.wgsl's CrUniforms has no member ${name}`);
  for (const m of layout.members) {
    const v = values[m.name];
    if (v === undefined) continue;
    const xs = Array.isArray(v) || ArrayBuffer.isView(v) ? [...v] : [v];
    const kind = m.type.startsWith('vec') ? m.type.at(-1) : m.type[0];
    const perElement = m.type.startsWith('vec') ? Number(m.type[3]) : 1;
    if (xs.length > perElement * m.count) throw new Error(`clouds.wgsl's CrUniforms member ${m.name} takes ${perElement * m.count} values, not ${xs.length}`);
    xs.forEach((x, k) => {
      const at = m.offset + (m.count > 1 ? m.stride * Math.floor(k / perElement) + 4 * (k % perElement) : 4 * k);
      if (kind === 'f') dv.setFloat32(at, x, true);
      else if (kind === 'i') dv.setInt32(at, x, true);
      else dv.setUint32(at, x, true);
    });
  }
  return buffer;
}

// One frame: draws, copies to the canvas (unless show is false) and reads the image back.
// pixels: RGBA8 with the bottom row first (as WebGL2's readPixels gives it). ms: submit to
// mapped readback. Frames run one after another (they share the read-back buffer).
export function renderClouds(c, values, show = true) {
  const run = (c.last || Promise.resolve()).then(() => renderOnce(c, values, show));
  c.last = run.catch(() => {});
  return run;
}

// The pipeline of the permutation in values (its override constants; an unset one is 0, as an
// unset uniform), and the values that go to the uniform struct: cr_fragment's (the cloud
// passes), or with composite cr_composite's (whose only switch is the dither, composite.frag's).
async function pipelineFor(c, values, composite = false) {
  const constants = {}, uniforms = {};
  for (const [name, v] of Object.entries(values)) (c.overrides.includes(name) ? constants : uniforms)[name] = v;
  for (const name of c.overrides) constants[name] = Math.trunc(constants[name] ?? 0);
  const key = (composite ? 'composite:' + constants.u_dither : c.overrides.map((name) => constants[name]).join(','));
  if (!c.pipelines.has(key)) {
    c.pipelines.set(key, await c.gpu.device.createRenderPipelineAsync({
      layout: composite ? c.compositeLayout : c.pipelineLayout,
      vertex: { module: c.module, entryPoint: 'cr_vertex' },
      fragment: composite
        ? { module: c.module, entryPoint: 'cr_composite', constants: { u_dither: constants.u_dither }, targets: [{ format: 'rgba8unorm' }] }
        : { module: c.module, entryPoint: 'cr_fragment', constants, targets: [{ format: 'rgba32float' }, { format: 'r32float' }] },
      primitive: { topology: 'triangle-list' },
    }));
  }
  return { pipeline: c.pipelines.get(key), uniforms };
}

async function renderOnce(c, values, show) {
  const { device } = c.gpu;
  const { pipeline, uniforms } = await pipelineFor(c, values);
  const background = (await pipelineFor(c, { ...values, u_pass: 3 })).pipeline;
  const composite = (await pipelineFor(c, values, true)).pipeline;
  device.queue.writeBuffer(c.uniformBuffer, 0, packUniforms(c.layout, uniforms));
  const encoder = device.createCommandEncoder();
  // The background (pass 3), the layer (pass 0), then the composite (WebGL2's order).
  for (const [p, targets] of [[background, c.background], [pipeline, c.layer], [composite, [c.color]]]) {
    const pass = encoder.beginRenderPass({ colorAttachments: targets.map((t) =>
      ({ view: t.createView(), loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 0] })) });
    pass.setPipeline(p);
    pass.setBindGroup(0, c.bindGroup);
    if (p === composite) pass.setBindGroup(1, c.compositeGroup);
    pass.draw(3);
    pass.end();
  }
  encoder.copyTextureToBuffer({ texture: c.color }, { buffer: c.readBuffer, bytesPerRow: c.bytesPerRow }, [c.width, c.height]);
  if (show && c.context) encoder.copyTextureToTexture({ texture: c.color }, { texture: c.context.getCurrentTexture() }, [c.width, c.height]);
  const t0 = performance.now();
  device.queue.submit([encoder.finish()]);
  await c.readBuffer.mapAsync(GPUMapMode.READ);
  const ms = performance.now() - t0;
  const mapped = new Uint8Array(c.readBuffer.getMappedRange());
  const pixels = new Uint8Array(c.width * c.height * 4);
  for (let y = 0; y < c.height; ++y)  // WebGPU's row 0 is the top: store it last
    pixels.set(mapped.subarray(y * c.bytesPerRow, y * c.bytesPerRow + c.width * 4), (c.height - 1 - y) * c.width * 4);
  if (show && c.context2d) {
    const rgba = new ImageData(c.width, c.height);
    for (let y = 0; y < c.height; ++y) rgba.data.set(mapped.subarray(y * c.bytesPerRow, y * c.bytesPerRow + c.width * 4), y * c.width * 4);
    for (let i = 3; i < rgba.data.length; i += 4) rgba.data[i] = 255;  // the colour as the WebGL2 canvas shows it on black
    c.context2d.putImageData(rgba, 0, 0);
  }
  c.readBuffer.unmap();
  if (c.errors.length) throw new Error(`WebGPU: ${c.errors.join('; ')}`);
  return { ms, pixels };
}
