// cloudmath/core.hpp: constants, saturate, remap, safe smoothstep and the stable
// exponential helpers every other module is built on.
//
// Use:      #include <cloudmath/core.hpp>
// Types:    every function is a template over the scalar type T (float or double);
//           saturate and the exponential helpers also take glm::vec<N, T> component-wise.
// Errors:   no function throws, allocates or touches global state. Inputs outside the
//           documented domain get the documented (finite) result; the clamps are written
//           with comparisons, never NaN tests, so they behave the same under -ffast-math.
// NaN/Inf:  with IEEE semantics a NaN input propagates to a NaN result (saturate and the
//           clamps pass it through); +-Inf gives the mathematical limit where one exists.
//           Under -ffast-math (-ffinite-math-only) the compiler assumes neither occurs and
//           such inputs give unspecified values (never undefined behaviour in our code).
// GLSL twin: cloudmath/glsl/core.glsl (cm_ prefix).
#ifndef CLOUDMATH_CORE_HPP
#define CLOUDMATH_CORE_HPP

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace cloudmath {

// ---------------------------------------------------------------------------------------
// Constants (variable templates so float code never promotes to double).
template <class T> inline constexpr T pi_v = T(3.141592653589793238462643383279502884L);
template <class T> inline constexpr T two_pi_v = T(6.283185307179586476925286766559005768L);
template <class T> inline constexpr T four_pi_v = T(12.56637061435917295385057353311801154L);
template <class T> inline constexpr T inv_pi_v = T(0.318309886183790671537767526745028724L);
template <class T> inline constexpr T inv_four_pi_v = T(0.079577471545947667884441881686257181L);

namespace detail {

template <class T>
inline constexpr bool is_real_v = std::is_floating_point_v<T>;

// Applies a scalar function to each component of a GLM vector; the vector overloads of
// component-wise functions are thin wrappers over the scalar reference code.
template <glm::length_t L, class T, glm::qualifier Q, class F>
inline glm::vec<L, T, Q> map(const glm::vec<L, T, Q>& v, F f) noexcept {
    glm::vec<L, T, Q> r;
    for (glm::length_t i = 0; i < L; ++i) r[i] = f(v[i]);
    return r;
}

template <glm::length_t L, class T, glm::qualifier Q, class F>
inline glm::vec<L, T, Q> map(const glm::vec<L, T, Q>& a, const glm::vec<L, T, Q>& b,
                             F f) noexcept {
    glm::vec<L, T, Q> r;
    for (glm::length_t i = 0; i < L; ++i) r[i] = f(a[i], b[i]);
    return r;
}

// Clamp written with comparisons only: NaN passes through with IEEE semantics, and nothing
// depends on NaN behaviour under -ffast-math.
template <class T>
constexpr T clamp(T x, T lo, T hi) noexcept {
    return x < lo ? lo : (x > hi ? hi : x);
}

template <class T>
constexpr T max(T a, T b) noexcept {
    return a < b ? b : a;
}

template <class T>
constexpr T min(T a, T b) noexcept {
    return b < a ? b : a;
}

template <class T>
constexpr T abs(T x) noexcept {
    return x < T(0) ? -x : x;
}

// a == b, for the comparisons that are meant to be exact (a range of width exactly 0, a
// divisor that is exactly 0): the one place our headers compare floats with ==. Users build
// with -Wfloat-equal (and clang's -Weverything), which cannot tell an intended exact compare
// from a mistaken one, so the warning is silenced here and only here. Not a <= b && a >= b:
// GCC keeps that as two compares and a branch.
#if defined(__GNUC__)  // GCC and Clang
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wfloat-equal"
#endif
template <class T>
constexpr bool exactly_equal(T a, T b) noexcept {
    return a == b;
}
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

// The next wider floating-point type: where a difference of two T cannot overflow.
template <class T> struct wider { using type = long double; };
template <> struct wider<float> { using type = double; };
template <class T> using wider_t = typename wider<T>::type;

// True when x is a NaN, read from its bits. For the float-to-int conversions only (indices,
// counts, lattice cells): a NaN that reaches one is undefined behaviour (x86 gives INT_MIN,
// and a table indexed with it is read 2^31 entries away), and -ffast-math
// (-ffinite-math-only) folds x != x, std::isnan and every comparison-based NaN test to false,
// so only the bits are a test that holds in every build. long double goes through double (a
// NaN stays a NaN).
template <class T>
inline bool is_nan_bits(T x) noexcept {
    if constexpr (std::is_same_v<T, float>) {
        std::uint32_t b;
        std::memcpy(&b, &x, sizeof b);
        return (b & 0x7fffffffu) > 0x7f800000u;
    } else {
        const double d = static_cast<double>(x);
        std::uint64_t b;
        std::memcpy(&b, &d, sizeof b);
        return (b & 0x7fffffffffffffffull) > 0x7ff0000000000000ull;
    }
}

// floor(x) as an int clamped to [lo, hi], for every x in every build: NaN gives lo, +-Inf and
// values beyond the range give the nearer end; no out-of-range value reaches the conversion.
template <class T>
inline int floor_to_int(T x, int lo, int hi) noexcept {
    if (is_nan_bits(x) || x <= T(lo)) return lo;
    if (x >= T(hi)) return hi;
    return static_cast<int>(std::floor(x));
}

}  // namespace detail

// ---------------------------------------------------------------------------------------
// saturate(x) = clamp(x, 0, 1). NaN propagates (IEEE builds). constexpr for scalars.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] constexpr T saturate(T x) noexcept {
    return detail::clamp(x, T(0), T(1));
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> saturate(const glm::vec<L, T, Q>& x) noexcept {
    return detail::map(x, [](T v) { return saturate(v); });
}

// ---------------------------------------------------------------------------------------
// remap(x, old_min, old_max, new_min, new_max)
//   = new_min + (x - old_min) / (old_max - old_min) * (new_max - new_min), unclamped.
// Source: Schneider, "The real-time volumetric cloudscapes of Horizon Zero Dawn" (2015),
// and every Nubis-style renderer since.
// Degenerate range old_min == old_max: the limit of the clamped remap, a step:
//   new_min for x < old_min, new_max for x >= old_min (finite, no division by zero).
// A range that is tiny but not zero divides by it: the unclamped result can overflow to
// +-Inf when (x - old_min) / (old_max - old_min) exceeds the type's range; use
// remap_clamped when the result must stay bounded. Reversed ranges work as expected.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] constexpr T remap(T x, T old_min, T old_max, T new_min, T new_max) noexcept {
    if (detail::exactly_equal(old_max, old_min)) return x < old_min ? new_min : new_max;
    return new_min + (x - old_min) / (old_max - old_min) * (new_max - new_min);
}

namespace detail {

// t = saturate((x - old_min) / (old_max - old_min)), the degenerate range as remap's step (0
// below old_min, 1 at and above): remap_clamped to [0, 1], which smoothstep_safe, erode,
// apply_coverage and height_fraction use directly (the same bits as remap_clamped(..., 0, 1)).
template <class T>
constexpr T remap_unit(T x, T old_min, T old_max) noexcept {
    if (detail::exactly_equal(old_max, old_min)) return x < old_min ? T(0) : T(1);
    const T big = std::numeric_limits<T>::max() / T(4);
    if (max(max(abs(x), abs(old_min)), abs(old_max)) > big) {
        using W = wider_t<T>;
        if constexpr (std::numeric_limits<W>::max_exponent > std::numeric_limits<T>::max_exponent) {
            return static_cast<T>(saturate((W(x) - W(old_min)) / (W(old_max) - W(old_min))));
        } else {
            const T h = T(0.5);  // exact for the inputs > max / 4 that matter here
            return saturate((x * h - old_min * h) / (old_max * h - old_min * h));
        }
    }
    return saturate((x - old_min) / (old_max - old_min));
}

}  // namespace detail

// remap_clamped: remap with the result clamped to the new range (either orientation).
// Domain: every finite input (and +-Inf for x). For finite input the result is finite and
// lies in [min(new_min, new_max), max(new_min, new_max)], bit for bit:
// - t = (x - old_min) / (old_max - old_min) is clamped to [0, 1] before it is scaled, so a
//   tiny old range gives t = +-Inf -> 0 or 1, never Inf * 0;
// - when |x|, |old_min| or |old_max| exceeds a quarter of the type's largest value, t is
//   computed in a wider type (detail::wider_t: double for float, long double for double
//   where it has the wider exponent range, as on x86-64 Linux), where neither difference
//   can overflow: remap_clamped(3e38f, -3e38f, 3e38f, 0, 1) was Inf / Inf = NaN. Halving
//   the inputs would do in IEEE builds, but -ffast-math factors the halving back out,
//   (x/2 - m/2) -> (x - m)/2, and overflows again; a conversion it cannot undo. Where long
//   double is no wider (MSVC, Apple arm64) double inputs take the halved form, which then
//   holds in IEEE builds only.
// - the blend (1 - t) new_min + t new_max can round one ulp past an end (for example
//   new_min == new_max = 0.920364857f gave 0.920364916f), so it is clamped to the range.
// The end points are exact: x <= old_min gives new_min, x >= old_max gives new_max bit for
// bit. Inputs up to a quarter of the largest value take the plain form in T.
// Degenerate range: the same step as remap. NaN input gives NaN (IEEE builds).
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] constexpr T remap_clamped(T x, T old_min, T old_max, T new_min,
                                        T new_max) noexcept {
    const T t = detail::remap_unit(x, old_min, old_max);
    const T r = (T(1) - t) * new_min + t * new_max;  // exact at t = 0 and t = 1
    return new_min < new_max ? detail::clamp(r, new_min, new_max) : detail::clamp(r, new_max, new_min);
}

// smoothstep_safe(edge0, edge1, x): GLSL smoothstep, t^2 (3 - 2 t) with
// t = saturate((x - edge0) / (edge1 - edge0)), but defined for every pair of edges:
// GLSL leaves edge0 >= edge1 undefined; here edge0 == edge1 is a step at edge0
// (0 below, 1 at and above) and edge0 > edge1 gives the mirrored (decreasing) curve.
// Named _safe so that `using namespace glm;` beside `using namespace cloudmath;` stays
// unambiguous. Domain: every finite input (t as in remap_clamped: no overflow for huge
// edges); the result is in [0, 1].
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] constexpr T smoothstep_safe(T edge0, T edge1, T x) noexcept {
    const T t = detail::remap_unit(x, edge0, edge1);  // remap_clamped(x, edge0, edge1, 0, 1)
    return t * t * (T(3) - T(2) * t);
}

// ---------------------------------------------------------------------------------------
// Stable exponential helpers.
//
// one_minus_exp_neg(x) = 1 - exp(-x), computed as -expm1(-x): accurate to about 1 ulp
// for all x, where the textbook 1 - exp(-x) loses all digits for x below the type's
// epsilon (float: 1 - exp(-1e-8) == 0). Domain: all finite x; +Inf -> 1.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T one_minus_exp_neg(T x) noexcept {
    return -std::expm1(-x);
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> one_minus_exp_neg(const glm::vec<L, T, Q>& x) noexcept {
    return detail::map(x, [](T v) { return one_minus_exp_neg(v); });
}

// one_minus_exp_neg_over_x(x) = (1 - exp(-x)) / x, with the limit 1 at x = 0.
// This is the weight of the energy-conserving step integral (Hillaire 2015):
// integral_0^d exp(-s t) dt = d * f(s d). Evaluated as -expm1(-x) / x: within 2 ulp of the
// exact value for every x >= 0 in float and double (two correctly rounded or 1-ulp
// operations). The textbook (1 - exp(-x)) / x returns 0 in float for x < 6e-8 and is 20%
// off at 1e-7. Also correct for negative x (the weight of a growing exponential) until
// exp(-x) overflows near x = -88 (float) / -709 (double). x = +Inf -> 0.
// The one special case: |x| below the smallest normal number returns exactly 1 (the true
// value rounds to 1 there). Testing against the smallest normal rather than against 0 keeps
// denormal x correct under -ffast-math, whose flush-to-zero mode makes x / x = 0 / 0.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T one_minus_exp_neg_over_x(T x) noexcept {
    if (detail::abs(x) < std::numeric_limits<T>::min()) return T(1);
    return -std::expm1(-x) / x;
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> one_minus_exp_neg_over_x(
    const glm::vec<L, T, Q>& x) noexcept {
    return detail::map(x, [](T v) { return one_minus_exp_neg_over_x(v); });
}

}  // namespace cloudmath

#endif  // CLOUDMATH_CORE_HPP
