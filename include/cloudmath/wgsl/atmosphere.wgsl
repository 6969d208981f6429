// cloudmath/wgsl/atmosphere.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, geometry.wgsl, phase.wgsl, transmittance.wgsl.
//
// cloudmath/glsl/atmosphere.glsl: GLSL twin of cloudmath/atmosphere.hpp: a planet's air
// (CmAtmosphere, Earth's from cm_earth_atmosphere()), its extinction at an altitude, the
// optical depth and transmittance along a ray by quadrature, the transmittance LUT's
// parametrisation (Bruneton 2017) both ways, the scattering coefficients, the sun's illuminance,
// Hillaire 2020's multiple scattering and its LUT's parametrisation, the sky's radiance and the
// aerial perspective (with CM_ATMOSPHERE_TABLE, below), and EV100 exposure.
// Use: CmAtmosphere air = cm_earth_atmosphere();
//      vec3 T_sun = cm_atmosphere_transmittance(air, altitude, sun_dir.y, 64);
//      vec3 T_lut = texture(u_transmittance_lut, cm_atmosphere_transmittance_lut_uv(air, altitude, mu, vec2(256.0, 64.0))).rgb;
//      // with #define CM_ATMOSPHERE_TABLE my_table before the include (the section below):
//      vec3 sky = sun_lux * cm_atmosphere_sky_radiance(air, CmAtmosphereTable(32, 32, 3, 64), altitude, view_dir, sun_dir, 32, 32);
// Units: metres, 1/m; channels 680, 550, 440 nm.

// atmosphere_parameters (atmosphere.hpp), field for field.
struct CmAtmosphere {
    bottom_radius: f32,
    top_radius: f32,
    rayleigh_scattering: vec3f,
    rayleigh_scale_height: f32,
    mie_scattering: f32,
    mie_extinction: f32,
    mie_scale_height: f32,
    mie_g: f32,
    ozone_absorption: vec3f,
    ozone_center: f32,
    ozone_half_width: f32,
    ground_albedo: f32,
}

// Earth's air (Bruneton 2017): see earth_atmosphere() in atmosphere.hpp.
fn cm_earth_atmosphere() -> CmAtmosphere {
    return CmAtmosphere(6360e3, 6420e3, vec3f(5.802e-6, 13.558e-6, 33.1e-6), 8000.0, 3.996e-6, 4.40e-6, 1200.0, 0.8, vec3f(0.650e-6, 1.881e-6, 0.085e-6), 25e3, 15e3, 0.1);
}

// Rayleigh + Mie extinction + ozone absorption at an altitude (below 0 taken as 0).
fn cm_atmosphere_extinction(air: CmAtmosphere, altitude: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    let tent: f32 = max(1.0 - abs(h - air.ozone_center) / air.ozone_half_width, 0.0);
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) + vec3f(air.mie_extinction * exp(-h / air.mie_scale_height)) + air.ozone_absorption * tent;
}

// The distance along the ray to the top of the air (0 once outside, pointing outward).
fn cm_atmosphere_distance_to_top(air: CmAtmosphere, altitude: f32, cos_zenith: f32) -> f32 {
    let t: vec2f = cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, air.top_radius - air.bottom_radius);
    return max(t.y, 0.0);
}

// True when the ray meets the ground sphere in front of the point.
fn cm_atmosphere_ray_hits_ground(air: CmAtmosphere, altitude: f32, cos_zenith: f32) -> bool {
    if (!(cos_zenith < 0.0)) { return false; }
    let t: vec2f = cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, 0.0);
    return t.x >= 0.0 && t.y >= t.x;
}

// Optical depth along `distance` metres of the ray: the midpoint rule over `steps` steps.
fn cm_atmosphere_optical_depth(air: CmAtmosphere, altitude: f32, cos_zenith: f32, distance: f32, steps: i32) -> vec3f {
    let n: i32 = max(steps, 1);
    let ds: f32 = max(distance, 0.0) / f32(n);
    var tau: vec3f = vec3f(0.0);
    for (var i: i32 = 0; i < n; i++) {
        let t: f32 = (f32(i) + 0.5) * ds;
        tau += cm_atmosphere_extinction(air, cm_altitude_along_ray(altitude, cos_zenith, air.bottom_radius, t));
    }
    return tau * ds;
}

// Transmittance from the point to the top of the air along the direction; 0 into the ground.
fn cm_atmosphere_transmittance(air: CmAtmosphere, altitude: f32, cos_zenith: f32, steps: i32) -> vec3f {
    if (cm_atmosphere_ray_hits_ground(air, altitude, cos_zenith)) { return vec3f(0.0); }
    return exp(-cm_atmosphere_optical_depth(air, altitude, cos_zenith, cm_atmosphere_distance_to_top(air, altitude, cos_zenith), steps));
}

// The texture coordinates of (altitude, cos_zenith) in a transmittance LUT of `size` texels.
fn cm_atmosphere_transmittance_lut_uv(air: CmAtmosphere, altitude: f32, cos_zenith: f32, size: vec2f) -> vec2f {
    let R: f32 = air.bottom_radius;
    let top: f32 = air.top_radius;
    let r: f32 = R + clamp(altitude, 0.0, top - R);
    let H: f32 = sqrt((top - R) * (top + R));
    let rho: f32 = sqrt(max((r - R) * (r + R), 0.0));
    let d: f32 = cm_atmosphere_distance_to_top(air, r - R, cos_zenith);
    let d_min: f32 = top - r;
    let d_max: f32 = rho + H;
    let x_mu: f32 = select(0.0, clamp((d - d_min) / (d_max - d_min), 0.0, 1.0), d_max > d_min);
    let x_r: f32 = rho / H;
    return vec2f(0.5 / size.x + x_mu * (1.0 - 1.0 / size.x), 0.5 / size.y + x_r * (1.0 - 1.0 / size.y));
}

// The inverse: (altitude, cos_zenith) of texture coordinate uv (a LUT generator's texel).
fn cm_atmosphere_transmittance_lut_altitude_mu(air: CmAtmosphere, uv: vec2f, size: vec2f) -> vec2f {
    let R: f32 = air.bottom_radius;
    let top: f32 = air.top_radius;
    let x_mu: f32 = cm_saturate((uv.x - 0.5 / size.x) / (1.0 - 1.0 / size.x));
    let x_r: f32 = cm_saturate((uv.y - 0.5 / size.y) / (1.0 - 1.0 / size.y));
    let H: f32 = sqrt((top - R) * (top + R));
    let rho: f32 = H * x_r;
    let r: f32 = sqrt(rho * rho + R * R);
    let d_min: f32 = top - r;
    let d_max: f32 = rho + H;
    let d: f32 = d_min + x_mu * (d_max - d_min);
    let mu: f32 = select(1.0, clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0), d > 0.0);
    return vec2f(r - R, mu);
}

// sigma_s (1/m per channel): Rayleigh plus Mie scattering at an altitude (ozone only absorbs).
fn cm_atmosphere_scattering_coefficient(air: CmAtmosphere, altitude: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) + vec3f(air.mie_scattering * exp(-h / air.mie_scale_height));
}

// Scattering times phase (1/(m sr)): Rayleigh's phase for the molecules, Cornette-Shanks for
// the aerosols; cos_theta between the sun's and the view ray's directions (both outward).
fn cm_atmosphere_scattering(air: CmAtmosphere, altitude: f32, cos_theta: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    return air.rayleigh_scattering * (exp(-h / air.rayleigh_scale_height) * cm_phase_rayleigh(cos_theta)) + vec3f(air.mie_scattering * exp(-h / air.mie_scale_height) * cm_phase_cornette_shanks(cos_theta, air.mie_g));
}

// The sun's illuminance on a plane facing it: sun_illuminance (above the air) x transmittance.
fn cm_atmosphere_sun_illuminance(air: CmAtmosphere, altitude: f32, cos_sun_zenith: f32, sun_illuminance: vec3f) -> vec3f {
    return sun_illuminance * cm_atmosphere_transmittance(air, altitude, cos_sun_zenith, 64);
}

// Hillaire 2020's Psi_ms (see atmosphere_multiple_scattering in atmosphere.hpp): every order of
// scattering from the second on, per unit sun illuminance and scattering coefficient, from
// `directions` rays (spherical Fibonacci) of `steps` steps, sun transmittance in sun_steps steps;
// the second order turned towards the point by Rayleigh's phase (molecules), isotropically
// (aerosols).
fn cm_atmosphere_multiple_scattering(air: CmAtmosphere, altitude: f32, cos_sun_zenith: f32, directions: i32, steps: i32, sun_steps: i32) -> vec3f {
    let n_dir: i32 = max(directions, 1);
    let n: i32 = max(steps, 1);
    let h: f32 = clamp(altitude, 0.0, air.top_radius - air.bottom_radius);
    let r: f32 = air.bottom_radius + h;
    let mu_s: f32 = clamp(cos_sun_zenith, -1.0, 1.0);
    let sun: vec3f = vec3f(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    let golden_angle: f32 = CM_PI * (3.0 - sqrt(5.0));
    var L2: vec3f = vec3f(0.0);
    var f: vec3f = vec3f(0.0);
    for (var k: i32 = 0; k < n_dir; k++) {
        let mu: f32 = 1.0 - (2.0 * f32(k) + 1.0) / f32(n_dir);
        let phi: f32 = golden_angle * f32(k);
        let sin_zenith: f32 = sqrt(max(1.0 - mu * mu, 0.0));
        let dir: vec3f = vec3f(sin_zenith * cos(phi), mu, sin_zenith * sin(phi));
        let ground: bool = cm_atmosphere_ray_hits_ground(air, h, mu);
        var len: f32;
        if (ground) {
            len = cm_ray_sphere_intersect_altitude(h, mu, air.bottom_radius, 0.0).x;
        } else {
            len = cm_atmosphere_distance_to_top(air, h, mu);
        }
        let ds: f32 = len / f32(n);
        let nu: f32 = dot(dir, sun);
        var throughput: vec3f = vec3f(1.0);
        var L: vec3f = vec3f(0.0);
        var F: vec3f = vec3f(0.0);
        for (var i: i32 = 0; i < n; i++) {
            let t: f32 = (f32(i) + 0.5) * ds;
            let hy: f32 = cm_altitude_along_ray(h, mu, air.bottom_radius, t);
            let mu_sy: f32 = clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), -1.0, 1.0);
            let sigma_t: vec3f = cm_atmosphere_extinction(air, hy);
            let sigma_s: vec3f = cm_atmosphere_scattering_coefficient(air, hy);
            let step_t: vec3f = cm_beer_lambert_v3(sigma_t * ds);
            let integral: vec3f = cm_one_minus_exp_neg_over_x_v3(sigma_t * ds) * ds;
            let sun_t: vec3f = cm_atmosphere_transmittance(air, hy, mu_sy, sun_steps);
            // The second order's last turn: Rayleigh's phase for the molecules, isotropic aerosols.
            let h0: f32 = max(hy, 0.0);
            let turn: vec3f = air.rayleigh_scattering * (exp(-h0 / air.rayleigh_scale_height) * cm_phase_rayleigh(nu)) + vec3f(air.mie_scattering * exp(-h0 / air.mie_scale_height) * CM_INV_FOUR_PI);
            L += throughput * turn * sun_t * integral;
            F += throughput * sigma_s * integral;
            throughput *= step_t;
        }
        if (ground) {
            let mu_sg: f32 = clamp((r * mu_s + len * nu) / air.bottom_radius, -1.0, 1.0);
            L += throughput * cm_atmosphere_transmittance(air, 0.0, mu_sg, sun_steps) * (max(mu_sg, 0.0) * air.ground_albedo * CM_INV_PI);
        }
        L2 += L;
        f += F;
    }
    L2 /= vec3f(f32(n_dir));
    f /= vec3f(f32(n_dir));
    return L2 / (vec3f(1.0) - min(f, vec3f(0.999)));
}

// What the multiple-scattering field scatters into a ray per unit length (see
// atmosphere_multiple_scattering_source): psi and its vertical second moment from the LUTs
// (vertical_moment = psi / 3 for an isotropic field); Rayleigh's phase over the field for the
// molecules, isotropic for the aerosols.
fn cm_atmosphere_multiple_scattering_source(air: CmAtmosphere, altitude: f32, psi: vec3f, vertical_moment: vec3f, cos_view_zenith: f32) -> vec3f {
    let h: f32 = max(altitude, 0.0);
    let mu2: f32 = clamp(cos_view_zenith * cos_view_zenith, 0.0, 1.0);
    let horizontal: vec3f = (psi - vertical_moment) * 0.5;
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) * (0.75 * (psi + horizontal * (1.0 - mu2) + vertical_moment * mu2)) + psi * (air.mie_scattering * exp(-h / air.mie_scale_height));
}

// The multiple-scattering LUT's (u, v) of (altitude, cos_sun_zenith), and the inverse: u by
// sign(mu_s) sqrt(|mu_s|), which crowds the columns around Earth's shadow (atmosphere.hpp).
fn cm_atmosphere_multiple_scattering_lut_uv(air: CmAtmosphere, altitude: f32, cos_sun_zenith: f32, size: vec2f) -> vec2f {
    let c: f32 = clamp(cos_sun_zenith, -1.0, 1.0);
    let root: f32 = sqrt(abs(c));
    let x_mu: f32 = cm_saturate(0.5 + 0.5 * (select(root, -root, c < 0.0)));
    let x_h: f32 = cm_saturate(altitude / (air.top_radius - air.bottom_radius));
    return vec2f(0.5 / size.x + x_mu * (1.0 - 1.0 / size.x), 0.5 / size.y + x_h * (1.0 - 1.0 / size.y));
}
fn cm_atmosphere_multiple_scattering_lut_altitude_mu(air: CmAtmosphere, uv: vec2f, size: vec2f) -> vec2f {
    let x_mu: f32 = cm_saturate((uv.x - 0.5 / size.x) / (1.0 - 1.0 / size.x));
    let x_h: f32 = cm_saturate((uv.y - 0.5 / size.y) / (1.0 - 1.0 / size.y));
    let m: f32 = 2.0 * x_mu - 1.0;
    return vec2f(x_h * (air.top_radius - air.bottom_radius), m * abs(m));
}

// ---------------------------------------------------------------------------------------
// The sky and the aerial perspective (atmosphere_inscatter, atmosphere_sky_radiance): the
// march of atmosphere.hpp step for step, reading the multiple-scattering table through a
// function you define, so that the texels come from your own textures:
//   vec3 my_table(int part, int x, int y);   // declared before the include, defined anywhere
//   #define CM_ATMOSPHERE_TABLE my_table
//   #include "cloudmath/glsl/atmosphere.glsl"
//   vec3 my_table(int part, int x, int y) {  // e.g. the parts stacked in one RGB32F texture
//       return part == CM_ATMOSPHERE_TABLE_GROUND ? texelFetch(u_ground, ivec2(x, 0), 0).rgb
//                                                 : texelFetch(u_table, ivec2(x, y + part * 32), 0).rgb;
//   }
// It returns texel (x, y) of `part` (row y = 0 first, as atmosphere_sky_luts stores them):
// CM_ATMOSPHERE_TABLE_PSI the LUT's Psi_ms, _VERTICAL its vertical moments, _ALONG its
// sun-azimuth moments, _AEROSOL + j (j = 0 .. CM_ATMOSPHERE_AEROSOL_NODES - 1) the aerosol
// field's node j, and _GROUND the ground irradiance (x its column, y = 0). The library
// interpolates them itself, exactly as the C++ (detail::lut_bilinear, clamp to edge), so a
// shader and the CPU give the same sky to float rounding, whatever the texture filtering.
const CM_ATMOSPHERE_TABLE_PSI = 0;
const CM_ATMOSPHERE_TABLE_VERTICAL = 1;
const CM_ATMOSPHERE_TABLE_ALONG = 2;
const CM_ATMOSPHERE_TABLE_GROUND = 3;
const CM_ATMOSPHERE_TABLE_AEROSOL = 4;
const CM_ATMOSPHERE_AEROSOL_NODES = 17;

// atmosphere_multiple_scattering_table (atmosphere.hpp): which parts of the table a shader has
// and their sizes. parts 0: no multiple scattering (the single-scattering sky); 1: Psi_ms alone
// (Hillaire's LUT, an isotropic field); 2: with the vertical moments; 3: with the sun-azimuth
// moments and the aerosol field as well (atmosphere_make_sky_luts). width and height (>= 2)
// are the LUT's; ground_width the ground irradiance's texels (0: the ground below the horizon
// reflects the sun alone).
struct CmAtmosphereTable {
    width: i32,
    height: i32,
    parts: i32,
    ground_width: i32,
}

// What a view ray gathers (atmosphere_segment): the transmittance to the segment's end and the
// light scattered into it per unit sun illuminance (1/sr).
struct CmAtmosphereSegment {
    transmittance: vec3f,
    radiance: vec3f,
}

// floor(x) as an int clamped to [lo, hi]; NaN gives lo (core.hpp's floor_to_int).
fn cmi_floor_to_int(x: f32, lo: i32, hi: i32) -> i32 {
    if (!(x > f32(lo))) { return lo; }
    if (x >= f32(hi)) { return hi; }
    return i32(floor(x));
}

// The length of a ray in the air: to the ground where it meets it, else to the top.
fn cmi_atmosphere_ray_length(air: CmAtmosphere, altitude: f32, cos_zenith: f32) -> f32 {
    if (cm_atmosphere_ray_hits_ground(air, altitude, cos_zenith)) { return cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, 0.0).x; }
    return cm_atmosphere_distance_to_top(air, altitude, cos_zenith);
}

// The Lambertian ground's radiance per unit sun illuminance under a sun of zenith cosine mu_s.
fn cmi_atmosphere_lit_ground(air: CmAtmosphere, mu_s: f32, sun_steps: i32) -> vec3f {
    return cm_atmosphere_transmittance(air, 0.0, mu_s, sun_steps) * (max(mu_s, 0.0) * air.ground_albedo * CM_INV_PI);
}

// The square of the cosine of the azimuth between directions of zenith cosines mu and mu_s
// whose dot product is nu; 1/2 (no azimuth) when either is vertical.
fn cmi_atmosphere_cos2_azimuth(mu: f32, mu_s: f32, nu: f32) -> f32 {
    let den: f32 = (1.0 - mu * mu) * (1.0 - mu_s * mu_s);
    if (!(den > 1e-8)) { return 0.5; }
    let c: f32 = nu - mu * mu_s;
    return clamp(c * c / den, 0.0, 1.0);
}

// EV100 of a camera (f-number, shutter seconds, ISO), of an average luminance, and the exposure.
fn cm_ev100_from_camera(aperture: f32, shutter_time: f32, iso: f32) -> f32 {
    return log2(aperture * aperture / shutter_time * 100.0 / iso);
}
fn cm_ev100_from_luminance(average_luminance: f32) -> f32 { return log2(average_luminance * 100.0 / 12.5); }
fn cm_exposure_from_ev100(ev100: f32) -> f32 { return 1.0 / (1.2 * exp2(ev100)); }
