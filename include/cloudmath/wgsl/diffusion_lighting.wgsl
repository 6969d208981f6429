// cloudmath/wgsl/diffusion_lighting.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, phase.wgsl, diffusion_lighting_models.wgsl.
//
// cloudmath/glsl/diffusion_lighting.glsl: GLSL twin of cloudmath/diffusion_lighting.hpp,
// multiple scattering from diffusion along the sun's chord with a fitted correction table.
// The formulas, their sources and the inputs are documented in the C++ header.
//
// Use:      float M = cm_diffusion_scattering(tau_sun, tau_behind, tau_view, mu, g, albedo,
//                                             CM_DIFFUSION_MODEL_FITTED);
//           // tau_behind: optical depth behind the sample along the sun direction (a second
//           // short march away from the sun); tau_view: optical depth from the camera.
// Configuration (#define before the include):
//   CM_DIFFUSION_PHASE  name of a user function `float f(float mu, float scale)` returning the
//                       phase function with eccentricities scaled by `scale` (1, 0.5, 0.8).
//                       When defined, cm_diffusion_scattering_with(...) is available (the C++
//                       generic form); g is then that phase function's mean cosine.
// Models:   CM_DIFFUSION_MODEL_FITTED (fitted to homogeneous media), CM_DIFFUSION_MODEL_CLOUDS
//           (fitted to whole-cloud images: the one for cloud fields, the example renderer's
//           default), CM_DIFFUSION_MODEL_PHYSICAL (plain diffusion, for comparison), generated
//           in diffusion_lighting_models.glsl; errors in the C++ header.
// GLSL 3.30 / ES 3.00: const arrays inside a struct, indexed at run time.

fn cmi_diffusion_depth(tau: f32) -> f32 { return clamp(tau, 0.0, 1e6); }

// (1 - albedo g, kappa): the similarity relations with absorption (C++ diffusion_similarity).
fn cm_diffusion_similarity(g: f32, albedo: f32) -> vec2f {
    let gc: f32 = clamp(g, -0.999, 0.999);
    let w: f32 = clamp(albedo, 0.0, 1.0);
    let s: f32 = max(1.0 - w * gc, 0.001);
    return vec2f(s, min(sqrt(3.0 * (1.0 - w) / s), 0.9));
}

// Fluence U (returned) and net flux F of the chord's diffusion solution with absorption
// kappa (the C++ diffusion_chord_fluence, same stable forms).
fn cm_diffusion_chord_fluence(x: f32, y: f32, exp_neg_x: f32, kappa: f32, flux: ptr<function, f32>) -> f32 {
    let z: f32 = CM_DIFFUSION_EXTRAPOLATION;
    let ez: f32 = exp(z);
    let L: f32 = x + y;
    let W: f32 = L + 2.0 * z;
    let a1: f32 = x + z;
    let a2: f32 = y + z;
    let e_far: f32 = exp(-(L + z));
    let k: f32 = clamp(kappa, 0.0, 0.9);
    var R1: f32;
    var R2: f32;
    var kQ1: f32;
    var kQ2: f32;
    if (k * W < 1e-4) {
        let k2: f32 = k * k;
        let W2: f32 = W * W;
        R1 = a1 / W * (1.0 + k2 * (a1 * a1 - W2) / 6.0);
        R2 = a2 / W * (1.0 + k2 * (a2 * a2 - W2) / 6.0);
        kQ1 = (1.0 + k2 * (a1 * a1 / 2.0 - W2 / 6.0)) / W;
        kQ2 = (1.0 + k2 * (a2 * a2 / 2.0 - W2 / 6.0)) / W;
    } else {
        let e1: f32 = exp(-k * a1);
        let e2: f32 = exp(-k * a2);
        let inv_denominator: f32 = 1.0 / cm_one_minus_exp_neg(2.0 * k * W);
        R1 = e2 * cm_one_minus_exp_neg(2.0 * k * a1) * inv_denominator;
        R2 = e1 * cm_one_minus_exp_neg(2.0 * k * a2) * inv_denominator;
        kQ1 = k * e2 * (1.0 + e1 * e1) * inv_denominator;
        kQ2 = k * e1 * (1.0 + e2 * e2) * inv_denominator;
    }
    let scale: f32 = 1.0 / (1.0 - k * k);
    (*flux) = scale * (ez * kQ2 - e_far * kQ1 - exp_neg_x);
    return max(3.0 * scale * (e_far * R1 + ez * R2 - exp_neg_x), 0.0);
}

// (u_sun, u_behind, u_mu, u_surface), each in [0, 1].
fn cm_diffusion_table_coordinates(tau_sun: f32, tau_behind: f32, tau_view: f32, mu: f32, g: f32, albedo: f32) -> vec4f {
    let s: f32 = cm_diffusion_similarity(g, albedo).x;
    let x: f32 = s * cmi_diffusion_depth(tau_sun);
    let y: f32 = s * cmi_diffusion_depth(tau_behind);
    let z: f32 = CM_DIFFUSION_EXTRAPOLATION;
    let t: f32 = (x + z) * (y + z) / (x + y + 2.0 * z);
    let d: f32 = s * cmi_diffusion_depth(tau_view) + z;
    return vec4f(x / (1.0 + x), y / (1.0 + y), 0.5 * clamp(mu, -1.0, 1.0) + 0.5, d / (d + t));
}

// Lower node and upper weight of u over n equally spaced nodes.
fn cmi_diffusion_hat(u: f32, n: i32, i0: ptr<function, i32>, w1: ptr<function, f32>) {
    let p: f32 = clamp(u, 0.0, 1.0) * f32(n - 1);
    // An integer clamp: int(NaN) is undefined (INT_MIN on common GPUs), and the node indexes
    // the table; [0, n - 2] whatever u is.
    let i: i32 = clamp(i32(p), 0, n - 2);
    (*i0) = i;
    (*w1) = p - f32(i);
}

fn cm_diffusion_table_lookup(m_in: CmDiffusionModel, u: vec4f) -> f32 {
    var m: CmDiffusionModel = m_in;
    var ix: i32;
    var iy: i32;
    var im: i32;
    var id: i32;
    var wx: f32;
    var wy: f32;
    var wm: f32;
    var wd: f32;
    cmi_diffusion_hat(u.x, CM_DIFFUSION_SIZE_X, &ix, &wx);
    cmi_diffusion_hat(u.y, CM_DIFFUSION_SIZE_Y, &iy, &wy);
    cmi_diffusion_hat(u.z, CM_DIFFUSION_SIZE_MU, &im, &wm);
    cmi_diffusion_hat(u.w, CM_DIFFUSION_SIZE_D, &id, &wd);
    var sum: f32 = 0.0;
    for (var a: i32 = 0; a < 2; a++) {
        for (var b: i32 = 0; b < 2; b++) {
            for (var c: i32 = 0; c < 2; c++) {
                for (var e: i32 = 0; e < 2; e++) {
                    let w: f32 = (select(1.0 - wx, wx, a == 1)) * (select(1.0 - wy, wy, b == 1)) * (select(1.0 - wm, wm, c == 1)) * (select(1.0 - wd, wd, e == 1));
                    let index: i32 = (((ix + a) * CM_DIFFUSION_SIZE_Y + iy + b) * CM_DIFFUSION_SIZE_MU + im + c) * CM_DIFFUSION_SIZE_D + id + e;
                    sum += w * m.table[index];
                }
            }
        }
    }
    return sum;
}

// The model with the three phase values it needs (scales 1, 0.5 and 0.8) given.
fn cmi_diffusion_scattering_phases(tau_sun: f32, tau_behind: f32, tau_view: f32, mu: f32, g: f32, albedo: f32, m: CmDiffusionModel, p1: f32, p_half: f32, p_four_fifths: f32) -> f32 {
    let mc: f32 = clamp(mu, -1.0, 1.0);
    let gc: f32 = clamp(g, -0.999, 0.999);
    let w: f32 = clamp(albedo, 0.0, 1.0);
    let medium: vec2f = cm_diffusion_similarity(gc, w);
    let ts: f32 = cmi_diffusion_depth(tau_sun);
    let x: f32 = medium.x * ts;
    let y: f32 = medium.x * cmi_diffusion_depth(tau_behind);
    let direct: f32 = exp(-ts);
    let e_half: f32 = exp(-0.5 * x);
    let e_one: f32 = e_half * e_half;
    let beams: vec3f = max(vec3f(e_half, e_one, e_one * e_one) - direct, vec3f(0.0));
    let w_half: f32 = m.peak[0] * beams.x + m.peak[2] * beams.y + m.peak[4] * beams.z;
    let w_four_fifths: f32 = m.peak[1] * beams.x + m.peak[3] * beams.y + m.peak[5] * beams.z;
    let peak: f32 = w_half * p_half + w_four_fifths * p_four_fifths;
    let source: f32 = w * (1.0 - gc) / medium.x;
    var flux: f32;
    let U: f32 = cm_diffusion_chord_fluence(x, y, e_one, medium.y, &flux);
    let D: f32 = source * max(U + 3.0 * gc * flux * mc, 0.0) * CM_INV_FOUR_PI;
    let C: f32 = cm_diffusion_table_lookup(m, cm_diffusion_table_coordinates(ts, tau_behind, tau_view, mc, gc, w));
    return max(p1 * direct + peak + D * max(C, 0.0), 0.0);
}

// With the Henyey-Greenstein phase function of asymmetry g.
fn cm_diffusion_scattering(tau_sun: f32, tau_behind: f32, tau_view: f32, mu: f32, g: f32, albedo: f32, m: CmDiffusionModel) -> f32 {
    let mc: f32 = clamp(mu, -1.0, 1.0);
    return cmi_diffusion_scattering_phases(tau_sun, tau_behind, tau_view, mu, g, albedo, m, cm_phase_hg(mc, g), cm_phase_hg(mc, 0.5 * g), cm_phase_hg(mc, 0.8 * g));
}
