// A blank page with WebGPU in Debian's headless Chromium, for the WGSL tests
// (wgsl_parity.mjs, wgsl_validate.mjs). navigator.gpu exists only in a secure context:
// http://127.0.0.1 is one, about:blank is not, so the page is served from a local server.
// WebGPU runs through Dawn on SwiftShader's Vulkan (no GPU needed).
import { createServer } from 'node:http';
import { chromium } from 'playwright-core';

// The WebGPU flags; browser.mjs adds them to its WebGL2 ones.
export const webgpuFlags = ['--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-webgpu-adapter=swiftshader'];

// Opens the page. Returns { browser, page, logs, close }; logs collects the page's console
// and errors. extraFlags are added after the WebGPU and housekeeping flags.
export async function openWebGpuPage({ executablePath = '/usr/bin/chromium', extraFlags = [], title = 'cloudmath WGSL' } = {}) {
  const server = createServer((req, res) => {
    res.writeHead(200, { 'content-type': 'text/html' });
    res.end(`<!doctype html><meta charset="utf-8"><title>${title}</title>`);
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  const flags = ['--headless', '--no-sandbox', ...webgpuFlags, ...extraFlags,
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'];
  let browser;
  const close = async () => {
    if (browser) await browser.close();
    server.close();
  };
  try {
    browser = await chromium.launch({ executablePath, headless: true, args: flags });
    const page = await browser.newPage();
    const logs = [];
    page.on('console', (m) => logs.push(`${m.type()}: ${m.text()}`));
    page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));
    await page.goto(`http://127.0.0.1:${server.address().port}/`);
    return { browser, page, logs, flags, close };
  } catch (e) {
    await close();
    throw e;
  }
}
