// Shared helpers of the unit tests: bit-level finiteness (valid under -ffast-math, where
// std::isnan may be folded to false), error measures, and long double quadrature over the
// sphere graded toward the peaks of phase functions.
#ifndef CLOUDMATH_TEST_SUPPORT_HPP
#define CLOUDMATH_TEST_SUPPORT_HPP

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include <doctest/doctest.h>

namespace cm_test {

using ld = long double;

// True when x is neither NaN nor +-Inf, decided from the exponent bits so that it cannot
// be optimised away by -ffinite-math-only.
inline bool finite_bits(float x) {
    std::uint32_t u;
    std::memcpy(&u, &x, sizeof u);
    return (u & 0x7f800000u) != 0x7f800000u;
}
inline bool finite_bits(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return (u & 0x7ff0000000000000ull) != 0x7ff0000000000000ull;
}
inline bool nan_bits(float x) {
    std::uint32_t u;
    std::memcpy(&u, &x, sizeof u);
    return (u & 0x7f800000u) == 0x7f800000u && (u & 0x007fffffu) != 0;
}
inline bool nan_bits(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return (u & 0x7ff0000000000000ull) == 0x7ff0000000000000ull &&
           (u & 0x000fffffffffffffull) != 0;
}

// NaN and Inf built from their bit patterns, so -ffast-math cannot fold them.
template <class T>
T from_bits(std::uint32_t float_bits, std::uint64_t double_bits) {
    T x;
    if constexpr (std::is_same_v<T, float>)
        std::memcpy(&x, &float_bits, sizeof x);
    else
        std::memcpy(&x, &double_bits, sizeof x);
    return x;
}
template <class T>
T make_nan() {
    return from_bits<T>(0x7fc00000u, 0x7ff8000000000000ull);
}
template <class T>
T make_inf() {
    return from_bits<T>(0x7f800000u, 0x7ff0000000000000ull);
}

// True when this translation unit is compiled with IEEE semantics for NaN and Inf; the
// NaN/Inf input tests only make sense then (the documented behaviour under -ffast-math is
// "unspecified value", which cannot be asserted).
#if defined(__FAST_MATH__) || (defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__)
inline constexpr bool ieee_build = false;
#else
inline constexpr bool ieee_build = true;
#endif

// Quad precision (GCC's __float128, 113-bit mantissa, software arithmetic) for references
// whose textbook form cancels even in long double. __extension__ keeps -Wpedantic quiet.
__extension__ typedef __float128 quad;

// sqrt in quad: long double estimate refined by two Newton steps (no libquadmath needed).
inline quad sqrt_q(quad x) {
    if (x <= 0) return 0;
    quad r = std::sqrt(static_cast<ld>(x));
    r = (r + x / r) / 2;
    r = (r + x / r) / 2;
    return r;
}

// As std::string: doctest prints a const char* as a pointer.
template <class T>
std::string type_name() {
    return std::is_same_v<T, float> ? "float" : "double";
}

template <class T>
constexpr T eps() {
    return std::numeric_limits<T>::epsilon();
}

// |got - ref| / |ref|, or |got - ref| when ref == 0.
inline ld rel_err(ld got, ld ref) {
    const ld diff = std::fabs(got - ref);
    return ref == 0 ? diff : diff / std::fabs(ref);
}

// Relative error in units of the type's epsilon.
template <class T>
ld rel_err_eps(T got, ld ref) {
    return rel_err(static_cast<ld>(got), ref) / static_cast<ld>(eps<T>());
}

// |got - ref| <= ulps * eps * |ref| + the smallest normal number: relative accuracy with an
// absolute floor for results that underflow (exp(-700) is 0 in float, correctly).
template <class T>
bool close_ulps(T got, ld ref, ld ulps) {
    return std::fabs(static_cast<ld>(got) - ref) <=
           ulps * static_cast<ld>(eps<T>()) * std::fabs(ref) + static_cast<ld>(std::numeric_limits<T>::min());
}

// Identities that hold bit for bit with IEEE arithmetic (a weight of exactly 0 or 1, a
// term times 0) may differ in the last bits when -ffast-math re-associates the sums; there
// they are checked to 4 ulp instead.
template <class T>
bool same_value(T a, T b) {
    if constexpr (ieee_build) return a == b;
    return std::fabs(static_cast<ld>(a) - static_cast<ld>(b)) <=
           4 * static_cast<ld>(eps<T>()) * std::fabs(static_cast<ld>(b));
}

// Gauss-Legendre 16-point rule on [a, b] in long double; nodes from Newton's iteration on
// the Legendre polynomial (computed once).
struct gauss16 {
    std::array<ld, 16> x{}, w{};
    gauss16() {
        const int n = 16;
        const ld pi = 3.141592653589793238462643383279502884L;
        for (int i = 0; i < n; ++i) {
            ld z = std::cos(pi * (i + 0.75L) / (n + 0.5L));
            ld dp = 0;
            for (int it = 0; it < 100; ++it) {
                ld p0 = 1, p1 = z;
                for (int k = 2; k <= n; ++k) {
                    const ld p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n * (z * p1 - p0) / (z * z - 1);
                const ld dz = p1 / dp;
                z -= dz;
                if (std::fabs(dz) < 1e-19L) break;
            }
            x[static_cast<std::size_t>(i)] = z;
            w[static_cast<std::size_t>(i)] = 2 / ((1 - z * z) * dp * dp);
        }
    }
    template <class F>
    ld integrate(F f, ld a, ld b) const {
        const ld half = (b - a) / 2, mid = (a + b) / 2;
        ld s = 0;
        for (std::size_t i = 0; i < 16; ++i) s += w[i] * f(mid + half * x[i]);
        return s * half;
    }
};

// Integral over mu in [-1, 1] of f(mu), with panels graded geometrically toward both ends
// (1 - |mu| = 10^-k down to 1e-14), accurate to ~1e-15 for functions peaked at mu = +-1
// with widths down to 1e-4 (HG with |g| up to 0.9999).
template <class F>
ld integrate_mu(F f) {
    static const gauss16 gl;
    ld s = 0;
    // Interior [-0.9, 0.9] in 36 panels.
    for (int i = 0; i < 36; ++i) s += gl.integrate(f, -0.9L + 0.05L * i, -0.9L + 0.05L * (i + 1));
    // Graded panels near each end: 1 - |mu| in [10^-(k+1/4 step)...].
    ld hi = 0.1L;
    for (int k = 0; k < 56; ++k) {
        const ld lo = hi * 0.5623413251903491L;  // 10^(-1/4) per panel
        s += gl.integrate(f, 1 - hi, 1 - lo);
        s += gl.integrate(f, -1 + lo, -1 + hi);
        hi = lo;
    }
    // Remaining sliver [1 - hi, 1] and [-1, -1 + hi], hi ~ 1e-15.
    s += gl.integrate(f, 1 - hi, 1.0L) + gl.integrate(f, -1.0L, -1 + hi);
    return s;
}

// Integral of f over the unit sphere for an axially symmetric f(mu): 2 pi integral_mu.
template <class F>
ld integrate_sphere(F f) {
    return 2 * 3.141592653589793238462643383279502884L * integrate_mu(f);
}

// Deterministic uniform numbers in [0, 1) (SplitMix64), the same on every platform.
struct rng {
    std::uint64_t state;
    explicit rng(std::uint64_t seed) : state(seed) {}
    std::uint64_t next_u64() {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
};

}  // namespace cm_test

#endif  // CLOUDMATH_TEST_SUPPORT_HPP
