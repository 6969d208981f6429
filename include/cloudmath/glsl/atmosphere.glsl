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
#ifndef CM_ATMOSPHERE_GLSL
#define CM_ATMOSPHERE_GLSL

#include "core.glsl"
#include "geometry.glsl"
#include "phase.glsl"
#include "transmittance.glsl"

// atmosphere_parameters (atmosphere.hpp), field for field.
struct CmAtmosphere {
    float bottom_radius;
    float top_radius;
    vec3 rayleigh_scattering;
    float rayleigh_scale_height;
    float mie_scattering;
    float mie_extinction;
    float mie_scale_height;
    float mie_g;
    vec3 ozone_absorption;
    float ozone_center;
    float ozone_half_width;
    float ground_albedo;
};

// Earth's air (Bruneton 2017): see earth_atmosphere() in atmosphere.hpp.
CmAtmosphere cm_earth_atmosphere() {
    return CmAtmosphere(6360e3, 6420e3, vec3(5.802e-6, 13.558e-6, 33.1e-6), 8000.0, 3.996e-6, 4.40e-6, 1200.0, 0.8,
                        vec3(0.650e-6, 1.881e-6, 0.085e-6), 25e3, 15e3, 0.1);
}

// Rayleigh + Mie extinction + ozone absorption at an altitude (below 0 taken as 0).
vec3 cm_atmosphere_extinction(CmAtmosphere air, float altitude) {
    float h = max(altitude, 0.0);
    float tent = max(1.0 - abs(h - air.ozone_center) / air.ozone_half_width, 0.0);
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) + vec3(air.mie_extinction * exp(-h / air.mie_scale_height)) +
           air.ozone_absorption * tent;
}

// The distance along the ray to the top of the air (0 once outside, pointing outward).
float cm_atmosphere_distance_to_top(CmAtmosphere air, float altitude, float cos_zenith) {
    vec2 t = cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, air.top_radius - air.bottom_radius);
    return max(t.y, 0.0);
}

// True when the ray meets the ground sphere in front of the point.
bool cm_atmosphere_ray_hits_ground(CmAtmosphere air, float altitude, float cos_zenith) {
    if (!(cos_zenith < 0.0)) return false;
    vec2 t = cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, 0.0);
    return t.x >= 0.0 && t.y >= t.x;
}

// Optical depth along `distance` metres of the ray: the midpoint rule over `steps` steps.
vec3 cm_atmosphere_optical_depth(CmAtmosphere air, float altitude, float cos_zenith, float distance, int steps) {
    int n = max(steps, 1);
    float ds = max(distance, 0.0) / float(n);
    vec3 tau = vec3(0.0);
    for (int i = 0; i < n; ++i) {
        float t = (float(i) + 0.5) * ds;
        tau += cm_atmosphere_extinction(air, cm_altitude_along_ray(altitude, cos_zenith, air.bottom_radius, t));
    }
    return tau * ds;
}

// Transmittance from the point to the top of the air along the direction; 0 into the ground.
vec3 cm_atmosphere_transmittance(CmAtmosphere air, float altitude, float cos_zenith, int steps) {
    if (cm_atmosphere_ray_hits_ground(air, altitude, cos_zenith)) return vec3(0.0);
    return exp(-cm_atmosphere_optical_depth(air, altitude, cos_zenith, cm_atmosphere_distance_to_top(air, altitude, cos_zenith), steps));
}

// The texture coordinates of (altitude, cos_zenith) in a transmittance LUT of `size` texels.
vec2 cm_atmosphere_transmittance_lut_uv(CmAtmosphere air, float altitude, float cos_zenith, vec2 size) {
    float R = air.bottom_radius, top = air.top_radius;
    float r = R + clamp(altitude, 0.0, top - R);
    float H = sqrt((top - R) * (top + R));
    float rho = sqrt(max((r - R) * (r + R), 0.0));
    float d = cm_atmosphere_distance_to_top(air, r - R, cos_zenith);
    float d_min = top - r, d_max = rho + H;
    float x_mu = d_max > d_min ? clamp((d - d_min) / (d_max - d_min), 0.0, 1.0) : 0.0;
    float x_r = rho / H;
    return vec2(0.5 / size.x + x_mu * (1.0 - 1.0 / size.x), 0.5 / size.y + x_r * (1.0 - 1.0 / size.y));
}

// The inverse: (altitude, cos_zenith) of texture coordinate uv (a LUT generator's texel).
vec2 cm_atmosphere_transmittance_lut_altitude_mu(CmAtmosphere air, vec2 uv, vec2 size) {
    float R = air.bottom_radius, top = air.top_radius;
    float x_mu = cm_saturate((uv.x - 0.5 / size.x) / (1.0 - 1.0 / size.x));
    float x_r = cm_saturate((uv.y - 0.5 / size.y) / (1.0 - 1.0 / size.y));
    float H = sqrt((top - R) * (top + R));
    float rho = H * x_r;
    float r = sqrt(rho * rho + R * R);
    float d_min = top - r, d_max = rho + H;
    float d = d_min + x_mu * (d_max - d_min);
    float mu = d > 0.0 ? clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0) : 1.0;
    return vec2(r - R, mu);
}

// sigma_s (1/m per channel): Rayleigh plus Mie scattering at an altitude (ozone only absorbs).
vec3 cm_atmosphere_scattering_coefficient(CmAtmosphere air, float altitude) {
    float h = max(altitude, 0.0);
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) + vec3(air.mie_scattering * exp(-h / air.mie_scale_height));
}

// Scattering times phase (1/(m sr)): Rayleigh's phase for the molecules, Cornette-Shanks for
// the aerosols; cos_theta between the sun's and the view ray's directions (both outward).
vec3 cm_atmosphere_scattering(CmAtmosphere air, float altitude, float cos_theta) {
    float h = max(altitude, 0.0);
    return air.rayleigh_scattering * (exp(-h / air.rayleigh_scale_height) * cm_phase_rayleigh(cos_theta)) +
           vec3(air.mie_scattering * exp(-h / air.mie_scale_height) * cm_phase_cornette_shanks(cos_theta, air.mie_g));
}

// The sun's illuminance on a plane facing it: sun_illuminance (above the air) x transmittance.
vec3 cm_atmosphere_sun_illuminance(CmAtmosphere air, float altitude, float cos_sun_zenith, vec3 sun_illuminance) {
    return sun_illuminance * cm_atmosphere_transmittance(air, altitude, cos_sun_zenith, 64);
}

// Hillaire 2020's Psi_ms (see atmosphere_multiple_scattering in atmosphere.hpp): every order of
// scattering from the second on, per unit sun illuminance and scattering coefficient, from
// `directions` rays (spherical Fibonacci) of `steps` steps, sun transmittance in sun_steps steps;
// the second order turned towards the point by Rayleigh's phase (molecules), isotropically
// (aerosols).
vec3 cm_atmosphere_multiple_scattering(CmAtmosphere air, float altitude, float cos_sun_zenith, int directions, int steps,
                                       int sun_steps) {
    int n_dir = max(directions, 1);
    int n = max(steps, 1);
    float h = clamp(altitude, 0.0, air.top_radius - air.bottom_radius);
    float r = air.bottom_radius + h;
    float mu_s = clamp(cos_sun_zenith, -1.0, 1.0);
    vec3 sun = vec3(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    float golden_angle = CM_PI * (3.0 - sqrt(5.0));
    vec3 L2 = vec3(0.0);
    vec3 f = vec3(0.0);
    for (int k = 0; k < n_dir; ++k) {
        float mu = 1.0 - (2.0 * float(k) + 1.0) / float(n_dir);
        float phi = golden_angle * float(k);
        float sin_zenith = sqrt(max(1.0 - mu * mu, 0.0));
        vec3 dir = vec3(sin_zenith * cos(phi), mu, sin_zenith * sin(phi));
        bool ground = cm_atmosphere_ray_hits_ground(air, h, mu);
        float len = ground ? cm_ray_sphere_intersect_altitude(h, mu, air.bottom_radius, 0.0).x
                           : cm_atmosphere_distance_to_top(air, h, mu);
        float ds = len / float(n);
        float nu = dot(dir, sun);
        vec3 throughput = vec3(1.0);
        vec3 L = vec3(0.0);
        vec3 F = vec3(0.0);
        for (int i = 0; i < n; ++i) {
            float t = (float(i) + 0.5) * ds;
            float hy = cm_altitude_along_ray(h, mu, air.bottom_radius, t);
            float mu_sy = clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), -1.0, 1.0);
            vec3 sigma_t = cm_atmosphere_extinction(air, hy);
            vec3 sigma_s = cm_atmosphere_scattering_coefficient(air, hy);
            vec3 step_t = cm_beer_lambert(sigma_t * ds);
            vec3 integral = cm_one_minus_exp_neg_over_x(sigma_t * ds) * ds;
            vec3 sun_t = cm_atmosphere_transmittance(air, hy, mu_sy, sun_steps);
            // The second order's last turn: Rayleigh's phase for the molecules, isotropic aerosols.
            float h0 = max(hy, 0.0);
            vec3 turn = air.rayleigh_scattering * (exp(-h0 / air.rayleigh_scale_height) * cm_phase_rayleigh(nu)) +
                        vec3(air.mie_scattering * exp(-h0 / air.mie_scale_height) * CM_INV_FOUR_PI);
            L += throughput * turn * sun_t * integral;
            F += throughput * sigma_s * integral;
            throughput *= step_t;
        }
        if (ground) {
            float mu_sg = clamp((r * mu_s + len * nu) / air.bottom_radius, -1.0, 1.0);
            L += throughput * cm_atmosphere_transmittance(air, 0.0, mu_sg, sun_steps) * (max(mu_sg, 0.0) * air.ground_albedo * CM_INV_PI);
        }
        L2 += L;
        f += F;
    }
    L2 /= float(n_dir);
    f /= float(n_dir);
    return L2 / (vec3(1.0) - min(f, vec3(0.999)));
}

// What the multiple-scattering field scatters into a ray per unit length (see
// atmosphere_multiple_scattering_source): psi and its vertical second moment from the LUTs
// (vertical_moment = psi / 3 for an isotropic field); Rayleigh's phase over the field for the
// molecules, isotropic for the aerosols.
vec3 cm_atmosphere_multiple_scattering_source(CmAtmosphere air, float altitude, vec3 psi, vec3 vertical_moment,
                                              float cos_view_zenith) {
    float h = max(altitude, 0.0);
    float mu2 = clamp(cos_view_zenith * cos_view_zenith, 0.0, 1.0);
    vec3 horizontal = (psi - vertical_moment) * 0.5;
    return air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) *
               (0.75 * (psi + horizontal * (1.0 - mu2) + vertical_moment * mu2)) +
           psi * (air.mie_scattering * exp(-h / air.mie_scale_height));
}

// The multiple-scattering LUT's (u, v) of (altitude, cos_sun_zenith), and the inverse: u by
// sign(mu_s) sqrt(|mu_s|), which crowds the columns around Earth's shadow (atmosphere.hpp).
vec2 cm_atmosphere_multiple_scattering_lut_uv(CmAtmosphere air, float altitude, float cos_sun_zenith, vec2 size) {
    float c = clamp(cos_sun_zenith, -1.0, 1.0);
    float root = sqrt(abs(c));
    float x_mu = cm_saturate(0.5 + 0.5 * (c < 0.0 ? -root : root));
    float x_h = cm_saturate(altitude / (air.top_radius - air.bottom_radius));
    return vec2(0.5 / size.x + x_mu * (1.0 - 1.0 / size.x), 0.5 / size.y + x_h * (1.0 - 1.0 / size.y));
}
vec2 cm_atmosphere_multiple_scattering_lut_altitude_mu(CmAtmosphere air, vec2 uv, vec2 size) {
    float x_mu = cm_saturate((uv.x - 0.5 / size.x) / (1.0 - 1.0 / size.x));
    float x_h = cm_saturate((uv.y - 0.5 / size.y) / (1.0 - 1.0 / size.y));
    float m = 2.0 * x_mu - 1.0;
    return vec2(x_h * (air.top_radius - air.bottom_radius), m * abs(m));
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
#define CM_ATMOSPHERE_TABLE_PSI 0
#define CM_ATMOSPHERE_TABLE_VERTICAL 1
#define CM_ATMOSPHERE_TABLE_ALONG 2
#define CM_ATMOSPHERE_TABLE_GROUND 3
#define CM_ATMOSPHERE_TABLE_AEROSOL 4
#define CM_ATMOSPHERE_AEROSOL_NODES 17

// atmosphere_multiple_scattering_table (atmosphere.hpp): which parts of the table a shader has
// and their sizes. parts 0: no multiple scattering (the single-scattering sky); 1: Psi_ms alone
// (Hillaire's LUT, an isotropic field); 2: with the vertical moments; 3: with the sun-azimuth
// moments and the aerosol field as well (atmosphere_make_sky_luts). width and height (>= 2)
// are the LUT's; ground_width the ground irradiance's texels (0: the ground below the horizon
// reflects the sun alone).
struct CmAtmosphereTable {
    int width;
    int height;
    int parts;
    int ground_width;
};

// What a view ray gathers (atmosphere_segment): the transmittance to the segment's end and the
// light scattered into it per unit sun illuminance (1/sr).
struct CmAtmosphereSegment {
    vec3 transmittance;
    vec3 radiance;
};

// floor(x) as an int clamped to [lo, hi]; NaN gives lo (core.hpp's floor_to_int).
int cmi_floor_to_int(float x, int lo, int hi) {
    if (!(x > float(lo))) return lo;
    if (x >= float(hi)) return hi;
    return int(floor(x));
}

// The length of a ray in the air: to the ground where it meets it, else to the top.
float cmi_atmosphere_ray_length(CmAtmosphere air, float altitude, float cos_zenith) {
    if (cm_atmosphere_ray_hits_ground(air, altitude, cos_zenith))
        return cm_ray_sphere_intersect_altitude(altitude, cos_zenith, air.bottom_radius, 0.0).x;
    return cm_atmosphere_distance_to_top(air, altitude, cos_zenith);
}

// The Lambertian ground's radiance per unit sun illuminance under a sun of zenith cosine mu_s.
vec3 cmi_atmosphere_lit_ground(CmAtmosphere air, float mu_s, int sun_steps) {
    return cm_atmosphere_transmittance(air, 0.0, mu_s, sun_steps) * (max(mu_s, 0.0) * air.ground_albedo * CM_INV_PI);
}

// The square of the cosine of the azimuth between directions of zenith cosines mu and mu_s
// whose dot product is nu; 1/2 (no azimuth) when either is vertical.
float cmi_atmosphere_cos2_azimuth(float mu, float mu_s, float nu) {
    float den = (1.0 - mu * mu) * (1.0 - mu_s * mu_s);
    if (!(den > 1e-8)) return 0.5;
    float c = nu - mu * mu_s;
    return clamp(c * c / den, 0.0, 1.0);
}

#ifdef CM_ATMOSPHERE_TABLE
// Part `part` of a width x height table at uv, bilinear with clamp to edge (GL_LINEAR).
vec3 cmi_atmosphere_table_bilinear(int part, int w, int h, vec2 uv) {
    float x = uv.x * float(w) - 0.5;
    float y = uv.y * float(h) - 0.5;
    int x0 = cmi_floor_to_int(x, 0, w - 2);
    int y0 = cmi_floor_to_int(y, 0, h - 2);
    float fx = cm_saturate(x - float(x0));
    float fy = cm_saturate(y - float(y0));
    vec3 bottom = CM_ATMOSPHERE_TABLE(part, x0, y0) * (1.0 - fx) + CM_ATMOSPHERE_TABLE(part, x0 + 1, y0) * fx;
    vec3 upper = CM_ATMOSPHERE_TABLE(part, x0, y0 + 1) * (1.0 - fx) + CM_ATMOSPHERE_TABLE(part, x0 + 1, y0 + 1) * fx;
    return bottom * (1.0 - fy) + upper * fy;
}

// The sky's irradiance on the ground for the sun's zenith cosine mu_s there: the ground
// part's w texels read linearly by the LUT's column coordinate.
vec3 cmi_atmosphere_ground_irradiance_at(CmAtmosphere air, int w, float mu_s) {
    if (w < 2) return w == 1 ? CM_ATMOSPHERE_TABLE(CM_ATMOSPHERE_TABLE_GROUND, 0, 0) : vec3(0.0);
    float x = cm_atmosphere_multiple_scattering_lut_uv(air, 0.0, mu_s, vec2(float(w), 1.0)).x * float(w) - 0.5;
    int x0 = cmi_floor_to_int(x, 0, w - 2);
    float fx = cm_saturate(x - float(x0));
    return CM_ATMOSPHERE_TABLE(CM_ATMOSPHERE_TABLE_GROUND, x0, 0) * (1.0 - fx) +
           CM_ATMOSPHERE_TABLE(CM_ATMOSPHERE_TABLE_GROUND, x0 + 1, 0) * fx;
}

// What the table's field scatters into a ray of zenith cosine cos_view_zenith at (altitude,
// cos_sun_zenith); cos2_azimuth: the squared cosine of the view's azimuth from the sun's
// (atmosphere.hpp's detail::atmosphere_table_source).
vec3 cmi_atmosphere_table_source(CmAtmosphere air, CmAtmosphereTable ms, float altitude, float cos_sun_zenith,
                                 float cos_view_zenith, float cos2_azimuth) {
    vec2 uv = cm_atmosphere_multiple_scattering_lut_uv(air, altitude, cos_sun_zenith, vec2(float(ms.width), float(ms.height)));
    vec3 psi = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_PSI, ms.width, ms.height, uv);
    if (ms.parts < 2) return cm_atmosphere_scattering_coefficient(air, altitude) * psi;
    vec3 b = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_VERTICAL, ms.width, ms.height, uv);
    if (ms.parts < 3) return cm_atmosphere_multiple_scattering_source(air, altitude, psi, b, cos_view_zenith);
    float h = max(altitude, 0.0);
    float mu2 = clamp(cos_view_zenith * cos_view_zenith, 0.0, 1.0);
    float c2 = clamp(cos2_azimuth, 0.0, 1.0);
    vec3 along = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_ALONG, ms.width, ms.height, uv);
    vec3 horizontal = along * c2 + (psi - b - along) * (1.0 - c2);
    vec3 rayleigh = air.rayleigh_scattering * exp(-h / air.rayleigh_scale_height) *
                    (0.75 * (psi + horizontal * (1.0 - mu2) + b * mu2));
    vec3 aerosol = psi;
    // With the sun below this point's horizon the field is lit from one side of the sky only:
    // isotropic there (atmosphere.hpp says why).
    if (cos_sun_zenith > 0.0) {
        float m = clamp(cos_view_zenith, -1.0, 1.0);
        float x = m < 0.0 ? -sqrt(-m) : sqrt(m);
        float fj = (x + 1.0) * 0.5 * float(CM_ATMOSPHERE_AEROSOL_NODES - 1);
        int j0 = cmi_floor_to_int(fj, 0, CM_ATMOSPHERE_AEROSOL_NODES - 2);
        float fr = cm_saturate(fj - float(j0));
        aerosol = cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_AEROSOL + j0, ms.width, ms.height, uv) * (1.0 - fr) +
                  cmi_atmosphere_table_bilinear(CM_ATMOSPHERE_TABLE_AEROSOL + j0 + 1, ms.width, ms.height, uv) * fr;
    }
    return rayleigh + aerosol * (air.mie_scattering * exp(-h / air.mie_scale_height));
}

// The light the air scatters into the view ray between the camera (at `altitude`) and
// `distance` metres along it, or the end of the air or the ground if nearer, with the
// transmittance over the same stretch (atmosphere_inscatter: its steps t_i = D (i/steps)^2,
// the sun's single scattering and the table's field per step). Directions are unit vectors in
// the camera's frame with +y up. Per unit sun illuminance. Cost per step: one sun
// transmittance of sun_steps steps and, with ms.parts 3, 20 table reads of 4 texels.
CmAtmosphereSegment cm_atmosphere_inscatter(CmAtmosphere air, CmAtmosphereTable ms, float altitude, vec3 view_dir, vec3 sun_dir,
                                            float distance, int steps, int sun_steps) {
    int n = max(steps, 1);
    float h = clamp(altitude, 0.0, air.top_radius - air.bottom_radius);
    float r = air.bottom_radius + h;
    float mu = clamp(view_dir.y, -1.0, 1.0);
    float mu_s = clamp(sun_dir.y, -1.0, 1.0);
    float nu = clamp(dot(view_dir, sun_dir), -1.0, 1.0);
    float D = clamp(distance, 0.0, cmi_atmosphere_ray_length(air, h, mu));
    bool use_ms = ms.parts > 0 && ms.width >= 2 && ms.height >= 2;
    float cos2_azimuth = cmi_atmosphere_cos2_azimuth(mu, mu_s, nu);
    CmAtmosphereSegment out_segment = CmAtmosphereSegment(vec3(1.0), vec3(0.0));
    for (int i = 0; i < n; ++i) {
        float x0 = float(i) / float(n);
        float x1 = float(i + 1) / float(n);
        float t0 = D * x0 * x0;
        float t1 = D * x1 * x1;
        float ds = t1 - t0;
        float t = 0.5 * (t0 + t1);
        float hy = cm_altitude_along_ray(h, mu, air.bottom_radius, t);
        float mu_sy = clamp((r * mu_s + t * nu) / (air.bottom_radius + hy), -1.0, 1.0);
        vec3 sigma_t = cm_atmosphere_extinction(air, hy);
        vec3 source = cm_atmosphere_scattering(air, hy, nu) * cm_atmosphere_transmittance(air, hy, mu_sy, sun_steps);
        if (use_ms)
            source += cmi_atmosphere_table_source(air, ms, hy, mu_sy, clamp((r * mu + t) / (air.bottom_radius + hy), -1.0, 1.0),
                                                  cos2_azimuth);
        vec3 step_t = cm_beer_lambert(sigma_t * ds);
        vec3 integral = cm_one_minus_exp_neg_over_x(sigma_t * ds) * ds;
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
vec3 cm_atmosphere_sky_radiance(CmAtmosphere air, CmAtmosphereTable ms, float altitude, vec3 view_dir, vec3 sun_dir, int steps,
                                int sun_steps) {
    CmAtmosphereSegment seg = cm_atmosphere_inscatter(air, ms, altitude, view_dir, sun_dir, 3.0e38, steps, sun_steps);
    float h = clamp(altitude, 0.0, air.top_radius - air.bottom_radius);
    float mu = clamp(view_dir.y, -1.0, 1.0);
    if (!cm_atmosphere_ray_hits_ground(air, h, mu)) return seg.radiance;
    float t = cmi_atmosphere_ray_length(air, h, mu);
    float mu_sg = clamp(((air.bottom_radius + h) * sun_dir.y + t * dot(view_dir, sun_dir)) / air.bottom_radius, -1.0, 1.0);
    vec3 ground = cmi_atmosphere_lit_ground(air, mu_sg, sun_steps);
    if (ms.ground_width > 0) ground += cmi_atmosphere_ground_irradiance_at(air, ms.ground_width, mu_sg) * (air.ground_albedo * CM_INV_PI);
    return seg.radiance + seg.transmittance * ground;
}
#endif  // CM_ATMOSPHERE_TABLE

// EV100 of a camera (f-number, shutter seconds, ISO), of an average luminance, and the exposure.
float cm_ev100_from_camera(float aperture, float shutter_time, float iso) {
    return log2(aperture * aperture / shutter_time * 100.0 / iso);
}
float cm_ev100_from_luminance(float average_luminance) { return log2(average_luminance * 100.0 / 12.5); }
float cm_exposure_from_ev100(float ev100) { return 1.0 / (1.2 * exp2(ev100)); }

#endif  // CM_ATMOSPHERE_GLSL
