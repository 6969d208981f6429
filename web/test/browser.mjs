// web.browser: the demo page in Debian's Chromium (headless, SwiftShader's WebGL2 and WebGPU,
// no GPU), driven by Playwright (playwright-core) against the web/ folder served on localhost.
// Checks: every parity case within its budget and free of NaN/Inf; the cloud image is not
// blank (statistics in stated ranges) for two scenes and after switching variant and preset;
// the WebGPU image (clouds.wgsl) passes the same checks and matches the WebGL2 image
// (clouds.frag) within sameImage's thresholds, which a changed uniform and a shifted image fail.
//
//   node web/test/browser.mjs [--screenshot FILE] [--markdown FILE] [--chromium PATH]
// Exit status 0 when every check passes; each failed check is printed.
import { createServer } from 'node:http';
import { readFile, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { dirname, extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { webgpuFlags } from './webgpu_page.mjs';

const web = join(dirname(fileURLToPath(import.meta.url)), '..');
const arg = (name, fallback) => { const i = process.argv.indexOf(name); return i > 0 ? process.argv[i + 1] : fallback; };
const executablePath = arg('--chromium', '/usr/bin/chromium');
const screenshot = arg('--screenshot', null);
const markdown = arg('--markdown', null);
// The desktop renderer's sky for the horizon preset under the physical sky
// (cloudmath_cloud_renderer --preset horizon --sky physical --print-sky): what the page's
// physical sky, baked on the GPU from the same table, must give.
const skyReference = arg('--sky-reference', null);

// A static file server for web/ (what any static server does).
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json', '.css': 'text/css' };
const server = createServer(async (req, res) => {
  const path = normalize(decodeURIComponent(new URL(req.url, 'http://x').pathname)).replace(/^(\.\.[/\\])+/, '');
  const file = join(web, path.endsWith('/') ? path + 'index.html' : path);
  try {
    const body = await readFile(file);
    res.writeHead(200, { 'content-type': types[extname(file)] || 'application/octet-stream' });
    res.end(body);
  } catch {
    res.writeHead(404); res.end('not found');
  }
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const base = `http://127.0.0.1:${server.address().port}`;

const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); };

// docs/browser.md shows the same three.js snippet as web/README.md (which the page runs).
const threeBlock = (text) => [...text.matchAll(/```js\n([\s\S]*?)```/g)].map((m) => m[1]).find((b) => b.includes('THREE.ShaderMaterial'));
const webSnippet = threeBlock(await readFile(join(web, 'README.md'), 'utf8'));
const rootSnippet = threeBlock(await readFile(join(web, '..', 'docs', 'browser.md'), 'utf8'));
check(webSnippet && webSnippet === rootSnippet, 'docs/browser.md shows the three.js snippet of web/README.md unchanged');
const userDataDir = await mkdtemp(join(tmpdir(), 'cloudmath-chromium-'));
// WebGL2 through ANGLE on SwiftShader's Vulkan; WebGPU through Dawn on SwiftShader's Vulkan
// (--enable-unsafe-webgpu --enable-features=Vulkan --use-webgpu-adapter=swiftshader). Both
// APIs run in one page with these flags, but a WebGPU canvas also needs --use-vulkan=swiftshader
// and no --disable-gpu: without them the GPU process dies at the canvas's getCurrentTexture
// ("Could not find SharedImageBackingFactory ... WebgpuSwapChainTexture"), losing the WebGL2
// context too.
const flags = ['--headless', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
  '--use-vulkan=swiftshader', ...webgpuFlags,
  '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'];
let context, threeRevision = '?';
try {
  context = await chromium.launchPersistentContext(userDataDir, { executablePath, headless: true, args: flags, viewport: { width: 1000, height: 1400 } });
  const page = context.pages()[0] || await context.newPage();
  const logs = [];
  page.on('console', (m) => logs.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));

  const load = async (query) => {
    await page.goto(`${base}/demo/${query}`, { waitUntil: 'commit' });  // the demo sets ready itself
    await page.waitForFunction(() => window.cloudmathDemo && (window.cloudmathDemo.ready || window.cloudmathDemo.error), null, { timeout: 600000, polling: 500 });
    return page.evaluate(() => window.cloudmathDemo);
  };
  const imageOk = (img, what) => {
    check(img && img.mean > 0.1 && img.mean < 0.95, `${what}: mean luminance ${img && img.mean.toFixed(3)} in (0.1, 0.95)`);
    check(img && img.std > 0.03, `${what}: luminance standard deviation ${img && img.std.toFixed(3)} > 0.03`);
    check(img && img.cloudFraction > 0.02 && img.cloudFraction < 0.98, `${what}: cloudy pixels ${img && img.cloudFraction.toFixed(3)} in (0.02, 0.98)`);
    check(img && img.levels > 20, `${what}: ${img && img.levels} grey levels > 20`);
  };
  // The WebGPU image against the WebGL2 one (RGBA8, compared in the page). Measured on
  // SwiftShader: identical for cumulus and horizon (PSNR inf), one channel of one pixel one
  // level apart for cumulus with HG and the cheap preset (100.5 dB).
  // Other GPUs may round differently (float ordering and contraction, texture filtering's
  // fixed-point weights), so the bounds leave room: PSNR >= 45 dB is an RMS difference of at
  // most 1.4 levels of 255 (every pixel one level off is 48.1 dB), and no channel off by more
  // than 16 levels. They are tight enough to fail: measured, a 5 % exposure change gives
  // 39.9 dB under the artistic sky (largest difference 3) and 41.9 dB under the physical one,
  // the image shifted by one pixel 41.5 and 43.6 dB (largest 62 and 45).
  const psnrText = (c) => (c.psnrDb === Infinity ? 'inf' : c.psnrDb.toFixed(1));
  const sameImage = (c) => !!c && c.psnrDb >= 45 && c.maxAbsDiff <= 16 && c.alphaMaxAbsDiff <= 16;
  const comparisonText = (c) => c ? `PSNR ${psnrText(c)} dB, mean |diff| ${c.meanAbsDiff.toFixed(3)}, max ${c.maxAbsDiff} ` +
    `(opacity ${c.alphaMaxAbsDiff}), ${(100 * c.differingPixelFraction).toFixed(2)} % of pixels differ` : 'no comparison';
  const waitWebgpu = () => page.waitForFunction(() => !window.cloudmathDemo.webgpu.busy, null, { timeout: 600000, polling: 500 });
  const webgpuOk = (demo, what) => {
    const w = demo.webgpu;
    check(w && w.available && !w.error, `${what}: WebGPU draws clouds.wgsl${w && w.error ? ': ' + w.error : w && !w.available ? ': ' + w.reason : ''}`);
    imageOk(w && w.image, `${what}, WebGPU`);
    check(sameImage(w && w.comparison), `${what}: WebGPU image as WebGL2's (PSNR >= 45 dB, max diff <= 16): ${comparisonText(w && w.comparison)}`);
  };

  const t0 = Date.now();
  let demo = await load('?scene=cumulus');
  check(!demo.error, `page loads without error${demo.error ? ': ' + demo.error : ''}`);
  console.log(`renderer: ${demo.renderer}; loaded in ${((Date.now() - t0) / 1000).toFixed(1)} s (bake ${demo.bakeMs?.toFixed(0)} ms, cloud shader ${demo.compileMs?.toFixed(0)} ms, frame ${demo.frames?.[0]?.toFixed(0)} ms)`);
  check(typeof demo.renderer === 'string' && demo.renderer.length > 0, `WebGL2 renderer reported (${demo.renderer})`);
  check(demo.parity.length >= 31, `${demo.parity.length} parity cases >= 31`);
  for (const r of demo.parity)
    check(r.pass, `parity ${r.fn}: max error ${r.maxError.toExponential(2)} <= ${r.budget}, NaN/Inf ${r.nonFinite}` + (r.pass ? '' : ` (worst at ${JSON.stringify(r.worstAt)})`));
  imageOk(demo.image, 'cumulus, default variant');
  console.log(`WebGPU adapter: ${demo.webgpu.adapter} (${demo.webgpu.presentation}); pipeline ${demo.webgpu.compileMs?.toFixed(0)} ms, ` +
    `warm-up frame ${demo.webgpu.warmUpMs?.toFixed(0)} ms, frame ${demo.webgpu.frameMs?.toFixed(0)} ms`);
  check(typeof demo.webgpu.adapter === 'string' && demo.webgpu.adapter.length > 0, `WebGPU adapter reported (${demo.webgpu.adapter || demo.webgpu.reason})`);
  webgpuOk(demo, 'cumulus, default variant');
  if (screenshot) { await page.screenshot({ path: screenshot, fullPage: true }); console.log(`screenshot: ${screenshot}`); }
  const parity = demo.parity, renderer = demo.renderer, firstFrame = demo.frames[0];
  const gpuFrame = demo.webgpu.frameMs, gpuAdapter = demo.webgpu.adapter, firstComparison = demo.webgpu.comparison;
  const firstBake = demo.sky?.ms, firstFar = demo.farShadow?.ms;
  check(Number.isFinite(firstBake), `the default sky is the physical one, its tables baked (${firstBake?.toFixed(0)} ms)`);

  // The thresholds can fail: a WebGPU frame with one lighting uniform changed (the exposure 5 %
  // higher), and the WebGL2 image against itself moved by one pixel.
  if (demo.webgpu.available) {
    const perturbed = await page.evaluate((e) => window.cloudmathDemoTools.perturbed({ u_exposure: e }), demo.exposure * 1.05);
    check(!sameImage(perturbed.comparison), `WebGPU with the exposure 5 % higher fails the comparison: ${comparisonText(perturbed.comparison)}`);
    const shifted = await page.evaluate(() => window.cloudmathDemoTools.shifted(1));
    check(!sameImage(shifted), `WebGL2 image shifted by one pixel fails the comparison: ${comparisonText(shifted)}`);
  }

  // The controls: another variant and multiple-scattering preset redraw a different image.
  const before = demo.image;
  await page.selectOption('#variant', 'hg');
  await page.selectOption('#ms', 'cheap');
  await waitWebgpu();
  demo = await page.evaluate(() => window.cloudmathDemo);
  check(demo.frames.length === 3, `variant and preset controls redraw (${demo.frames.length} frames)`);
  imageOk(demo.image, 'cumulus, HG, ms_preset cheap');
  check(Math.abs(demo.image.mean - before.mean) > 1e-4, `the variant changes the image (mean ${before.mean.toFixed(4)} -> ${demo.image.mean.toFixed(4)})`);
  check(demo.webgpu.frames.length >= 2, `the controls redraw the WebGPU image too (${demo.webgpu.frames.length} frames)`);
  webgpuOk(demo, 'cumulus, HG, ms_preset cheap');

  demo = await load('?scene=horizon&sun=12&coverage=0.4');
  check(!demo.error, 'horizon scene loads');
  imageOk(demo.image, 'horizon, sun 12 deg, coverage 0.4');
  webgpuOk(demo, 'horizon, sun 12 deg, coverage 0.4');

  // The terrain (the mountains preset): clouds.wgsl's port of the boxes and the march's end at
  // them draws the WebGL2 image; without the boxes the image is another (the comparison fails).
  demo = await load('?scene=mountains');
  check(!demo.error, `mountains scene loads${demo.error ? ': ' + demo.error : ''}`);
  imageOk(demo.image, 'mountains (terrain)');
  webgpuOk(demo, 'mountains (terrain)');
  if (demo.webgpu.available) {
    const flat = await page.evaluate(() => window.cloudmathDemoTools.perturbed({ u_terrain: 0 }));
    check(!sameImage(flat.comparison), `mountains: WebGPU without the terrain is not the WebGL2 image with it: ${comparisonText(flat.comparison)}`);
  }

  // The artistic sky (?sky=artistic), the physical sky being the default.
  demo = await load('?scene=cumulus&sky=artistic');
  check(!demo.error, `cumulus under the artistic sky loads${demo.error ? ': ' + demo.error : ''}`);
  check(demo.exposure === 1, `the artistic sky's exposure is the scene's (${demo.exposure})`);
  imageOk(demo.image, 'cumulus, artistic sky');
  webgpuOk(demo, 'cumulus, artistic sky');

  // The physical sky: the tables baked on the GPU by cloudmath's GLSL twins from
  // web/demo/sky_table.bin (WebGPU reads the same texels), the sky's values read back, against the
  // desktop renderer's CPU-made values for the same preset. Float rounding differs (the GPU's
  // march, JavaScript's double reduction): 1e-3 of each value, or of its vector's largest part.
  demo = await load('?scene=horizon&sky=physical');
  check(!demo.error, `horizon under the physical sky loads${demo.error ? ': ' + demo.error : ''}`);
  imageOk(demo.image, 'horizon, physical sky');
  webgpuOk(demo, 'horizon, physical sky');
  // The far shadow toward the low sun, drawn by clouds.frag's pass 4 over the page's noise:
  // every node in [0, 1], some wholly shaded (paths that meet the ground), some partly.
  const far = demo.farShadow?.table || [];
  check(far.length === 16 * 48 && far.every((x) => Number.isFinite(x) && x >= 0 && x <= 1) && far.some((x) => x === 0) &&
    far.filter((x) => x > 0.05 && x < 0.95).length > 20,
    `horizon, physical sky: the far shadow's 768 nodes in [0, 1], ${far.filter((x) => x === 0).length} in the planet's shadow, ` +
    `${far.filter((x) => x > 0.05 && x < 0.95).length} partly shaded (> 20), drawn in ${demo.farShadow?.ms?.toFixed(0)} ms`);
  if (skyReference) {
    const want = JSON.parse(await readFile(skyReference, 'utf8'));
    const got = demo.sky || {};
    const pairs = [['sun_radiance', got.sunRadiance], ['sky_zenith', got.skyZenith], ['sky_horizon', got.skyHorizon], ['ground', got.ground],
      ['ambient_top', got.ambientTop], ['ambient_bottom', got.ambientBottom], ...want.sun_by_height.map((_, i) => [`sun_by_height[${i}]`, got.sunByHeight?.[i]])];
    let worst = 0, worstAt = '';
    for (const [key, g] of pairs) {
      const w = key.startsWith('sun_by_height') ? want.sun_by_height[Number(key.slice(14, -1))] : want[key];
      const scale = Math.max(...w.map(Math.abs));
      w.forEach((x, k) => {
        const e = g && Number.isFinite(g[k]) ? Math.abs(g[k] - x) / Math.max(Math.abs(x), 1e-3 * scale, 1e-30) : Infinity;
        if (e > worst) { worst = e; worstAt = `${key}[${k}]: ${g && g[k]} vs ${x}`; }
      });
    }
    const evError = Math.abs((got.ev100 ?? NaN) - want.ev100);
    check(worst <= 1e-3, `physical sky's values against the desktop renderer's: largest relative difference ${worst.toExponential(2)} <= 1e-3 (${worstAt})`);
    check(evError <= 1e-3, `physical sky's EV100 ${got.ev100?.toFixed(4)} against the desktop's ${want.ev100.toFixed(4)}`);
    console.log(`physical sky baked in ${got.ms?.toFixed(0)} ms (2 sky-view tables 64 x 64, the aerial-perspective table 256 x 32, 19 values)`);
  }

  // The three.js snippet of web/README.md, run as written with three.js from npm.
  await page.goto(`${base}/demo/three.html`, { waitUntil: 'commit' });
  await page.waitForFunction(() => window.threeDemo && (window.threeDemo.ready || window.threeDemo.error), null, { timeout: 120000, polling: 250 });
  const three = await page.evaluate(() => window.threeDemo);
  threeRevision = three.threeRevision;
  check(!three.error, `three.js page runs the README snippet${three.error ? ': ' + three.error : ''}`);
  check(three.glsl3 && three.shaderErrors && three.shaderErrors.length === 0,
    `three.js r${three.threeRevision} compiles the snippet's GLSL3 ShaderMaterial (${JSON.stringify(three.shaderErrors)})`);
  check(three.litFraction > 0.1 && three.levels > 30, `three.js sphere is drawn: ${three.litFraction?.toFixed(3)} of the pixels lit, ${three.levels} grey levels`);

  if (markdown) {
    const rows = parity.map((r) => `| \`${r.fn}\` | ${r.values} | ${r.maxError === 0 ? '0' : r.maxError.toExponential(1)} | ${r.budget.toExponential(0)} | ${r.nonFinite} |`);
    await writeFile(markdown, `# GLSL parity in the browser: WebGL2 against JavaScript\n\n` +
      `Measured by \`bash scripts/web-demo.sh\` (web/test/browser.mjs: Playwright driving Debian's Chromium, ` +
      `headless, flags \`${flags.join(' ')}\`) on **${renderer}**, ${new Date().toISOString().slice(0, 16).replace('T', ' ')} UTC. ` +
      `Each cm_ function runs in a GLSL ES 3.00 fragment shader (highp) into an RGBA32F target; the reference is an ` +
      `independent JavaScript double-precision formula on the same float-rounded inputs (web/demo/parity.js). ` +
      `Error: |GPU - JS| / max(|JS|, 1e-30).\n\n| function | values | max error | budget | NaN/Inf |\n|---|---|---|---|---|\n` +
      rows.join('\n') + `\n\nCloud frame (cumulus preset, default variant, physical sky, 320 x 180, 64 view steps, base volume 64^3): ` +
      `${firstFrame.toFixed(0)} ms on this software renderer; the physical sky's tables (two 64 x 64 sky views, the 256 x 32 ` +
      `aerial-perspective table and 19 sun and sky values, web/demo/physical_sky.js) baked in ${firstBake?.toFixed(0)} ms, once per scene and sun, ` +
      `and its far shadow (16 x 48 nodes, clouds.frag's pass 4) drawn in ${firstFar?.toFixed(0)} ms. The same frame from clouds.wgsl (the WGSL port, with ` +
      `cloudmath's generated WGSL library) on WebGPU (${gpuAdapter}): ${gpuFrame?.toFixed(0)} ms; against the WebGL2 image ` +
      `${comparisonText(firstComparison)}. The three.js snippet of web/README.md runs as written ` +
      `(three.js r${threeRevision}, GLSL3 ShaderMaterial, no shader errors).\n\n![the demo page](images/web_demo.png)\n`);
    console.log(`markdown: ${markdown}`);
  }
  if (failures.length) console.log(logs.join('\n'));
} catch (e) {
  failures.push(String(e && e.stack || e));
  console.log(`FAIL ${e && e.message || e}`);
} finally {
  if (context) await context.close();
  server.close();
  await rm(userDataDir, { recursive: true, force: true });
}
console.log(failures.length ? `${failures.length} check(s) failed` : 'all checks passed');
process.exit(failures.length ? 1 : 0);
