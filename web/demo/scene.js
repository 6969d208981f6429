// The example renderer's scenes, lighting variants and frame constants (examples/cloud_renderer/
// scene.hpp and scene.cpp), in JavaScript: the same numbers as the desktop renderer's uniforms
// under the artistic sky and the classic density field (the physical sky's: physical_sky.js).
// Frame: camera at the origin, +y up, -z north, +x east, metres.

import { mieParams } from './parity.js';

const degrees = Math.PI / 180;

export const scenePresets = [
  // name, description, altitude, yaw, pitch, sun elevation, sun azimuth, coverage, cloud type
  ['ground', 'on the ground looking up, sun high', 2, 0, 28, 50, 140, 0.3, 0.65],
  ['horizon', 'on the ground at the horizon, low sun ahead', 2, 250, 12, 6, 265, 0.3, 0.7],
  ['sun_behind', 'looking away from a low sun', 2, 70, 15, 15, 250, 0.32, 0.7],
  ['inside', 'inside the layer, looking across it', 2700, 20, 0, 30, 160, 0.28, 0.6],
  ['above', 'above the clouds looking down, low sun', 7000, 200, -18, 10, 230, 0.33, 0.75],
  ['stratus', 'overcast stratus from the ground', 2, 40, 22, 35, 100, 0.6, 0.0],
  ['cumulus', 'scattered cumulus, sun high', 2, 300, 18, 60, 180, 0.27, 1.0],
  ['mountains', "above a cloud sea, the terrain's boxes rising through it", 4700, 0, -6, 20, 120, 0.5, 0.5],
].map(([name, description, cameraAltitude, yaw, pitch, sunElevation, sunAzimuth, coverage, cloudType]) => ({
  name, description, cameraAltitude, yaw, pitch, fovY: 60, sunElevation, sunAzimuth, coverage, cloudType,
  terrain: name === 'mountains',  // scene.hpp's scene::terrain: the boxes below stand in the view
  planetRadius: 6371000, layerBottom: 1500, layerTop: 4000, extinction: 0.04, albedo: 0.99,
  maxDistance: 35000, baseTile: 12000, detailTile: 1500, weatherTile: 60000, wind: [1200, -800], exposure: 1,
}));

// The example's terrain (scene.hpp's terrain_boxes, read with scene::terrain): each box's centre
// (x, z) relative to the camera, its half width and its top's altitude (m). ctest
// cloud_renderer.variant_table checks these numbers against scene.hpp's.
export const terrainBoxes = [[-3500, -9000, 1200, 3300], [1500, -12500, 1600, 4500], [5200, -7500, 900, 2600], [-800, -16000, 1400, 5400]];

// Lighting variants (scene.hpp's `variant`, and its scene's sun, haze, shadows and dither switches; the
// names of scripts/render-docs.sh). The default is the diffusion model with 6-step marches
// toward the sun and away from it, opaque view steps refined into sub-steps, and the sky light
// occluded inside the clouds, and toward a low sun the far field beyond the capped march in
// full-density steps (reach 0, scene.hpp's reach_mode::far); `octaves` is the production octave
// choice it replaced. The demo draws one full frame per change: no Beer shadow map (shadows:
// 0, so no ground shadows), no temporal scheme.
const standard = { lighting: 1, phase: 1, octaves: 3, powder: 0, light: 1, behind: 1, lightSteps: 6, refine: 16, integration: 0, viewSteps: 64, schedule: 0, ambient: 1, reach: 0, shadows: 0, sun: 1, haze: 1, dither: 1 };
const octaves = { ...standard, lighting: 0, powder: 1, light: 0, behind: 0, refine: 1, ambient: 0 };
export const variants = {
  default: { ...standard },
  octaves: { ...octaves },
  hg: { ...standard, phase: 0 },
  mie: { ...standard, phase: 3 },
  octaves1: { ...octaves, octaves: 1, powder: 0 },
  powder_off: { ...octaves, powder: 0 },
  march: { ...standard, behind: 1, lightSteps: 32 },
  naive16: { ...standard, integration: 1, viewSteps: 16, refine: 1 },
  analytic16: { ...standard, viewSteps: 16 },
};

// The phase model's mean cosine, the diffusion model's g (scene.cpp's phase_mean_cosine):
// HG g; dual lobe (1 - w) g0 + w g1; the Mie fit (1 - w) g_hg + w Draine's
// g (1 + alpha (3 + 2 g^2) / 5) / (1 + alpha (1 + 2 g^2) / 3).
export function phaseMeanCosine(f, phase) {
  if (phase === 0) return f.phaseG;
  if (phase === 1) return (1 - f.phaseW) * f.phaseG + f.phaseW * f.phaseGBack;
  if (phase === 2) return 3 * f.phaseG * (4 + f.phaseG ** 2) / (5 * (2 + f.phaseG ** 2));
  const [gh, gd, a, w] = mieParams(f.dropletDiameter);
  return (1 - w) * gh + w * gd * (1 + a * (3 + 2 * gd * gd) / 5) / (1 + a * (1 + 2 * gd * gd) / 3);
}

// Multiple-scattering presets (include/cloudmath/multiple_scattering.hpp, ms_preset): a, b, c
// and the octave count, which replaces the variant's.
export const msPresets = {
  production: [0.5, 0.5, 0.5, 3],
  fitted: [0.197, 0.409, 0.8, 5],
  cheap: [0.0639, 0.582, 0.676, 2],
  thin: [0.173, 0.435, 0.805, 3],
  thick: [0.299, 0.625, 0.529, 6],
};

const f32 = Math.fround;
function direction(heading, elevation) {
  const h = heading * degrees, e = elevation * degrees;
  return [Math.cos(e) * Math.sin(h), Math.sin(e), -Math.cos(e) * Math.cos(h)];
}
const normalize = (v) => { const l = Math.hypot(...v); return v.map((x) => x / l); };
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const mix = (a, b, t) => a.map((x, i) => x + (b[i] - x) * t);
const scale = (a, k) => a.map((x) => x * k);
const clamp = (x, lo, hi) => Math.min(Math.max(x, lo), hi);

// make_frame_constants of scene.cpp.
export function frameConstants(s) {
  const pitch = clamp(s.pitch, -89, 89);
  const f = {};
  f.forward = direction(s.yaw, pitch);
  f.right = normalize([Math.cos(s.yaw * degrees), 0, Math.sin(s.yaw * degrees)]);
  f.up = cross(f.right, f.forward);
  f.tanHalfFov = Math.tan(0.5 * s.fovY * degrees);
  f.sunDir = direction(s.sunAzimuth, s.sunElevation);
  const e = Math.max(s.sunElevation, -2);
  const airMass = 1 / (Math.sin(Math.max(e, 0) * degrees) + 0.50572 * Math.pow(e + 6.07995 + 2, -1.6364));
  const sun = [0.06, 0.13, 0.30].map((t) => Math.exp(-t * airMass));
  const day = clamp((s.sunElevation + 4) / 14, 0.05, 1);
  f.sunRadiance = scale(sun, 12);
  f.skyZenith = scale([0.16, 0.30, 0.62], day);
  f.skyHorizon = scale(mix([0.62, 0.72, 0.86], [0.85, 0.62, 0.45], 1 - day), day);
  f.ground = scale([0.12, 0.11, 0.09], day);
  f.ambientTop = scale(mix(f.skyZenith, f.skyHorizon, 0.4), 1.1);
  f.ambientBottom = f.ground.map((g, i) => g * 1.5 + 0.25 * f.ambientTop[i]);
  f.sunAngularRadius = 4.6524e-3;  // the real Sun (sun.hpp's sun_angular_radius)
  Object.assign(f, { phaseG: 0.8, phaseGBack: -0.25, phaseW: 0.2, dropletDiameter: 15, msA: 0.5, msB: 0.5, msC: 0.5,
    coneStep: 120, coneSpread: 0.4, coneFarDistance: 1800, coneFarLength: 900, lightMarchMax: 6000, minTransmittance: 0.01,
    marchNearDistance: 1000 });
  for (const k of Object.keys(f)) f[k] = Array.isArray(f[k]) ? f[k].map(f32) : f32(f[k]);
  return f;
}
