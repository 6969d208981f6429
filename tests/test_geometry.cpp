// Tests of geometry.hpp: ray/sphere roots against quad-precision references, the float
// accuracy of the altitude form at Earth radius against the textbook forms (REFERENCES.md
// table), cloud-layer segments from below, inside and above, tangent rays, and a property
// sweep that every returned stretch really lies inside the layer.
#include <cloudmath/geometry.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;
using cm_test::quad;

namespace {

const ld R_EARTH = 6371e3L;

// Roots of |(0, R + h) + t d|^2 = (R + H)^2 in quad precision, textbook formula (the
// cancellation of c = r^2 - (R + H)^2 costs 14 of quad's 34 digits at Earth scale).
struct roots_q {
    bool hit;
    ld t0, t1;
};
roots_q altitude_roots_ref(ld h, ld mu, ld R, ld H) {
    const quad r = quad(R) + quad(h), rs = quad(R) + quad(H), m = mu;
    const quad b = r * m;
    const quad c = r * r - rs * rs;
    const quad disc = b * b - c;
    if (disc < 0) return {false, -1, -1};
    const quad sq = cm_test::sqrt_q(disc);
    return {true, ld(-b - sq), ld(-b + sq)};
}

// First root at t >= 0, or -1.
ld first_positive(ld t0, ld t1) { return t0 >= 0 ? t0 : (t1 >= 0 ? t1 : -1); }

// Altitude of the point at distance t (quad reference).
ld altitude_ref(ld h, ld mu, ld R, ld t) {
    const quad r = quad(R) + quad(h), tq = t, m = mu;
    const quad x = r + tq * m;                       // along up
    const quad y = tq * cm_test::sqrt_q(1 - m * m);  // sideways
    return ld(cm_test::sqrt_q(x * x + y * y) - quad(R));
}

// The textbook float forms the library replaces.
float naive_first_root(float h, float mu, float R, float H) {
    // Sphere centred at the origin, ray from (0, R + h, 0).
    const float oy = R + h, dy = mu, dx = std::sqrt(std::fmax(0.0f, 1.0f - mu * mu));
    const float b = oy * dy;
    const float c = oy * oy - (R + H) * (R + H);
    const float disc = b * b - c;
    if (disc < 0) return -1;
    const float sq = std::sqrt(disc);
    (void)dx;
    const float t0 = -b - sq, t1 = -b + sq;
    return t0 >= 0 ? t0 : t1;
}
float naive_q_first_root(float h, float mu, float R, float H) {
    const float r = R + h, b = r * mu, c = r * r - (R + H) * (R + H), disc = b * b - c;
    if (disc < 0) return -1;
    const float sq = std::sqrt(disc);
    const float q = b >= 0 ? -(b + sq) : (sq - b);
    const float t0 = std::fmin(q, c / q), t1 = std::fmax(q, c / q);
    return t0 >= 0 ? t0 : t1;
}

std::vector<float> mu_grid_horizon_dense() {
    std::vector<float> mus;
    for (int i = -1000; i <= 1000; ++i) mus.push_back(float(i) / 1000.0f);
    for (int k = 2; k <= 7; ++k)
        for (int j = 1; j <= 9; ++j) {
            mus.push_back(float(j) * std::pow(10.0f, float(-k)));
            mus.push_back(-float(j) * std::pow(10.0f, float(-k)));
        }
    return mus;
}

}  // namespace

TEST_CASE_TEMPLATE("ray_sphere_intersect: stable roots, inside, behind, miss, tangent, centre", T, float, double) {
    using v3 = glm::vec<3, T>;
    const v3 c(T(0));
    glm::vec<2, T> t = ray_sphere_intersect(v3(T(0), T(0), T(-5)), v3(T(0), T(0), T(1)), c, T(1));
    CHECK(t.x == T(4));
    CHECK(t.y == T(6));
    t = ray_sphere_intersect(v3(T(0)), v3(T(1), T(0), T(0)), c, T(2));  // from the centre
    CHECK(t.x == T(-2));
    CHECK(t.y == T(2));
    t = ray_sphere_intersect(v3(T(0), T(0), T(5)), v3(T(0), T(0), T(1)), c, T(1));  // behind
    CHECK(t.x == T(-6));
    CHECK(t.y == T(-4));
    t = ray_sphere_intersect(v3(T(0), T(2), T(-5)), v3(T(0), T(0), T(1)), c, T(1));  // miss
    CHECK(t == glm::vec<2, T>(T(-1)));
    t = ray_sphere_intersect(v3(T(0), T(1), T(-5)), v3(T(0), T(0), T(1)), c, T(1));  // tangent
    CHECK(t.x == doctest::Approx(T(5)));
    CHECK(t.y == doctest::Approx(T(5)));
    t = ray_sphere_intersect(v3(T(1), T(0), T(0)), v3(T(0), T(1), T(0)), c, T(1));  // tangent at origin
    CHECK(t == glm::vec<2, T>(T(0)));
    // Haines et al.'s case: a small sphere far away. Reference in quad precision.
    const T dist = T(1e5), rad = T(1);
    const v3 o(T(0.3), T(0.2), -dist), d = glm::normalize(v3(T(0), T(0), T(1)));
    t = ray_sphere_intersect(o, d, c, rad);
    const quad f2 = quad(ld(T(0.3))) * quad(ld(T(0.3))) + quad(ld(T(0.2))) * quad(ld(T(0.2)));
    const quad half_chord = cm_test::sqrt_q(quad(1) - f2);
    CHECK(cm_test::rel_err(t.x, ld(quad(ld(dist)) - half_chord)) <= 4 * cm_test::eps<T>());
    CHECK(cm_test::rel_err(t.y - dist, ld(half_chord)) <= (std::is_same_v<T, float> ? 0.02L : 1e-9L));
    if constexpr (cm_test::ieee_build) {
        const glm::vec<2, T> n = ray_sphere_intersect(v3(cm_test::make_nan<T>()), d, c, rad);
        CHECK(cm_test::nan_bits(n.x));  // documented: NaN input, NaN distances
    }
}

TEST_CASE("ray_sphere_intersect: float at Earth radius, within 1 m of the exact roots of the same inputs") {
    // A camera 1.8 m above a 6371 km sphere, at points all over it (so every component of the
    // position is rounded), rays from the zenith to the horizon; the sphere 1500 m above the
    // ground. Reference: the quadratic in long double on the same float inputs (the input's
    // own rounding is not the formula's error). The textbook quadratic in float, for scale.
    const float R = 6371000.0f, r = R + 1500.0f;
    ld worst = 0, worst_textbook = 0, worst_haines = 0;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j <= 24; ++j) {
            const double lon = 0.37 + 0.71 * i, lat = -1.2 + 0.1 * (i % 25);
            const glm::dvec3 up(std::cos(lat) * std::cos(lon), std::sin(lat), std::cos(lat) * std::sin(lon));
            const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), up));
            const double elevation = 1.5707963 * double(j) / 24.0;
            const glm::vec3 o(up * (double(R) + 1.8)), d(glm::normalize(up * std::sin(elevation) + east * std::cos(elevation)));
            const ld b = ld(o.x) * d.x + ld(o.y) * d.y + ld(o.z) * d.z;
            const ld dd = ld(d.x) * d.x + ld(d.y) * d.y + ld(d.z) * d.z;
            const ld c = ld(o.x) * o.x + ld(o.y) * o.y + ld(o.z) * o.z - ld(r) * ld(r);
            const ld exit = (-b + std::sqrt(b * b - dd * c)) / dd;  // from inside the sphere
            const glm::vec2 t = ray_sphere_intersect(o, d, glm::vec3(0.0f), r);
            worst = std::max(worst, std::fabs(ld(t.y) - exit));
            const float fb = glm::dot(o, d), fc = glm::dot(o, o) - r * r;
            worst_textbook = std::max(worst_textbook, std::fabs(ld(-fb + std::sqrt(fb * fb - fc)) - exit));
            const glm::vec3 perp = o - fb * d;  // Haines et al.'s discriminant alone (the form before)
            worst_haines = std::max(worst_haines, std::fabs(ld(-fb + std::sqrt(r * r - glm::dot(perp, perp))) - exit));
        }
    MESSAGE("worst distance error " << double(worst) << " m; the textbook quadratic " << double(worst_textbook)
                                     << " m; Haines' discriminant alone " << double(worst_haines) << " m");
    // -ffast-math may simplify the exact-product error terms away (documented): then the
    // result is the plain quadratic's, which only the IEEE builds improve on.
    if constexpr (cm_test::ieee_build) {
        CHECK(worst <= 1.0L);
        CHECK(worst_textbook > 4.0L * worst);
    } else {
        CHECK(worst <= 2.0L * worst_textbook);
    }
}

TEST_CASE("ray_sphere_intersect_altitude: float accuracy at Earth radius against the textbook forms") {
    struct scene { float h, H; ld budget; const char* name; bool textbook_fails; };
    // Budgets: the measured worst plus margin; REFERENCES.md reports 2.4e-7, 2.1e-7 and
    // 1.1e-6 for its altitude form and 2e-4 to 1e-3 for the textbook one.
    for (scene s : {scene{1.8f, 1500.0f, 5e-7L, "1.8 m -> 1500 m", true}, scene{1000.0f, 1500.0f, 5e-7L, "1000 m -> 1500 m", true},
                    scene{10000.0f, 4000.0f, 1e-6L, "10 km -> 4000 m", false}, scene{400e3f, 4000.0f, 1e-6L, "400 km -> 4000 m", false}}) {
        ld worst = 0, worst_naive = 0, worst_naive_q = 0;
        float worst_mu = 0;
        for (float mu : mu_grid_horizon_dense()) {
            const roots_q ref = altitude_roots_ref(s.h, mu, R_EARTH, s.H);
            if (!ref.hit) continue;
            const ld t_ref = first_positive(ref.t0, ref.t1);
            if (t_ref < 0) continue;
            // Grazing rays from above are ill-conditioned for any formula: skip the band
            // where the two roots are closer than 1% of their distance.
            if (s.h > s.H && ref.t1 - ref.t0 < 0.01L * ref.t0) continue;
            const glm::vec2 t = ray_sphere_intersect_altitude(s.h, mu, float(R_EARTH), s.H);
            const float ours = t.x >= 0 ? t.x : t.y;
            const ld e = cm_test::rel_err(ours, t_ref);
            if (e > worst) { worst = e; worst_mu = mu; }
            worst_naive = std::fmax(worst_naive, cm_test::rel_err(naive_first_root(s.h, mu, float(R_EARTH), s.H), t_ref));
            worst_naive_q = std::fmax(worst_naive_q, cm_test::rel_err(naive_q_first_root(s.h, mu, float(R_EARTH), s.H), t_ref));
        }
        MESSAGE(std::string(s.name) << ": max relative error of the first root in float: altitude form " << double(worst)
                       << " (mu = " << worst_mu << "), textbook " << double(worst_naive) << ", textbook + q " << double(worst_naive_q));
        CHECK(worst <= s.budget);
        if (s.textbook_fails) CHECK(worst_naive > 1e-4L);  // the test would catch the textbook form
    }
}

TEST_CASE_TEMPLATE("ray_sphere_intersect_altitude: both roots, misses and clamped cos_zenith", T, float, double) {
    const T R = T(6371e3);
    // Straight up from 1.8 m to the 1500 m sphere: 1498.2 exactly representable? close.
    glm::vec<2, T> t = ray_sphere_intersect_altitude(T(1.8), T(1), R, T(1500));
    CHECK(cm_test::rel_err(t.y, 1500 - ld(T(1.8))) <= 4 * cm_test::eps<T>());
    CHECK(t.x < T(0));
    // Looking down from 10 km at the 4 km sphere: enter at 6 km.
    t = ray_sphere_intersect_altitude(T(10000), T(-1), R, T(4000));
    CHECK(cm_test::rel_err(t.x, 6000) <= 4 * cm_test::eps<T>());
    CHECK(cm_test::rel_err(t.y, 6000 + 2 * (ld(R) + 4000)) <= 4 * cm_test::eps<T>());
    // Looking up from above: the sphere below is behind the origin (both roots negative).
    t = ray_sphere_intersect_altitude(T(10000), T(0.5), R, T(4000));
    CHECK(t.y < T(0));
    // Horizontal from above: the line misses the lower sphere.
    t = ray_sphere_intersect_altitude(T(10000), T(0), R, T(4000));
    CHECK(t == glm::vec<2, T>(T(-1)));
    CHECK(ray_sphere_intersect_altitude(T(100), T(3), R, T(500)) == ray_sphere_intersect_altitude(T(100), T(1), R, T(500)));
    // Horizontal ray at the sphere's own altitude: tangent at the origin, both roots 0.
    t = ray_sphere_intersect_altitude(T(500), T(0), R, T(500));
    CHECK(t == glm::vec<2, T>(T(0)));
}

TEST_CASE_TEMPLATE("cloud_layer_segment: below, inside, above, ground, tangent and degenerate layers", T, float, double) {
    const T R = T(6371e3), lo = T(1500), hi = T(4000);
    auto seg = [&](T h, T mu) { return cloud_layer_segment(h, mu, R, lo, hi); };
    auto near = [](T got, ld want) { return cm_test::rel_err(got, want) <= 8 * cm_test::eps<T>(); };
    // Below, looking up.
    glm::vec<2, T> s = seg(T(1.8), T(1));
    CHECK(near(s.x, 1500 - ld(T(1.8))));
    CHECK(near(s.y, 4000 - ld(T(1.8))));
    // Below, horizontal: the long way through the bottom sphere (about 138 km).
    s = seg(T(1.8), T(0));
    const ld r = ld(R) + ld(T(1.8));
    CHECK(cm_test::rel_err(s.x, std::sqrt((ld(R) + 1500) * (ld(R) + 1500) - r * r)) <= 1e-6L);
    CHECK(cm_test::rel_err(s.y, std::sqrt((ld(R) + 4000) * (ld(R) + 4000) - r * r)) <= 1e-6L);
    // Below, looking down: the ground comes first.
    s = seg(T(1.8), T(-0.1));
    CHECK(s.y <= s.x);
    // On the ground looking exactly horizontally: grazes the ground, reaches the layer.
    s = seg(T(0), T(0));
    CHECK(s.x > T(1.3e5));
    CHECK(s.y > s.x);
    // Inside.
    s = seg(T(2000), T(1));
    CHECK(s.x == T(0));
    CHECK(near(s.y, 2000));
    s = seg(T(2000), T(-1));
    CHECK(s.x == T(0));
    CHECK(near(s.y, 500));
    s = seg(T(2000), T(0));  // horizontal: leaves through the top sphere
    CHECK(s.x == T(0));
    CHECK(cm_test::rel_err(s.y, std::sqrt((ld(R) + 4000) * (ld(R) + 4000) - (ld(R) + 2000) * (ld(R) + 2000))) <= 1e-6L);
    s = seg(T(1500), T(0));  // at the bottom, horizontal: the tangent does not stop it
    CHECK(s.y > T(1e5));
    s = seg(T(1500), T(-0.5));  // at the bottom, looking down: empty
    CHECK(s.y <= s.x);
    s = seg(T(4000), T(0.5));  // at the top, looking up: empty
    CHECK(s.y <= s.x);
    // Above.
    s = seg(T(10000), T(-1));
    CHECK(near(s.x, 6000));
    CHECK(near(s.y, 8500));
    s = seg(T(10000), T(1));
    CHECK(s == glm::vec<2, T>(T(-1)));
    s = seg(T(400e3), T(-1));  // from orbit
    CHECK(near(s.x, 396000));
    CHECK(near(s.y, 398500));
    // Above, grazing only the top of the layer: enters and leaves through the top sphere.
    const T mu_graze = T(-0.0318);  // from 5 km: tangent to the 4000 m sphere near -0.0177, to 1500 m near -0.0331
    s = seg(T(5000), mu_graze);
    const roots_q top = altitude_roots_ref(5000, ld(mu_graze), ld(R), 4000);
    CHECK(top.hit);
    CHECK(cm_test::rel_err(s.x, top.t0) <= 1e-5L);
    CHECK(cm_test::rel_err(s.y, top.t1) <= 1e-5L);
    // Bad input.
    CHECK(seg(T(-50), T(1)) == seg(T(0), T(1)));                                      // below ground -> ground
    CHECK(cloud_layer_segment(T(1.8), T(1), R, hi, lo) == seg(T(1.8), T(1)));           // swapped layer
    const glm::vec<2, T> z = cloud_layer_segment(T(1.8), T(1), R, T(2000), T(2000));   // zero thickness
    CHECK(z.y <= z.x);
    CHECK(cloud_layer_segment(T(100), T(1.5), R, lo, hi) == seg(T(100), T(1)));
    // Denormal cos_zenith is horizontal.
    CHECK(seg(T(2000), std::numeric_limits<T>::denorm_min()).y == doctest::Approx(seg(T(2000), T(0)).y));
    if constexpr (cm_test::ieee_build) {  // documented: NaN never gives a non-empty stretch
        const T nan = cm_test::make_nan<T>();
        for (const glm::vec<2, T>& n : {cloud_layer_segment(nan, T(0.5), R, lo, hi), cloud_layer_segment(T(1.8), nan, R, lo, hi),
                                        cloud_layer_segment(T(1.8), T(0.5), nan, lo, hi), cloud_layer_segment(T(1.8), T(0.5), R, nan, hi),
                                        cloud_layer_segment(T(1.8), T(0.5), R, lo, nan), cloud_layer_segment(T(5000), nan, R, lo, hi)})
            CHECK_FALSE(n.y > n.x);
        CHECK(cm_test::nan_bits(ray_sphere_intersect_altitude(T(1.8), nan, R, T(1500)).x));
    }
}

TEST_CASE_TEMPLATE("cloud_layer_segment property sweep: every returned stretch lies in the layer", T, float, double) {
    const T R = T(6371e3), lo = T(1500), hi = T(4000);
    // Relative tolerance on altitudes of points near the ends (the segment's ends are roots
    // computed in T): a few metres in float over 1e5 m rays, micrometres in double.
    const ld tol_rel = std::is_same_v<T, float> ? 2e-6L : 1e-13L;
    int segments = 0, empties = 0;
    bool finite = true;
    for (T h : {T(0), T(1.8), T(500), T(1500), T(1501), T(2750), T(3999), T(4000), T(4001), T(10000), T(400e3)}) {
        for (int i = -400; i <= 400; ++i) {
            const T mu = T(i) / T(400);
            const glm::vec<2, T> s = cloud_layer_segment(h, mu, R, lo, hi);
            finite = finite && cm_test::finite_bits(s.x) && cm_test::finite_bits(s.y);
            if (!(s.y > s.x)) { ++empties; continue; }
            ++segments;
            INFO("h = " << h << ", mu = " << mu << ", segment " << s.x << " .. " << s.y);
            CHECK(s.x >= T(0));
            const ld slack = tol_rel * ld(s.y) + 1e-9L;
            // Interior points are inside the layer (above the ground).
            for (int k = 1; k < 8; ++k) {
                const ld t = ld(s.x) + (ld(s.y) - ld(s.x)) * k / 8;
                const ld a = altitude_ref(h, mu, ld(R), t);
                CHECK(a >= ld(lo) - slack * 4);
                CHECK(a <= ld(hi) + slack * 4);
            }
            // The ends are on the layer's boundary (or the start is the camera inside it).
            const ld a0 = altitude_ref(h, mu, ld(R), s.x), a1 = altitude_ref(h, mu, ld(R), s.y);
            if (s.x > T(0)) CHECK((std::fabs(a0 - ld(lo)) <= slack || std::fabs(a0 - ld(hi)) <= slack));
            CHECK((std::fabs(a1 - ld(lo)) <= slack || std::fabs(a1 - ld(hi)) <= slack));
        }
    }
    MESSAGE(cm_test::type_name<T>() << ": " << segments << " segments and " << empties << " empty rays checked");
    CHECK(finite);
    CHECK(segments > 3000);
}

TEST_CASE_TEMPLATE("altitude_along_ray: accurate in float where |p| - R loses metres", T, float, double) {
    const T R = T(6371e3);
    ld worst = 0;
    ld worst_naive = 0;
    for (T h : {T(1.8), T(1000), T(3000)})
        for (T mu : {T(-0.001), T(0), T(0.01), T(0.2), T(1)})
            for (T t : {T(10), T(1000), T(20000), T(100000)}) {
                const ld ref = altitude_ref(h, mu, ld(R), t);
                if (ref < 0) continue;
                // In units of the result's ulp, with a millimetre floor near the ground.
                worst = std::fmax(worst, std::fabs(altitude_along_ray(h, mu, R, t) - ref) / (cm_test::eps<T>() * std::fmax(std::fabs(ref), 1e4L)));
                // Textbook: build the point and subtract the radius.
                const T s = std::sqrt(std::fmax(T(0), T(1) - mu * mu));
                const glm::vec<3, T> p(t * s, R + h + t * mu, T(0));
                worst_naive = std::fmax(worst_naive, std::fabs(ld(glm::length(p) - R) - ref));
            }
    MESSAGE(cm_test::type_name<T>() << " altitude_along_ray: max altitude error: ours " << double(worst) << " eps relative (1e4 m floor), |p| - R " << double(worst_naive) << " m absolute");
    CHECK(worst <= 8);
    if constexpr (std::is_same_v<T, float>) CHECK(worst_naive > 0.1L);
    CHECK(altitude_along_ray(T(1000), T(1), R, T(0)) == doctest::Approx(T(1000)));
}

TEST_CASE_TEMPLATE("height_fraction: saturated linear fraction, degenerate layer is a step", T, float, double) {
    static_assert(height_fraction(T(2750), T(1500), T(4000)) == T(0.5), "constexpr");
    CHECK(height_fraction(T(1500), T(1500), T(4000)) == T(0));
    CHECK(height_fraction(T(4000), T(1500), T(4000)) == T(1));
    CHECK(height_fraction(T(100), T(1500), T(4000)) == T(0));
    CHECK(height_fraction(T(1e9), T(1500), T(4000)) == T(1));
    CHECK(height_fraction(T(1999), T(2000), T(2000)) == T(0));
    CHECK(height_fraction(T(2000), T(2000), T(2000)) == T(1));
    for (int i = 0; i <= 100; ++i) {
        const T a = T(1500) + T(25) * T(i);
        CHECK(cm_test::rel_err(height_fraction(a, T(1500), T(4000)), (ld(a) - 1500) / 2500) <= 4 * cm_test::eps<T>());
    }
}

TEST_CASE_TEMPLATE("point_altitude: camera-relative points at planet scale against long double", T, float, double) {
    using v3 = glm::vec<3, T>;
    const T R = T(6371000);
    for (T cam : {T(1.8), T(2700), T(7000)}) {
        CHECK(point_altitude(v3(T(0)), cam, R) == cam);  // the camera itself
        // Straight up: the camera's altitude plus the height.
        CHECK(double(point_altitude(v3(T(0), T(1500), T(0)), cam, R)) == doctest::Approx(double(cam) + 1500.0).epsilon(1e-6));
        // Anywhere: |(0, R + cam, 0) + p| - R in long double, for points up to 100 km away.
        for (const v3 p : {v3(T(100000), T(0), T(0)), v3(T(-3000), T(1200), T(40000)), v3(T(0), T(-1), T(20000)),
                           v3(T(5), T(-2), T(-7))}) {
            // |q|^2 - R^2 with y^2 - R^2 = (y - R)(y + R) taken exactly: the reference has no
            // cancellation either.
            const ld x = ld(p.x), h = ld(p.y) + ld(cam), z = ld(p.z);
            const ld excess = x * x + z * z + h * (h + 2 * ld(R));
            const ld want = excess / (std::sqrt(ld(R) * ld(R) + excess) + ld(R));
            const T got = point_altitude(p, cam, R);
            CAPTURE(double(want));
            // A few ulp of the distance (the altitude is a difference of planet-size numbers
            // taken without cancellation).
            CHECK(std::fabs(ld(got) - want) <= 8 * ld(std::numeric_limits<T>::epsilon()) * (ld(glm::length(glm::vec<3, ld>(p))) + ld(cam)));
        }
    }
    // The same as altitude_along_ray along p's direction.
    const v3 p(T(300), T(200), T(-4000));
    const T t = glm::length(p);
    CHECK(point_altitude(p, T(10), R) == altitude_along_ray(T(10), p.y / t, R, t));
}
