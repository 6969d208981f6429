// Statistics of an RGBA8 image and the comparison of two, for the WebGL2 and WebGPU frames.

// Mean and standard deviation of the luminance (0..1), the share of cloudy pixels (opacity
// above 0.5) and the number of distinct grey levels.
export function imageStats(px) {
  let sum = 0, sum2 = 0, cloudy = 0;
  const levels = new Set();
  const n = px.length / 4;
  for (let i = 0; i < px.length; i += 4) {
    const y = (0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2]) / 255;
    sum += y; sum2 += y * y;
    levels.add(Math.round(y * 255));
    if (px[i + 3] > 127) cloudy++;
  }
  const mean = sum / n;
  return { mean, std: Math.sqrt(Math.max(sum2 / n - mean * mean, 0)), cloudFraction: cloudy / n, levels: levels.size, pixels: n };
}

// Two RGBA8 images of the same size: PSNR over the RGB channels (peak 255; Infinity when
// equal), the mean and largest absolute RGB difference in 8-bit levels, the largest alpha
// (opacity) difference, and the share of pixels with any channel different.
export function compareImages(a, b) {
  if (a.length !== b.length) throw new Error(`compareImages: ${a.length} and ${b.length} bytes`);
  let sq = 0, abs = 0, max = 0, alphaMax = 0, differing = 0;
  for (let i = 0; i < a.length; i += 4) {
    let any = false;
    for (let k = 0; k < 4; ++k) {
      const d = Math.abs(a[i + k] - b[i + k]);
      if (d) any = true;
      if (k === 3) { alphaMax = Math.max(alphaMax, d); continue; }
      sq += d * d; abs += d; max = Math.max(max, d);
    }
    if (any) differing++;
  }
  const n = (a.length / 4) * 3;
  const mse = sq / n;
  return { psnrDb: mse > 0 ? 10 * Math.log10(255 * 255 / mse) : Infinity, meanAbsDiff: abs / n, maxAbsDiff: max,
    alphaMaxAbsDiff: alphaMax, differingPixelFraction: differing / (a.length / 4) };
}

// The image moved right by dx pixels (the left column repeated): a deliberately wrong image.
export function shiftImage(px, width, dx) {
  const out = new Uint8Array(px.length);
  const height = px.length / 4 / width;
  for (let y = 0; y < height; ++y)
    for (let x = 0; x < width; ++x) {
      const from = (y * width + Math.min(Math.max(x - dx, 0), width - 1)) * 4;
      out.set(px.subarray(from, from + 4), (y * width + x) * 4);
    }
  return out;
}
