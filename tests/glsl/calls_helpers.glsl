// Helpers of the test shaders built from calls.txt: goes after the cloudmath module and
// before main. Defines the user functions declared in calls_prelude.glsl and turns struct
// and void results into floats.

// Phase function of cm_multiple_scattering_with: a dual lobe whose eccentricities scale.
float cm_test_phase(float mu, float scale) { return cm_phase_hg_dual(mu, 0.8 * scale, -0.5 * scale, 0.5); }

// Extinction (1/m) of cm_cone_optical_depth at sample i.
float cm_test_extinction(vec3 p, int i) {
    return cm_height_fog_density(p.y, 0.01, 1e-3) * (1.0 + 0.1 * float(i));
}

// The multiple-scattering table of cm_atmosphere_inscatter and cm_atmosphere_sky_radiance:
// made up, smooth in the texel and distinct per part (a renderer reads its textures here).
vec3 cm_test_atmosphere_table(int part, int x, int y) { return vec3(0.3, 0.45, 0.8) * (1.0 + 0.01 * float(x + y + part)); }

// cm_diffusion_chord_fluence's fluence plus its flux (an out parameter).
float cm_test_chord_fluence(float x, float y, float exp_neg_x, float kappa) {
    float flux;
    float U = cm_diffusion_chord_fluence(x, y, exp_neg_x, kappa, flux);
    return U + flux;
}

float cm_test_sum(CmMieApproxParams p) { return p.g_hg + p.g_draine + p.alpha + p.w_draine; }
float cm_test_sum(CmMarchAccumulator acc) { return cm_test_sum(acc.luminance + acc.transmittance); }

// cm_march_add_segment on a copy of acc; the state after the step, summed.
float cm_test_add_segment(CmMarchAccumulator acc, vec3 S, vec3 sigma_t, float ds) {
    cm_march_add_segment(acc, S, sigma_t, ds);
    return cm_test_sum(acc);
}
float cm_test_add_segment(CmMarchAccumulator acc, vec3 S, float sigma_t, float ds) {
    cm_march_add_segment(acc, S, sigma_t, ds);
    return cm_test_sum(acc);
}

// cm_beer_shadow_add_step on an accumulator started at (a.x, a.y, a.z, a.w): the texel after a step.
float cm_test_beer_shadow(vec4 a, vec4 b) {
    CmBeerShadowAccumulator acc = CmBeerShadowAccumulator(a.x, a.y, a.z, a.w);
    cm_beer_shadow_add_step(acc, b.x, b.y, b.z);
    return cm_test_sum(cm_beer_shadow_texel(acc));
}
