// sky_tables.frag: the physical sky's tables, built on the GPU as Hillaire 2020 (and UE5)
// builds them: one table node per fragment, from cloudmath's GLSL twins of
// atmosphere_sky_radiance, atmosphere_inscatter and atmosphere_sun_illuminance, which read Earth's
// multiple-scattering table (physical_air's 32 x 32 refined LUT, made once on the CPU and
// uploaded once) through CM_ATMOSPHERE_TABLE. physical_sky.cpp and scene.cpp make the same nodes
// on the CPU for the CPU renderer (make_sky_view, make_table, compute_physical_sky), which
// test_cloud_renderer compares them with.
//
// The hosts (sky_tables_gl.cpp; the web demo's physical_sky.js, through web/build.mjs's
// sky_tables_frag.js) prepend #version and draw one full-screen triangle per table
// (u_kind, a uniform: the three draws share one program and cost microseconds to switch):
//   0 a sky-view table (physical_sky.hpp's sky_view_table): pixel (az, el) is node (az, el);
//   1 the aerial-perspective table (haze_table): pixel (d + n_d az, el) is node (d, az, el);
//   2 the sky's values (scene.cpp's physical_sky_samples), one row: pixels 0-7 the sun on the
//     clouds by height in the layer, 8 the sun at the band's middle (the drawn disc), 9 the sun
//     at the camera (the ground), 10 the zenith, 11-18 the horizon 2 degrees up every 45
//     degrees of azimuth, 19 the band (bottom, top; the web demo's far shadow takes its range).
// Tables take the sun at azimuth 0 (they are symmetric about its vertical plane: only its
// elevation matters); the values take it as it is.

uniform highp sampler2D u_table;  // the table's parts stacked: part p at rows 32 p .. 32 p + 31 (RGB32F)
uniform int u_kind;               // 0 a sky-view table, 1 the aerial-perspective table, 2 the values
uniform ivec3 u_size;             // sky view: n_az, n_el; haze: n_d, n_az, n_el
uniform float u_altitude;         // the table's altitude, or the camera's (m)
uniform vec3 u_sun;               // unit, toward the sun
uniform float u_max_distance;     // haze: the last distance node (m)
uniform float u_layer_bottom, u_layer_top;  // values: the layer (m)
uniform float u_cloud_type, u_type_spread;   // ... and what its band comes from (scene.hpp's scene)
uniform int u_shape;                         // ... 0 classic, 1 detailed

layout(location = 0) out vec4 out_color;

vec3 cr_sky_table(int part, int x, int y);
#define CM_ATMOSPHERE_TABLE cr_sky_table
#include "cloudmath.glsl"

vec3 cr_sky_table(int part, int x, int y) { return texelFetch(u_table, ivec2(x, y + 32 * part), 0).rgb; }

// physical_sky.cpp's node_direction: node (az, el) of n_az x n_el directions, the sun at
// azimuth 0 (sky_coordinates' inverse: the zenith cosine crowded at the horizon).
vec3 cr_node_direction(int az, int el, int n_az, int n_el) {
    float s = 2.0 * float(el) / float(n_el - 1) - 1.0;  // sign(mu) sqrt|mu|
    float mu = s < 0.0 ? -s * s : s * s;
    float sin_zenith = sqrt(max(1.0 - mu * mu, 0.0));
    float phi = CM_PI * float(az) / float(n_az - 1);
    return vec3(sin_zenith * cos(phi), mu, sin_zenith * sin(phi));
}

// scene.cpp's cloud_band: the altitudes outside which the field has no density, the type's
// range or, for the detailed shape, the union over the types the weather map can give.
vec2 cr_cloud_band() {
    vec2 range = cm_height_range_for_type(u_cloud_type);
    if (u_shape == 1) {
        // The range's ends are piecewise linear in the type with a kink at 0.5: its extremes
        // over an interval are at the interval's ends or at 0.5.
        float lo = clamp(u_cloud_type - 0.5 * u_type_spread, 0.0, 1.0), hi = clamp(u_cloud_type + 0.5 * u_type_spread, 0.0, 1.0);
        vec2 a = cm_height_range_for_type(lo), b = cm_height_range_for_type(hi), c = cm_height_range_for_type(clamp(0.5, lo, hi));
        range = vec2(min(range.x, min(a.x, min(b.x, c.x))), max(range.y, max(a.y, max(b.y, c.y))));
        range.x *= cm_cloud_top_fraction(0.0);  // a lower top compresses the profile down
    }
    return range * (u_layer_top - u_layer_bottom) + u_layer_bottom;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    CmAtmosphere air = cm_earth_atmosphere();
    // physical_air's table: the refined LUT with every part, no ground irradiance.
    CmAtmosphereTable table = CmAtmosphereTable(32, 32, 3, 0);
    const float lux = 128000.0;  // physical_sky.hpp's sun_lux: radiance in cd/m^2
    vec3 L;
    if (u_kind == 0) {
        L = lux * cm_atmosphere_sky_radiance(air, table, u_altitude, cr_node_direction(p.x, p.y, u_size.x, u_size.y), u_sun, 32, 32);
    } else if (u_kind == 1) {
        int k = p.x % u_size.x, az = p.x / u_size.x;
        float x = float(k) / float(u_size.x - 1);
        vec3 dir = cr_node_direction(az, p.y, u_size.y, u_size.z);
        L = k == 0 ? vec3(0.0) : lux * cm_atmosphere_inscatter(air, table, u_altitude, dir, u_sun, u_max_distance * x * x, 16, 16).radiance;
    } else if (p.x < 8) {
        float altitude = u_layer_bottom + (u_layer_top - u_layer_bottom) * float(p.x) / 7.0;
        L = cm_atmosphere_sun_illuminance(air, altitude, u_sun.y, vec3(lux));
    } else if (p.x == 8) {
        vec2 band = cr_cloud_band();
        L = cm_atmosphere_sun_illuminance(air, 0.5 * (band.x + band.y), u_sun.y, vec3(lux));
    } else if (p.x == 9) {
        L = cm_atmosphere_sun_illuminance(air, u_altitude, u_sun.y, vec3(lux));
    } else if (p.x == 10) {
        L = lux * cm_atmosphere_sky_radiance(air, table, u_altitude, vec3(0.0, 1.0, 0.0), u_sun, 32, 32);
    } else if (p.x == 19) {
        L = vec3(cr_cloud_band(), 0.0);
    } else {
        float az = float(p.x - 11) * (45.0 * CM_PI / 180.0), e = 2.0 * CM_PI / 180.0;
        L = lux * cm_atmosphere_sky_radiance(air, table, u_altitude, vec3(cos(az) * cos(e), sin(e), sin(az) * cos(e)), u_sun, 32, 32);
    }
    out_color = vec4(L, 1.0);
}
