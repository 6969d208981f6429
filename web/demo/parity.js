// GLSL-against-JavaScript parity cases: each cm_ function evaluated on the GPU (float, WebGL2)
// and by an independent JavaScript double-precision formula (REFERENCES.md's closed forms),
// over grids that include the hard cases (|g| -> 1, mu = +-1, tau = 0, sigma_t = 0).
// Error: |GPU - JS| / max(|JS|, floor); budget as in docs/glsl_parity.md (1e-5, 1e-4 for the
// Mie fit). Inputs are rounded to float first, so both sides see the same numbers.

const PI = Math.PI;
const f = Math.fround;
const gMax = f(0.9999);  // the library's |g| clamp, as the float the shader holds
const clampG = (g) => Math.min(Math.max(g, -gMax), gMax);
const clampMu = (mu) => Math.min(Math.max(mu, -1), 1);

export const hg = (mu, g) => { g = clampG(g); mu = clampMu(mu); return (1 - g * g) / (4 * PI * Math.pow(1 + g * g - 2 * g * mu, 1.5)); };
const cs = (mu, g) => { g = clampG(g); mu = clampMu(mu); return 3 * (1 - g * g) * (1 + mu * mu) / (8 * PI * (2 + g * g) * Math.pow(1 + g * g - 2 * g * mu, 1.5)); };
const draine = (mu, g, a) => { g = clampG(g); mu = clampMu(mu); return (1 - g * g) * (1 + a * mu * mu) / (4 * PI * (1 + a * (1 + 2 * g * g) / 3) * Math.pow(1 + g * g - 2 * g * mu, 1.5)); };
const schlick = (mu, k) => { k = clampG(k); mu = clampMu(mu); return (1 - k * k) / (4 * PI * (1 - k * mu) ** 2); };
const sat = (x) => Math.min(Math.max(x, 0), 1);
// Jendersie & d'Eon 2023, 5 <= d <= 50 um.
export const mieParams = (d) => [Math.exp(-0.0990567 / (d - 1.67154)), Math.exp(-2.20679 / (d + 3.91029) - 0.428934),
  Math.exp(3.62489 - 8.29288 / (d + 5.52825)), Math.exp(-0.599085 / (d - 0.641583) - 0.665888)];
const octaves = (tau, mu, g, a, b, c, n) => { let s = 0; for (let i = 0; i < n; ++i) s += b ** i * hg(mu, c ** i * g) * Math.exp(-(a ** i) * tau); return s; };
const presets = { PRODUCTION: [0.5, 0.5, 0.5, 3], FITTED: [0.197, 0.409, 0.8, 5], CHEAP: [0.0639, 0.582, 0.676, 2], THIN: [0.173, 0.435, 0.805, 3], THICK: [0.299, 0.625, 0.529, 6] };

function grid(...axes) {
  let out = [[]];
  for (const axis of axes) out = out.flatMap((p) => axis.map((v) => [...p, v]));
  return out.map((p) => [...p, 0, 0, 0, 0].slice(0, 4).map(f));
}
const MU = [-1, -0.999, -0.5, -0.1, 0, 0.3, 0.7, 0.95, 0.999, 1];
const G = [-0.9999, -0.5, 0, 0.3, 0.8, 0.95, 0.9999];
const TAU = [0, 1e-6, 0.01, 0.5, 1, 3, 10, 30];

export const cases = [
  { fn: 'cm_saturate', module: 'core', expr: 'cm_saturate(a.x)', inputs: grid([-2, -0, 0, 0.25, 1, 3]), ref: (a) => sat(a[0]) },
  { fn: 'cm_remap', module: 'core', expr: 'cm_remap(a.x, a.y, a.z, 10.0, 20.0)', inputs: grid([-1, 0.25, 0.5, 2], [0, 0.1], [1, 0.9]), ref: (a) => 10 + (a[0] - a[1]) / (a[2] - a[1]) * 10 },
  { fn: 'cm_phase_isotropic', module: 'phase', expr: 'cm_phase_isotropic()', inputs: grid([0]), ref: () => 1 / (4 * PI) },
  { fn: 'cm_phase_rayleigh', module: 'phase', expr: 'cm_phase_rayleigh(a.x)', inputs: grid(MU), ref: (a) => 3 / (16 * PI) * (1 + a[0] * a[0]) },
  { fn: 'cm_phase_hg', module: 'phase', expr: 'cm_phase_hg(a.x, a.y)', inputs: grid(MU, G), ref: (a) => hg(a[0], a[1]) },
  { fn: 'cm_phase_hg_dual', module: 'phase', expr: 'cm_phase_hg_dual(a.x, a.y, -0.5, a.z)', inputs: grid(MU, [0.8, 0.95], [0, 0.2, 0.5, 1]), ref: (a) => (1 - a[2]) * hg(a[0], a[1]) + a[2] * hg(a[0], f(-0.5)) },
  { fn: 'cm_phase_cornette_shanks', module: 'phase', expr: 'cm_phase_cornette_shanks(a.x, a.y)', inputs: grid(MU, G), ref: (a) => cs(a[0], a[1]) },
  { fn: 'cm_phase_draine', module: 'phase', expr: 'cm_phase_draine(a.x, a.y, a.z)', inputs: grid(MU, [0, 0.5, 0.8, 0.95], [0, 1, 22]), ref: (a) => draine(a[0], a[1], a[2]) },
  { fn: 'cm_phase_schlick', module: 'phase', expr: 'cm_phase_schlick(a.x, a.y)', inputs: grid(MU, G), ref: (a) => schlick(a[0], a[1]) },
  { fn: 'cm_phase_mie_approx', module: 'phase', expr: 'cm_phase_mie_approx(a.x, a.y)', budget: 1e-4,
    inputs: grid(MU, [5, 10, 15, 25, 50]), ref: (a) => { const [gh, gd, al, w] = mieParams(a[1]); return (1 - w) * hg(a[0], gh) + w * draine(a[0], gd, al); } },
  { fn: 'cm_beer_lambert', module: 'transmittance', expr: 'cm_beer_lambert(a.x)', inputs: grid(TAU), ref: (a) => Math.exp(-a[0]) },
  { fn: 'cm_powder', module: 'transmittance', expr: 'cm_powder(a.x, a.y)', inputs: grid(TAU.slice(1), [1, 2]), ref: (a) => -Math.expm1(-a[1] * a[0]) },
  { fn: 'cm_beer_powder', module: 'transmittance', expr: 'cm_beer_powder(a.x)', inputs: grid(TAU.slice(1)), ref: (a) => 2 * Math.exp(-a[0]) * -Math.expm1(-2 * a[0]) },
  { fn: 'cm_nubis_attenuation', module: 'transmittance', expr: 'cm_nubis_attenuation(a.x)', inputs: grid(TAU), ref: (a) => Math.max(Math.exp(-a[0]), 0.7 * Math.exp(-0.25 * a[0])) },
  { fn: 'cm_integrate_scattering', module: 'integration', expr: 'cm_integrate_scattering(a.x, a.y, a.z)', inputs: grid([1, 2.5], [0, 1e-6, 0.01, 0.1, 3], [1, 25, 100]),
    ref: (a) => a[1] === 0 ? a[0] * a[2] : a[0] * -Math.expm1(-a[1] * a[2]) / a[1] },
  { fn: 'cm_multiple_scattering', module: 'multiple_scattering', expr: 'cm_multiple_scattering(a.x, a.y, 0.8, 0.5, 0.5, 0.5, int(a.z))', inputs: grid([0, 0.5, 5, 30], MU, [1, 3, 8]),
    ref: (a) => octaves(a[0], a[1], f(0.8), 0.5, 0.5, 0.5, a[2]) },
  ...Object.entries(presets).map(([name, [pa, pb, pc, n]]) => ({
    fn: `cm_multiple_scattering (CM_MS_PRESET_${name})`, module: 'multiple_scattering', expr: `cm_multiple_scattering(a.x, a.y, 0.85, CM_MS_PRESET_${name})`,
    inputs: grid([0, 0.5, 5, 30], MU), ref: (a) => octaves(a[0], a[1], f(0.85), f(pa), f(pb), f(pc), n) })),
  { fn: 'cm_smoothstep_safe', module: 'core', expr: 'cm_smoothstep_safe(a.x, a.y, a.z)', inputs: grid([0, 1], [1, 0, 2], [-1, 0.2, 0.5, 0.9, 3]),
    ref: (a) => { const t = sat((a[2] - a[0]) / (a[1] - a[0])); return t * t * (3 - 2 * t); } },
  { fn: 'cm_remap_clamped', module: 'core', expr: 'cm_remap_clamped(a.x, 0.0, 2.0, 10.0, 20.0)', inputs: grid([-1, 0, 0.3, 1, 2, 5]), ref: (a) => 10 + sat(a[0] / 2) * 10 },
  { fn: 'cm_one_minus_exp_neg', module: 'core', expr: 'cm_one_minus_exp_neg(a.x)', inputs: grid([0, 1e-7, 1e-3, 0.2, 0.3, 1, 10, 50]), ref: (a) => -Math.expm1(-a[0]) },
  { fn: 'cm_one_minus_exp_neg_over_x', module: 'core', expr: 'cm_one_minus_exp_neg_over_x(a.x)', inputs: grid([0, 1e-7, 1e-3, 0.2, 0.3, 1, 10, 50]),
    ref: (a) => a[0] === 0 ? 1 : -Math.expm1(-a[0]) / a[0] },
  { fn: 'cm_schlick_k_from_hg_g', module: 'phase', expr: 'cm_schlick_k_from_hg_g(a.x)', inputs: grid(G), ref: (a) => 1.55 * a[0] - 0.55 * a[0] ** 3 },
  { fn: 'cm_phase_hg_schlick', module: 'phase', expr: 'cm_phase_hg_schlick(a.x, a.y)', inputs: grid(MU, G.slice(1, -1)),
    ref: (a) => schlick(a[0], f(1.55 * a[1] - 0.55 * a[1] ** 3)) },
  // HG's inverse CDF (Pharr et al., pbrt): mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g),
  // mu = 2u - 1 at g = 0; judged by the absolute error in mu (floor 1).
  { fn: 'cm_sample_phase_hg', module: 'phase', expr: 'cm_sample_phase_hg(a.x, a.y)', floor: 1,
    inputs: grid([-0.9, -0.5, 0, 0.3, 0.8, 0.95], [0, 0.1, 0.5, 0.9, 0.999, 1]),
    ref: (a) => { const [g, u] = a; if (g === 0) return 2 * u - 1; const q = (1 - g * g) / (1 - g + 2 * g * u); return Math.min(Math.max((1 + g * g - q * q) / (2 * g), -1), 1); } },
  // Far root of a ray from altitude h (cosine of zenith mu) to the sphere at altitude H over
  // R = 6371 km: t = -r mu + sqrt((Rs - r)(Rs + r) + r^2 mu^2), r = R + h, Rs = R + H.
  { fn: 'cm_ray_sphere_intersect_altitude', module: 'geometry', expr: 'cm_ray_sphere_intersect_altitude(a.x, a.y, 6371000.0, a.z).y',
    inputs: grid([2, 1000], [-0.5, -0.05, 0, 0.1, 0.5, 1], [1500, 4000]),
    ref: (a) => { const r = 6371000 + a[0], Rs = 6371000 + a[2], mu = a[1]; return -r * mu + Math.sqrt((Rs - r) * (Rs + r) + r * r * mu * mu); } },
  { fn: 'cm_altitude_along_ray', module: 'geometry', expr: 'cm_altitude_along_ray(a.x, a.y, 6371000.0, a.z)',
    inputs: grid([2, 1500], [-0.1, 0, 0.2, 1], [100, 5000, 50000]),
    ref: (a) => { const R = 6371000, h = a[0], r = R + h, t = a[2], s = t * t + 2 * r * t * a[1]; return (h * (2 * R + h) + s) / (Math.sqrt(r * r + s) + R); } },
  { fn: 'cm_height_fraction', module: 'geometry', expr: 'cm_height_fraction(a.x, 1500.0, 4000.0)', inputs: grid([0, 1500, 2000, 3999, 4000, 9000]), ref: (a) => sat((a[0] - 1500) / 2500) },
];

export const defaultBudget = 1e-5;
export const floor = 1e-30;
