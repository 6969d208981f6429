// WGSL parity: the WGSL twins of the GLSL library run as WebGPU compute shaders in Debian's
// Chromium (headless; WebGPU on SwiftShader's Vulkan through Dawn when there is no GPU), each
// case compared with the C++ float functions' outputs dumped by `test_glsl_parity --dump-cases`.
//
//   node web/test/wgsl_parity.mjs --cases CASES.json --program K BODY_K.wgsl [--program K BODY_K.wgsl ...]
//                                 [--markdown FILE] [--chromium PATH]
//
// CASES.json: {"programs": [{"config", "cases"}, ...], "cases": [{"function", "components",
//   "floor", "budget", "config", "program", "index", "inputs": [[a.x,a.y,a.z,a.w,b.x,b.y,b.z,b.w], ...],
//   "expected": [[x,y,z,w], ...]}, ...]} (non-finite expected values are null).
// --program K BODY: the cases whose "program" is K run on BODY (make_parity_shader.mjs
//   --program K), u_case.x = their "index"; every program of the dump needs its body.
// A body (tests/shader_parity/make_parity_shader.mjs --target wgsl) holds the library, its
//   helpers and `fn cm_test_case(c: i32, a: vec4f, b: vec4f) -> vec4f`; this script appends
//   the bindings and the entry point (ENTRY below), so line numbers in messages are the body's.
//   A line `// cm_parity: {"constants": {NAME: value}, "skip": {"index": "why"}}` in a body
//   gives the pipeline-overridable constants to set and the cases WGSL cannot express: those
//   are not run, and are listed (and written under the markdown table).
//
// In the page: the WebGPU adapter and device (adapter info is reported), one shader module per
// program, which must compile without error (getCompilationInfo(): every error and warning is
// printed with its source line), one compute pipeline, then one dispatch per case on the inputs
// as f32. In node, as test_glsl_parity.cpp's evaluate(): per output component j < components,
// error = |got - want| / max(|want|, floor) in double where want is finite; a non-finite got
// where want is finite counts as NaN/Inf. Rows per function (budget: the largest of its cases').
// Exit status: 0 when every row is within its budget and free of NaN/Inf; 1 on any failure
// (compile error, pipeline or device error, out of budget, NaN/Inf); 2 on usage errors.
import { readFile, writeFile, rename } from 'node:fs/promises';
import { basename } from 'node:path';
import { openWebGpuPage } from './webgpu_page.mjs';

const usage = 'usage: node web/test/wgsl_parity.mjs --cases CASES.json --program K BODY.wgsl ... [--markdown FILE] [--chromium PATH]';
const args = process.argv.slice(2);
const opts = { program: new Map() };
const usageError = (why) => {
  console.error(`wgsl_parity.mjs: ${why}\n${usage}`);
  process.exit(2);
};
for (let i = 0; i < args.length; ++i) {
  const name = args[i].replace(/^--/, '');
  if (name === 'program' && args[i] === '--program') {
    if (i + 2 >= args.length || !/^[0-9]+$/.test(args[i + 1])) usageError('--program takes a program number and a file');
    if (opts.program.has(Number(args[i + 1]))) usageError(`--program ${args[i + 1]} given twice`);
    opts.program.set(Number(args[i + 1]), args[i + 2]);
    i += 2;
    continue;
  }
  if (!args[i].startsWith('--') || !['cases', 'markdown', 'chromium'].includes(name)) usageError(`unknown argument ${args[i]}`);
  if (i + 1 >= args.length) usageError(`${args[i]} takes a value`);
  opts[name] = args[++i];
}
if (!opts.cases) usageError('no --cases');
if (!opts.program.size) usageError('give --program K FILE for every program of the dump');
const executablePath = opts.chromium || '/usr/bin/chromium';

// The bindings and entry point appended to every body. u_case = (case index, evaluations, 0, 0).
const ENTRY = `
// ---- appended by web/test/wgsl_parity.mjs ----
@group(0) @binding(0) var<storage, read> inputs: array<vec4f>;
@group(0) @binding(1) var<storage, read_write> outputs: array<vec4f>;
@group(0) @binding(2) var<uniform> u_case: vec4i;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if (i >= u32(u_case.y)) {
        return;
    }
    outputs[i] = cm_test_case(u_case.x, inputs[2u * i], inputs[2u * i + 1u]);
}
`;

// ---- the cases -------------------------------------------------------------------------
const fail = (message) => {
  console.log(`FAIL ${message}`);
  process.exit(1);
};
let dump;
try {
  dump = JSON.parse(await readFile(opts.cases, 'utf8'));
} catch (e) {
  fail(`cannot read the cases ${opts.cases}: ${e.message}`);
}
if (!dump || !Array.isArray(dump.cases) || dump.cases.length === 0) fail(`${opts.cases}: no "cases" array`);
const cases = dump.cases.map((c, k) => {
  const where = `${opts.cases}: case ${k} (${c && c.function})`;
  for (const field of ['function', 'components', 'floor', 'budget', 'index', 'inputs', 'expected'])
    if (c[field] === undefined || c[field] === null) fail(`${where}: no "${field}"`);
  if (!Array.isArray(c.inputs) || !Array.isArray(c.expected) || c.inputs.length !== c.expected.length)
    fail(`${where}: ${c.inputs.length} inputs but ${c.expected.length} expected outputs`);
  if (!(c.components >= 1 && c.components <= 4)) fail(`${where}: components ${c.components} not in 1..4`);
  if (!Number.isInteger(c.index) || c.index < 0) fail(`${where}: index ${c.index} is not a case number`);
  c.inputs.forEach((row, r) => { if (!Array.isArray(row) || row.length !== 8) fail(`${where}: input ${r} is not 8 numbers`); });
  c.expected.forEach((row, r) => { if (!Array.isArray(row) || row.length < c.components) fail(`${where}: expected ${r} has fewer than ${c.components} values`); });
  return { ...c, config: Boolean(c.config) };
});

const programs = [];
const addProgram = async (name, file, mine) => {
  let body;
  try {
    body = await readFile(file, 'utf8');
  } catch (e) {
    fail(`cannot read the ${name} body ${file}: ${e.message}`);
  }
  if (!/\bfn\s+cm_test_case\s*\(/.test(body)) fail(`${file} defines no fn cm_test_case`);
  if (new Set(mine.map((c) => c.index)).size !== mine.length) fail(`${opts.cases}: two ${name} cases with the same "index"`);
  for (const c of mine) c.programName = name;
  // make_parity_shader.mjs's `// cm_parity: {"constants": {NAME: value}, "skip": {index: why}}`:
  // the pipeline-overridable constants of the program, and the cases WGSL cannot express.
  let meta = { constants: {}, skip: {} };
  const line = body.match(/^\/\/ cm_parity: (.*)$/m);
  if (line) {
    try {
      meta = { constants: {}, skip: {}, ...JSON.parse(line[1]) };
    } catch (e) {
      fail(`${file}: the cm_parity line is not JSON: ${e.message}`);
    }
  }
  for (const [k, v] of Object.entries(meta.constants)) if (typeof v !== 'number') fail(`${file}: constant ${k} = ${JSON.stringify(v)} is not a number`);
  for (const [index, why] of Object.entries(meta.skip)) {
    const c = mine.find((x) => String(x.index) === index);
    if (!c) fail(`${file}: skips case ${index}, which ${name} does not have`);
    c.skipped = String(why);
  }
  const source = body + (body.endsWith('\n') ? '' : '\n') + ENTRY;
  programs.push({ name, file, source, constants: meta.constants, bodyLines: body.split('\n').length - (body.endsWith('\n') ? 1 : 0), cases: mine });
};
const numbers = [...new Set(cases.map((c) => c.program))].sort((x, y) => x - y);
if (numbers.some((k) => !Number.isInteger(k))) fail(`${opts.cases}: a case has no "program" number`);
const missing = numbers.filter((k) => !opts.program.has(k));
if (missing.length) fail(`no --program body for program(s) ${missing.join(', ')} of ${opts.cases}`);
for (const [k, file] of [...opts.program].sort((x, y) => x[0] - y[0])) {
  const mine = cases.filter((c) => c.program === k);
  if (!mine.length) fail(`--program ${k}: ${opts.cases} has no case in program ${k}`);
  const config = mine.some((c) => c.config);
  if (config && !mine.every((c) => c.config)) fail(`${opts.cases}: program ${k} mixes configuration and main cases`);
  await addProgram(`program ${k}${config ? ' (config)' : ''}`, file, mine);
}

// Inputs as f32, two vec4f per evaluation (a then b), base64 to the page.
const toBase64 = (floats) => Buffer.from(floats.buffer, floats.byteOffset, floats.byteLength).toString('base64');
const fromBase64 = (text) => {
  const bytes = Buffer.from(text, 'base64');
  return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
};
const pagePrograms = programs.map((p) => ({
  name: p.name,
  source: p.source,
  constants: p.constants,
  cases: p.cases.filter((c) => !c.skipped).map((c) => {
    const data = new Float32Array(c.inputs.length * 8);
    c.inputs.forEach((row, r) => row.forEach((v, j) => { data[r * 8 + j] = v === null ? NaN : v; }));
    return { index: c.index, n: c.inputs.length, data: toBase64(data) };
  }),
}));

// ---- the page --------------------------------------------------------------------------
// Runs in Chromium. Compiles every program first and returns the messages; runs the cases
// only when no program has an error.
async function runInPage(programs) {
  const fromB64 = (text) => {
    const s = atob(text);
    const bytes = new Uint8Array(s.length);
    for (let i = 0; i < s.length; ++i) bytes[i] = s.charCodeAt(i);
    return bytes;
  };
  const toB64 = (bytes) => {
    let s = '';
    for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return btoa(s);
  };
  const out = { adapter: null, programs: [], error: null };
  if (!navigator.gpu) return { ...out, error: 'navigator.gpu is missing (WebGPU disabled or not a secure context)' };
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) return { ...out, error: 'navigator.gpu.requestAdapter() returned null' };
  const info = adapter.info || {};
  out.adapter = {};
  for (const k of ['vendor', 'architecture', 'device', 'description', 'driver', 'backend', 'type', 'isFallbackAdapter'])
    if (info[k] !== undefined && info[k] !== null && info[k] !== '') out.adapter[k] = info[k];
  out.adapter.features = [...adapter.features].sort();
  const device = await adapter.requestDevice();
  let lost = null;
  device.lost.then((l) => { lost = `${l.reason}: ${l.message}`; });
  const uncaptured = [];
  device.addEventListener('uncapturederror', (e) => uncaptured.push(e.error.message));
  const scoped = async (fn) => {
    device.pushErrorScope('validation');
    device.pushErrorScope('internal');
    device.pushErrorScope('out-of-memory');
    let result, thrown = null;
    try {
      result = await fn();
    } catch (e) {
      thrown = e;
    }
    const errors = [];
    for (let k = 0; k < 3; ++k) {
      const e = await device.popErrorScope();
      if (e) errors.push(`${e.constructor.name}: ${e.message}`);
    }
    if (thrown) errors.unshift(String(thrown && thrown.message || thrown));
    return { result, errors };
  };

  const compiled = [];
  for (const p of programs) {
    const t0 = performance.now();
    const { result: module, errors } = await scoped(async () => device.createShaderModule({ label: p.name, code: p.source }));
    const messages = module ? (await module.getCompilationInfo()).messages.map((m) => ({
      type: m.type, message: m.message, lineNum: m.lineNum, linePos: m.linePos, offset: m.offset, length: m.length })) : [];
    // A WGSL error also raises a validation error that repeats the message: keep it only when
    // getCompilationInfo() has no error to show.
    const shown = messages.some((m) => m.type === 'error') ? errors.filter((e) => !/Error while parsing WGSL/.test(e)) : errors;
    const entry = { name: p.name, messages, errors: shown, compileMs: performance.now() - t0, results: [] };
    out.programs.push(entry);
    compiled.push({ p, module, entry });
  }
  if (out.programs.some((e) => e.errors.length || e.messages.some((m) => m.type === 'error'))) return out;

  for (const { p, module, entry } of compiled) {
    const t0 = performance.now();
    let pipeline;
    try {
      pipeline = await device.createComputePipelineAsync({ label: p.name, layout: 'auto', compute: { module, entryPoint: 'main', constants: p.constants } });
    } catch (e) {
      entry.errors.push(`createComputePipelineAsync: ${e.message}`);
      return out;
    }
    entry.pipelineMs = performance.now() - t0;
    const t1 = performance.now();
    const { errors } = await scoped(async () => {
      for (const c of p.cases) {
        const inputs = fromB64(c.data);
        const outBytes = c.n * 16;
        const size = (bytes) => Math.max(16, Math.ceil(bytes / 16) * 16);
        const inBuf = device.createBuffer({ size: size(inputs.byteLength), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
        const outBuf = device.createBuffer({ size: size(outBytes), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
        const uniform = device.createBuffer({ size: 16, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
        const readback = device.createBuffer({ size: size(outBytes), usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
        if (inputs.byteLength) device.queue.writeBuffer(inBuf, 0, inputs);
        device.queue.writeBuffer(uniform, 0, new Int32Array([c.index, c.n, 0, 0]));
        const bind = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries: [
          { binding: 0, resource: { buffer: inBuf } }, { binding: 1, resource: { buffer: outBuf } }, { binding: 2, resource: { buffer: uniform } }] });
        const enc = device.createCommandEncoder();
        const pass = enc.beginComputePass();
        pass.setPipeline(pipeline);
        pass.setBindGroup(0, bind);
        const groups = Math.ceil(c.n / 64);
        if (groups > device.limits.maxComputeWorkgroupsPerDimension) throw new Error(`case ${c.index}: ${c.n} evaluations need ${groups} workgroups, more than the limit ${device.limits.maxComputeWorkgroupsPerDimension}`);
        if (groups > 0) pass.dispatchWorkgroups(groups);
        pass.end();
        enc.copyBufferToBuffer(outBuf, 0, readback, 0, size(outBytes));
        device.queue.submit([enc.finish()]);
        await readback.mapAsync(GPUMapMode.READ);
        const bytes = new Uint8Array(readback.getMappedRange().slice(0, outBytes));
        readback.unmap();
        for (const b of [inBuf, outBuf, uniform, readback]) b.destroy();
        entry.results.push({ index: c.index, out: toB64(bytes) });
        if (lost) throw new Error(`device lost: ${lost}`);
      }
    });
    entry.errors.push(...errors);
    entry.runMs = performance.now() - t1;
  }
  if (lost) out.error = `device lost: ${lost}`;
  if (uncaptured.length) out.error = `uncaptured WebGPU errors: ${uncaptured.join('; ')}`;
  return out;
}

// ---- run -------------------------------------------------------------------------------
const extraFlags = ['--enable-webgpu-developer-features', '--disable-gpu-watchdog'];
let session, result, chromiumVersion = '?', flags = [];
const t0 = Date.now();
try {
  session = await openWebGpuPage({ executablePath, extraFlags, title: 'cloudmath WGSL parity' });
  flags = session.flags;
  chromiumVersion = session.browser.version();
  result = await session.page.evaluate(runInPage, pagePrograms);
} catch (e) {
  console.log(`FAIL running the page: ${e && e.stack || e}`);
  if (session && session.logs.length) console.log(session.logs.join('\n'));
  if (session) await session.close();
  process.exit(1);
}
const logs = session.logs;
await session.close();

const failures = [];
const adapterName = (a) => {
  if (!a) return 'no adapter';
  const main = a.description || [a.vendor, a.architecture, a.device].filter(Boolean).join(' ');
  const details = [a.backend && `${a.backend} backend`, a.driver, a.type, a.vendor && `vendor ${a.vendor}`, a.architecture && `architecture ${a.architecture}`,
    a.isFallbackAdapter ? 'fallback adapter' : null].filter(Boolean);
  return `${main} (${details.join(', ')})`;
};
console.log(`Chromium ${chromiumVersion}, WebGPU adapter: ${adapterName(result.adapter)}`);
if (result.error && !result.programs.length) failures.push(result.error);

// Compilation messages, each with its source line.
const show = (p, m) => {
  const lines = p.source.split('\n');
  const where = m.lineNum > p.bodyLines ? `the entry point appended to ${p.file}, its line ${m.lineNum - p.bodyLines}` : `${p.file}:${m.lineNum}:${m.linePos}`;
  const text = lines[m.lineNum - 1];
  const out = [`${m.type}: ${where}: ${m.message}`];
  if (m.lineNum > 0 && text !== undefined) {
    if (m.lineNum > 1) out.push(`  ${String(m.lineNum - 1).padStart(6)} | ${lines[m.lineNum - 2]}`);
    out.push(`  ${String(m.lineNum).padStart(6)} | ${text}`);
    out.push(`  ${' '.repeat(6)} | ${' '.repeat(Math.max(0, m.linePos - 1))}${'^'.repeat(Math.max(1, Math.min(m.length || 1, text.length - m.linePos + 1)))}`);
  }
  return out.join('\n');
};
for (const entry of result.programs) {
  const p = programs.find((q) => q.name === entry.name);
  const errors = entry.messages.filter((m) => m.type === 'error');
  const others = entry.messages.filter((m) => m.type !== 'error');
  const constants = Object.entries(p.constants).map(([k, v]) => `${k} = ${v}`).join(', ');
  const skips = p.cases.filter((c) => c.skipped).length;
  console.log(`${p.name} (${p.file}, ${p.bodyLines} lines, ${p.cases.length} cases${skips ? `, ${skips} skipped` : ''}` +
    `${constants ? `, constants ${constants}` : ''}): ${errors.length} error(s), ` +
    `${others.length} warning/info message(s); shader module ${entry.compileMs.toFixed(0)} ms` +
    (entry.pipelineMs !== undefined ? `, pipeline ${entry.pipelineMs.toFixed(0)} ms` : '') +
    (entry.runMs !== undefined ? `, ${entry.results.length} dispatches ${entry.runMs.toFixed(0)} ms` : ''));
  for (const m of entry.messages) console.log(show(p, m));
  if (errors.length) failures.push(`the WGSL of the ${p.name} (${p.file}) does not compile: ${errors.length} error(s), listed above`);
  for (const e of entry.errors) failures.push(`${p.name}: ${e}`);
}
if (result.error && result.programs.length) failures.push(result.error);

// ---- compare (test_glsl_parity.cpp's evaluate()) ------------------------------------------
const g = (x, precision = 6) => {  // C's %g
  if (Number.isNaN(x)) return 'nan';
  if (!Number.isFinite(x)) return x < 0 ? '-inf' : 'inf';
  if (x === 0) return Object.is(x, -0) ? '-0' : '0';
  const exponent = Math.floor(Math.log10(Math.abs(Number(x.toPrecision(precision)))));
  if (exponent < -4 || exponent >= precision) {
    const [m, e] = x.toExponential(precision - 1).split('e');
    const mant = m.includes('.') ? m.replace(/0+$/, '').replace(/\.$/, '') : m;
    const ev = Number(e);
    return `${mant}e${ev < 0 ? '-' : '+'}${String(Math.abs(ev)).padStart(2, '0')}`;
  }
  const f = x.toFixed(Math.max(0, precision - 1 - exponent));
  return f.includes('.') ? f.replace(/0+$/, '').replace(/\.$/, '') : f;
};
const rows = [];
const ran = new Map();
for (const entry of result.programs) for (const r of entry.results) ran.set(`${entry.name}:${r.index}`, fromBase64(r.out));
const fmtInputs = (v) => `a=(${v.slice(0, 4).map((x) => g(Math.fround(x))).join(',')}) b=(${v.slice(4, 8).map((x) => g(Math.fround(x))).join(',')})`;
let compared = 0;
const skipped = cases.filter((c) => c.skipped);
for (const c of cases) {
  if (c.skipped) continue;
  const out = ran.get(`${c.programName}:${c.index}`);
  if (!out) continue;  // the program did not run: its failure is listed above
  ++compared;
  let row = rows.find((r) => r.function === c.function);
  if (!row) rows.push(row = { function: c.function, evaluations: 0, worst: 0, worstAt: '', nonfinite: 0, nonfiniteAt: '', budget: c.budget });
  row.budget = Math.max(row.budget, c.budget);
  const floor = Math.fround(c.floor);
  for (let k = 0; k < c.inputs.length; ++k) {
    for (let j = 0; j < c.components; ++j) {
      const got = out[k * 4 + j];
      const raw = c.expected[k][j];
      const want = raw === null ? NaN : Math.fround(raw);
      ++row.evaluations;
      if (!Number.isFinite(want)) continue;
      if (!Number.isFinite(got)) {
        if (row.nonfinite++ === 0) row.nonfiniteAt = `${fmtInputs(c.inputs[k])} [${j}]: WGSL ${g(got)}, C++ ${g(want, 9)}`;
        continue;
      }
      const err = Math.abs(got - want) / Math.max(Math.abs(want), floor);
      if (err > row.worst) {
        row.worst = err;
        row.worstAt = `${fmtInputs(c.inputs[k])} [${j}]: ${g(got, 9)} vs ${g(want, 9)}`;
      }
    }
  }
}

if (rows.length) {
  console.log(`${'function'.padEnd(42)} ${'values'.padStart(8)} ${'max error'.padStart(12)} ${'budget'.padStart(9)} ${'NaN'.padStart(5)}  worst case (WGSL vs C++)`);
  for (const r of rows) {
    const pass = r.worst <= r.budget && r.nonfinite === 0;
    const budget = r.budget === 0 ? '0e+00' : r.budget.toExponential(0).replace(/e([+-])(\d)$/, 'e$10$2');
    console.log(`${r.function.padEnd(42)} ${String(r.evaluations).padStart(8)} ${g(r.worst, 3).padStart(12)} ${budget.padStart(9)} ${String(r.nonfinite).padStart(5)}  ${pass ? '' : 'FAIL '}${r.nonfinite ? 'NaN/Inf at ' + r.nonfiniteAt + (r.worstAt ? '; worst ' : '') : ''}${r.worstAt}`);
    if (r.worst > r.budget) failures.push(`${r.function}: max error ${g(r.worst, 3)} out of budget ${g(r.budget)} at ${r.worstAt}`);
    if (r.nonfinite) failures.push(`${r.function}: ${r.nonfinite} NaN/Inf where the C++ is finite, first at ${r.nonfiniteAt}`);
  }
}
for (const c of skipped) console.log(`skipped: ${c.function} (${c.programName}, case ${c.index}): ${c.skipped}`);
if (compared + skipped.length < cases.length && !failures.length) failures.push(`only ${compared} of ${cases.length} cases ran`);

if (opts.markdown && !failures.length) {  // a failing run leaves the old table
  const a = result.adapter;
  const md = `# WGSL parity: WGSL twins against the C++ float functions\n\n` +
    `Measured by \`web/test/wgsl_parity.mjs\` (ctest \`web.wgsl_parity\`; regenerate with \`bash scripts/wgsl-parity.sh\`) ` +
    `on Chromium ${chromiumVersion}'s WebGPU (headless, flags \`${flags.slice(0, 6).join(' ')}\`), adapter **${adapterName(a)}**. ` +
    `The shipped WGSL twins (include/cloudmath/wgsl, generated from the GLSL by tools/shader_translate) run with the test's own code translated by tests/shader_parity/make_parity_shader.mjs --target wgsl; every case ` +
    `of docs/glsl_parity.md runs as a WebGPU compute shader on the inputs as f32, against the C++ outputs dumped by ` +
    `\`test_glsl_parity --dump-cases\`.\n\n` +
    `Error: |WGSL - C++| / max(|C++|, floor) per output component, over grids that include the hard cases of the C++ tests ` +
    `(|g| -> 1, mu = +-1, sigma_t = 0 to 1e4, Earth-radius cameras at 1.8 m to 400 km, tangent rays, degenerate ranges).\n\n` +
    `| function | values | max error | budget | NaN/Inf |\n|---|---|---|---|---|\n` +
    rows.map((r) => `| \`${r.function}\` | ${r.evaluations} | ${g(r.worst, 2)} | ${g(r.budget)} | ${r.nonfinite} |`).join('\n') + '\n' +
    (skipped.length ? '\nNot run in WGSL (make_parity_shader.mjs skips them):\n\n' +
      skipped.map((c) => `- \`${c.function}\` (${c.inputs.length} inputs): ${c.skipped}`).join('\n') + '\n' : '');
  const tmp = `${opts.markdown}.tmp-${process.pid}`;
  await writeFile(tmp, md);
  await rename(tmp, opts.markdown);  // atomically: a failed write leaves the old table
  console.log(`markdown: ${opts.markdown}`);
}

console.log(`${(Date.now() - t0) / 1000} s in Chromium`);
if (failures.length) {
  if (logs.length) console.log(`page console:\n${logs.join('\n')}`);
  console.log(`FAILED: ${failures.length} failure(s):`);
  for (const f of failures) console.log(`  - ${f}`);
  process.exit(1);
}
console.log(`PASSED: ${rows.length} functions, ${compared} cases${skipped.length ? `, ${skipped.length} skipped` : ''} (${programs.map((p) => basename(p.file)).join(', ')})`);
process.exit(0);
