// cloudmath/wgsl/atmosphere_hooks.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, geometry.wgsl, phase.wgsl, transmittance.wgsl, atmosphere.wgsl.
// and your function(s):
//   fn cm_atmosphere_table(part: i32, x: i32, y: i32) -> vec3f  (GLSL: #define CM_ATMOSPHERE_TABLE)
//
// Part `part` of a width x height table at uv, bilinear with clamp to edge (GL_LINEAR).
fn cmi_atmosphere_table_bilinear(part: i32, w: i32, h: i32, uv: vec2f) -> vec3f {
    let x: f32 = uv.x * f32(w) - 0.5;
    let y: f32 = uv.y * f32(h) - 0.5;
    let x0: i32 = cmi_floor_to_int(x, 0, w - 2);
    let y0: i32 = cmi_floor_to_int(y, 0, h - 2);
    let fx: f32 = cm_saturate(x - f32(x0));
    let fy: f32 = cm_saturate(y - f32(y0));
    let bottom: vec3f = cm_atmosphere_table(part, x0, y0) * (1.0 - fx) + cm_atmosphere_table(part, x0 + 1, y0) * fx;
    let upper: vec3f = cm_atmosphere_table(part, x0, y0 + 1) * (1.0 - fx) + cm_atmosphere_table(part, x0 + 1, y0 + 1) * fx;
    return bottom * (1.0 - fy) + upper * fy;
}

// The sky's irradiance on the ground for the sun's zenith cosine mu_s there: the ground
// part's w texels read linearly by the LUT's column coordinate.
fn cmi_atmosphere_ground_irradiance_at(air: CmAtmosphere, w: i32, mu_s: f32) -> vec3f {
    if (w < 2) {
        if (w == 1) {
            return cm_atmosphere_table(CM_ATMOSPHERE_TABLE_GROUND, 0, 0);
        }
        return vec3f(0.0);
    }
    let x: f32 = cm_atmosphere_multiple_scattering_lut_uv(air, 0.0, mu_s, vec2f(f32(w), 1.0)).x * f32(w) - 0.5;
    let x0: i32 = cmi_floor_to_int(x, 0, w - 2);
    let fx: f32 = cm_saturate(x - f32(x0));
    return cm_atmosphere_table(CM_ATMOSPHERE_TABLE_GROUND, x0, 0) * (1.0 - fx) + cm_atmosphere_table(CM_ATMOSPHERE_TABLE_GROUND, x0 + 1, 0) * fx;
}

// What the table's field scatters into a ray of zenith cosine cos_view_zenith at (altitude,
// cos_sun_zenith); cos2_azimuth: the squared cosine of the view's azimuth from the sun's
// (atmosphere.hpp's detail::atmosphere_table_source).
fn cmi_atmosphere_table_source(air: CmAtmosphere, ms: CmAtmosphereTable, altitude: f32, cos_sun_zenith: f32, cos_view_zenith: f32, cos2_azimuth: f32) -> vec3f {
    let uv: vec2f = cm_atmosphere_multiple_scattering_lut_uv(air, altitude, cos_sun_zenith, vec2f(f32(ms.width), f32(ms.height)));
    let psi: vec3f = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_PSI, ms.width, ms.height, uv);
    if (ms.parts < 2) { return cm_atmosphere_scattering_coefficient(air, altitude) * psi; }
    let b: vec3f = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_VERTICAL, ms.width, ms.height, uv);
    if (ms.parts < 3) { return cm_atmosphere_multiple_scattering_source(air, altitude, psi, b, cos_view_zenith); }
    let h: f32 = max(altitude, 0.0);
    let mu2: f32 = clamp(cos_view_zenith * cos_view_zenith, 0.0, 1.0);
    let c2: f32 = clamp(cos2_azimuth, 0.0, 1.0);
    let along: vec3f = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_ALONG, ms.width, ms.height, uv);
    let horizontal: vec3f = along * c2 + (psi - b - along) * (1.0 - c2);
    let rayleigh: vec3f = air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) * (0.75 * (psi + horizontal * (1.0 - mu2) + b * mu2));
    var aerosol: vec3f = psi;
    // With the sun below this point's horizon the field is lit from one side of the sky only:
    // isotropic there (atmosphere.hpp says why).
    if (cos_sun_zenith > 0.0) {
        let m: f32 = clamp(cos_view_zenith, -1.0, 1.0);
        let x: f32 = select(sqrt(m), -sqrt(-m), m < 0.0);
        let fj: f32 = (x + 1.0) * 0.5 * f32(CM_ATMOSPHERE_AEROSOL_NODES - 1);
        let j0: i32 = cmi_floor_to_int(fj, 0, CM_ATMOSPHERE_AEROSOL_NODES - 2);
        let fr: f32 = cm_saturate(fj - f32(j0));
        aerosol = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_AEROSOL + j0, ms.width, ms.height, uv) * (1.0 - fr) + cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_AEROSOL + j0 + 1, ms.width, ms.height, uv) * fr;
    }
    return rayleigh + aerosol * (air.mie_scattering * exp(-h / air.mie_scale_height));
}

// The light the air scatters into the view ray between the camera (at `altitude`) and
// `distance` metres along it, or the end of the air or the ground if nearer, with the
// transmittance over the same stretch (atmosphere_inscatter: its steps t_i = D (i/steps)^2,
// the sun's single scattering and the table's field per step). Directions are unit vectors in
// the camera's frame with +y up. Per unit sun illuminance. Cost per step: one sun
// transmittance of sun_steps steps and, with ms.parts 3, 20 table reads of 4 texels.
fn cm_atmosphere_inscatter(air: CmAtmosphere, ms: CmAtmosphereTable, altitude: f32, view_dir: vec3f, sun_dir: vec3f, distance: f32, steps: i32, sun_steps: i32) -> CmAtmosphereSegment {
    let n: i32 = max(steps, 1);
    let h: f32 = clamp(altitude, 0.0, air.top_radius - air.bottom_radius);
    let r: f32 = air.bottom_radius + h;
    let mu: f32 = clamp(view_dir.y, -1.0, 1.0);
    let mu_s: f32 = clamp(sun_dir.y, -1.0, 1.0);
    let nu: f32 = clamp(dot(view_dir, sun_dir), -1.0, 1.0);
    let D: f32 = clamp(distance, 0.0, cmi_atmosphere_ray_length(air, h, mu));
    let use_ms: bool = ms.parts > 0 && ms.width >= 2 && ms.height >= 2;
    let cos2_azimuth: f32 = cmi_atmosphere_cos2_azimuth(mu, mu_s, nu);
    var out_segment: CmAtmosphereSegment = CmAtmosphereSegment(vec3f(1.0), vec3f(0.0));
    for (var i: i32 = 0; i < n; i++) {
        let x0: f32 = f32(i) / f32(n);
        let x1: f32 = f32(i + 1) / f32(n);
        let t0: f32 = D * x0 * x0;
        let t1: f32 = D * x1 * x1;
        let ds: f32 = t1 - t0;
        let t: f32 = 0.5 * (t0 + t1);
        let hy: f32 = cm_altitude_along_ray(h, mu, air.bottom_radius, t);
        let mu_sy: f32 = clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), -1.0, 1.0);
        let sigma_t: vec3f = cm_atmosphere_extinction(air, hy);
        var source: vec3f = cm_atmosphere_scattering(air, hy, nu) * cm_atmosphere_transmittance(air, hy, mu_sy, sun_steps);
        if (use_ms) {
            source += cmi_atmosphere_table_source(air, ms, hy, mu_sy, clamp((r * mu + t) / (air.bottom_radius + hy), -1.0, 1.0), cos2_azimuth);
        }
        let step_t: vec3f = cm_beer_lambert_v3(sigma_t * ds);
        let integral: vec3f = cm_one_minus_exp_neg_over_x_v3(sigma_t * ds) * ds;
        out_segment.radiance += out_segment.transmittance * source * integral;
        out_segment.transmittance *= step_t;
    }
    return out_segment;
}

// The sky's radiance along view_dir per unit sun illuminance (1/sr; the sun's disc excluded):
// cm_atmosphere_inscatter to the end of the air and, for rays that meet the ground, the
// Lambertian ground seen through the air, lit by the sun and (ms.ground_width > 0) the sky
// (atmosphere_sky_radiance). Accuracy as the C++ (atmosphere.hpp's header); parity with it in
// docs/glsl_parity.md.
fn cm_atmosphere_sky_radiance(air: CmAtmosphere, ms: CmAtmosphereTable, altitude: f32, view_dir: vec3f, sun_dir: vec3f, steps: i32, sun_steps: i32) -> vec3f {
    let seg: CmAtmosphereSegment = cm_atmosphere_inscatter(air, ms, altitude, view_dir, sun_dir, 3.0e38, steps, sun_steps);
    let h: f32 = clamp(altitude, 0.0, air.top_radius - air.bottom_radius);
    let mu: f32 = clamp(view_dir.y, -1.0, 1.0);
    if (!cm_atmosphere_ray_hits_ground(air, h, mu)) { return seg.radiance; }
    let t: f32 = cmi_atmosphere_ray_length(air, h, mu);
    let mu_sg: f32 = clamp(((air.bottom_radius + h) * sun_dir.y + t * dot(view_dir, sun_dir)) / air.bottom_radius, -1.0, 1.0);
    var ground: vec3f = cmi_atmosphere_lit_ground(air, mu_sg, sun_steps);
    if (ms.ground_width > 0) {
        ground += cmi_atmosphere_ground_irradiance_at(air, ms.ground_width, mu_sg) * (air.ground_albedo * CM_INV_PI);
    }
    return seg.radiance + seg.transmittance * ground;
}
