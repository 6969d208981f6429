// physical_sky.hpp: what the physical sky (scene.hpp's sky_model::physical) takes from
// cloudmath's atmosphere beyond the frame constants: Earth's air with its multiple-scattering
// LUT, made once, and the aerial-perspective table, the light the air scatters into a view ray
// between the camera and a cloud, by direction and distance (Hillaire 2020's aerial-perspective
// volume, here over the camera's whole sphere of directions: the sky is symmetric about the
// sun's vertical plane, so two angles and a distance).
//
// Table: nodes over the view's zenith cosine mu (c = (0.5 + 0.5 sign(mu) sqrt|mu|) (n_el - 1):
// crowded at the horizon), its azimuth from the sun's, phi in [0, pi] (c = phi / pi (n_az - 1)),
// and the distance (c = sqrt(d / max_distance) (n_d - 1), 0 at the camera); each node
// sun_lux x atmosphere_inscatter's radiance (cd/m^2). Stored as a width n_d n_az by height n_el
// image (x = d + n_d az, y = el) that clouds.frag reads with texelFetch and interpolates
// exactly as haze_lookup does.
//
// These are the CPU renderer's tables, made on the CPU. The GL renderer draws the same nodes on
// the GPU with shaders/sky_tables.frag (sky_tables_gl.hpp), within 2.5e-6 relative of these.
#ifndef CLOUD_RENDERER_PHYSICAL_SKY_HPP
#define CLOUD_RENDERER_PHYSICAL_SKY_HPP

#include <cloudmath/atmosphere.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <typeindex>
#include <utility>
#include <vector>

namespace cloud_renderer {

// The sun above the air: a white 128 klux (REFERENCES.md), so radiance comes out in cd/m^2.
inline constexpr float sun_lux = 128000.0f;

struct physical_air {
    cloudmath::atmosphere_parameters<float> air = cloudmath::earth_atmosphere<float>();
    // 32 x 32, Hillaire's size, with the orders gathered, the sky-lit ground, the field's
    // vertical and sun-azimuth moments and its aerosol field (3 passes).
    cloudmath::atmosphere_sky_luts<float> luts = cloudmath::atmosphere_make_sky_luts(air, 32, 32);
    cloudmath::atmosphere_multiple_scattering_table<float> ms = luts.table();  // points into luts
    physical_air() = default;
    physical_air(const physical_air&) = delete;  // ms would point into the original
    physical_air& operator=(const physical_air&) = delete;
};
// Earth's air and its multiple-scattering LUT, made at the first call (about 1.5 s).
const physical_air& earth_air();

struct haze_table {
    int n_d = 16, n_az = 16, n_el = 32;
    float max_distance = 160000.0f;  // metres; farther reads the last node
    std::vector<glm::vec3> texels;   // n_d n_az x n_el, row-major
};
// The CPU's physical-sky tables, kept by whoever owns this object. What the physical sky derives
// from the sun and the scene's geometry (the sky views, the aerial perspective, the far shadow,
// the sky's frame constants) costs milliseconds to tenths of a second, and renderers ask for it
// every frame. made_once<Value>(key, make) calls make() the first time `key` is asked for and
// hands out the kept value while it is among the `capacity` keys asked for last (one list per
// Value type, the least recently asked for leaves first): a sun that moves makes a new key each
// frame, so each list is bounded. Values are shared: whoever holds one keeps it after it leaves
// the list, or after this object is gone. Thread-safe (a make() may ask this object for another
// type's value: the mutex is recursive). A cpu_temporal_renderer owns one, so its tables go with
// it; the free functions (render_cpu, make_frame_constants, physical_haze...) use the
// process's, shared_cpu_sky_tables(), unless given another.
class cpu_sky_tables {
public:
    static constexpr std::size_t default_capacity = 16;
    explicit cpu_sky_tables(std::size_t capacity = default_capacity) : capacity_(capacity > 0 ? capacity : 1) {}
    cpu_sky_tables(const cpu_sky_tables&) = delete;
    cpu_sky_tables& operator=(const cpu_sky_tables&) = delete;

    template <class Value, class Make>
    std::shared_ptr<const Value> made_once(const std::vector<float>& key, Make&& make) {
        const std::lock_guard<std::recursive_mutex> lock(mutex_);
        list& kept = lists_[std::type_index(typeid(Value))];
        for (auto it = kept.begin(); it != kept.end(); ++it)
            if (it->first == key) {
                kept.splice(kept.begin(), kept, it);
                return std::static_pointer_cast<const Value>(kept.front().second);
            }
        std::shared_ptr<const Value> value = std::make_shared<const Value>(make());
        kept.emplace_front(key, value);
        if (kept.size() > capacity_) kept.pop_back();
        return value;
    }
    // How many values of type Value this object keeps now (a test's check of the bound).
    template <class Value>
    std::size_t kept() const {
        const std::lock_guard<std::recursive_mutex> lock(mutex_);
        const auto found = lists_.find(std::type_index(typeid(Value)));
        return found == lists_.end() ? 0 : found->second.size();
    }
    std::size_t capacity() const { return capacity_; }

private:
    using list = std::list<std::pair<std::vector<float>, std::shared_ptr<const void>>>;  // the last asked for first
    std::size_t capacity_;
    mutable std::recursive_mutex mutex_;
    std::map<std::type_index, list> lists_;
};
// The process's tables, for the free functions that are given none.
cpu_sky_tables& shared_cpu_sky_tables();

// The table for a camera at `camera_altitude` and a sun in direction sun_dir (camera frame,
// +y up); made once per pair and kept in `tables` (about 40 ms each).
std::shared_ptr<const haze_table> physical_haze(float camera_altitude, const glm::vec3& sun_dir,
                                                cpu_sky_tables& tables = shared_cpu_sky_tables());

// The in-scattered radiance (cd/m^2) between the camera and `distance` metres along the unit
// direction dir, interpolated from the table's 8 nearest nodes.
glm::vec3 haze_lookup(const haze_table& t, const glm::vec3& dir, const glm::vec3& sun_dir, float distance);

// The sky's radiance (cd/m^2) seen from one altitude, by direction (Hillaire 2020's sky-view
// LUT, here over the whole sphere): nodes over the zenith cosine and the azimuth from the sun's
// as the haze table's (sky_coordinates), each sun_lux x atmosphere_sky_radiance (the air to
// its end; the lit ground below the horizon). Stored as a width n_az by height n_el image that
// clouds.frag's cr_sky_view reads with texelFetch and interpolates as sky_view_lookup does.
// The physical sky's background (the table at the camera) and the light the whole-cloud truth's
// paths meet when they leave the layer through its top (the table at the top).
struct sky_view_table {
    int n_az = 64, n_el = 64;
    std::vector<glm::vec3> texels;  // n_az x n_el, row-major
};
// The table at `altitude` for a sun in direction sun_dir (camera frame, +y up); made once per
// pair and kept in `tables` (about 0.1 s each).
std::shared_ptr<const sky_view_table> physical_sky_view(float altitude, const glm::vec3& sun_dir,
                                                        cpu_sky_tables& tables = shared_cpu_sky_tables());
// How many sky-view and aerial-perspective tables this process has made on the CPU (a test's
// proof that the GL renderer builds its own on the GPU).
int cpu_sky_table_builds();
// The sky's radiance (cd/m^2) in the unit direction dir, bilinear between the 4 nearest nodes.
glm::vec3 sky_view_lookup(const sky_view_table& t, const glm::vec3& dir, const glm::vec3& sun_dir);

// The upper hemisphere of a sky-view table: its mean radiance (isotropic sky light) and the
// irradiance it gives a horizontal plane, by a 64 x 64 midpoint quadrature in the zenith
// cosine and the azimuth from the sun (the table is symmetric about the sun's vertical plane).
struct sky_hemisphere {
    glm::vec3 mean_radiance{0.0f}, irradiance{0.0f};
};
sky_hemisphere upper_hemisphere(const sky_view_table& t, const glm::vec3& sun_dir);

// The sun at azimuth 0 with sun_dir's elevation: what the tables are made for (they are
// symmetric about the sun's vertical plane; the lookups take the azimuth from the sun's).
glm::vec3 sun_at_azimuth_zero(const glm::vec3& sun_dir);

// Where a direction lies in both tables, as fractions in [0, 1]: x the azimuth from the sun's,
// phi / pi; y the zenith cosine, 0.5 + 0.5 sign(mu) sqrt|mu| (crowded at the horizon, where the
// sky changes fastest). clouds.frag's cr_sky_coordinates.
glm::vec2 sky_coordinates(const glm::vec3& dir, const glm::vec3& sun_dir);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_PHYSICAL_SKY_HPP
