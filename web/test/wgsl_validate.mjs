// Validates WGSL files with Chromium's WebGPU (Tint), headless on SwiftShader: each file must
// compile without errors (createShaderModule + getCompilationInfo) and, when it has an entry
// point, build a pipeline. Used by docs.snippets for the ```wgsl blocks of the docs.
//
//   node web/test/wgsl_validate.mjs [--chromium PATH] [--prepend FILE]... FILE...
// --prepend: files put before each FILE (the cloudmath WGSL the snippet assumes).
// Exit 0 when every file compiles; 1 otherwise (messages with their source lines).
import { readFileSync } from 'node:fs';
import { openWebGpuPage } from './webgpu_page.mjs';

const args = process.argv.slice(2);
let executablePath = '/usr/bin/chromium';
const prepend = [], files = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--chromium') executablePath = args[++i];
  else if (args[i] === '--prepend') prepend.push(args[++i]);
  else files.push(args[i]);
}
if (!files.length) { console.error('usage: wgsl_validate.mjs [--chromium PATH] [--prepend FILE]... FILE...'); process.exit(2); }
const before = prepend.map((f) => readFileSync(f, 'utf8')).join('\n');

let failed = 0;
const session = await openWebGpuPage({ executablePath, title: 'wgsl' });
try {
  const { page } = session;
  for (const file of files) {
    const code = `${before}\n${readFileSync(file, 'utf8')}`;
    const result = await page.evaluate(async (code) => {
      if (!navigator.gpu) return { error: 'navigator.gpu is missing (no WebGPU in this browser)' };
      const adapter = await navigator.gpu.requestAdapter();
      if (!adapter) return { error: 'no WebGPU adapter' };
      const device = await adapter.requestDevice();
      device.pushErrorScope('validation');
      const module = device.createShaderModule({ code });
      const info = await module.getCompilationInfo();
      const messages = info.messages.map((m) => ({ type: m.type, line: m.lineNum, pos: m.linePos, text: m.message }));
      const entries = [...code.matchAll(/@(compute|fragment|vertex)[^\n]*?\bfn\s+(\w+)/g)].map((m) => [m[1], m[2]]);
      if (!messages.some((m) => m.type === 'error'))
        for (const [stage, entryPoint] of entries) {
          if (stage === 'compute') device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint } });
          else if (stage === 'fragment')
            device.createRenderPipeline({ layout: 'auto', vertex: { module: device.createShaderModule({ code: '@vertex fn v() -> @builtin(position) vec4f { return vec4f(0.0); }' }), entryPoint: 'v' },
              fragment: { module, entryPoint, targets: [{ format: 'rgba8unorm' }] } });
        }
      const scope = await device.popErrorScope();
      return { messages, entries: entries.length, pipelineError: scope ? scope.message : null };
    }, code);
    const lines = code.split('\n');
    const offset = before ? before.split('\n').length : 0;
    const errors = result.error ? [result.error] : [
      ...result.messages.filter((m) => m.type === 'error').map((m) => `${m.line > offset ? file : 'prepended'}:${m.line > offset ? m.line - offset : m.line}:${m.pos}: ${m.text}\n    ${lines[m.line - 1]}`),
      ...(result.pipelineError ? [`${file}: pipeline: ${result.pipelineError}`] : []),
    ];
    if (errors.length) { failed++; console.log(`FAIL ${file}\n  ${errors.join('\n  ')}`); }
    else console.log(`ok   ${file} (${result.messages.length} message(s), ${result.entries} entry point(s) built)`);
  }
} finally {
  await session.close();
}
process.exit(failed ? 1 : 0);
