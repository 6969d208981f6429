// cloudmath/fast_math.hpp: an exp written so that compilers vectorise it (within float
// rounding of std::exp), and opt-in fast approximations with documented errors.
//
// Use:      #include <cloudmath/fast_math.hpp>
//           float T = cloudmath::fast::beer_lambert(tau);          // rel. error <= 6.0e-5
//           batch::beer_lambert<cloudmath::fast_math>(tau, n, out); // the same, over arrays
// Why:      std::exp is a library call that GCC and Clang vectorise only under -ffast-math.
//           exp_vectorizable is plain arithmetic (Cody-Waite range reduction, a polynomial,
//           the power of two built in the exponent bits), so loops over it vectorise with the
//           default flags; it is what the exact batch functions (batch.hpp) use.
// Policy:   the approximations live in namespace cloudmath::fast and in the fast_math
//           policy of batch.hpp; they are never the default. The exact scalar functions are
//           unchanged by this header.
// Errors:   maximum relative errors below are measured over the stated ranges by
//           tests/test_fast_math.cpp, which asserts them.
// Domain:   finite input. NaN gives an unspecified value (no undefined behaviour): these are
//           throughput functions and do not test for NaN.
// GLSL:     none. GPUs have hardware exp2 and inversesqrt; the GLSL twins use the built-ins.
#ifndef CLOUDMATH_FAST_MATH_HPP
#define CLOUDMATH_FAST_MATH_HPP

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core.hpp"

// Forces inlining of the per-element kernels: the batch loops vectorise only when the kernel
// body is inlined into them, and GCC does not always choose to on its own.
#if defined(__GNUC__)
#define CLOUDMATH_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define CLOUDMATH_ALWAYS_INLINE inline
#endif

namespace cloudmath {

// Policies for the batch functions (batch.hpp).
struct exact_math {};  // within float rounding of the scalar functions (the default)
struct fast_math {};   // the approximations of namespace fast

namespace detail {

template <class T> struct exp_constants;
template <> struct exp_constants<float> {
    using bits = std::uint32_t;
    static constexpr float log2e = 1.44269504088896341f;
    static constexpr float ln2_hi = 0.693145751953125f;     // ln 2 to 16 bits: n * ln2_hi is exact
    static constexpr float ln2_lo = 1.42860682030941723e-6f; // ln 2 - ln2_hi
    // n = round(x log2 e) stays in [-149, 127]: pow2_bits flushes n < -126 to 0 (where exp
    // is denormal), and exp(88) = 1.65e38 is the largest result.
    static constexpr float min_x = -103.0f;
    static constexpr float max_x = 88.0f;
    static constexpr int bias = 127;
    static constexpr int mantissa = 23;
};
template <> struct exp_constants<double> {
    using bits = std::uint64_t;
    static constexpr double log2e = 1.44269504088896340736;
    static constexpr double ln2_hi = 6.93147180369123816490e-01;  // 32 significant bits
    static constexpr double ln2_lo = 1.90821492927058770002e-10;
    static constexpr double min_x = -745.0;  // n >= -1075: flushed to 0 below -1022
    static constexpr double max_x = 708.0;
    static constexpr int bias = 1023;
    static constexpr int mantissa = 52;
};

// 2^n from the exponent bits for n <= bias (the callers' clamp of x guarantees it); n below
// the normal range gives exactly 0, so products downstream never become slow denormals.
// One integer max, no branch.
template <class T>
CLOUDMATH_ALWAYS_INLINE T pow2_bits(int n) noexcept {
    using C = exp_constants<T>;
    int e = n + C::bias;
    e = e > 0 ? e : 0;
    const typename C::bits b = static_cast<typename C::bits>(e) << C::mantissa;
    T r;
    std::memcpy(&r, &b, sizeof r);
    return r;
}

// Round to nearest (ties to even) for |y| < 2^22 (float) / 2^51 (double): y + 1.5 2^m puts
// the rounded integer in the low mantissa bits, read back as an integer. No float-to-int
// conversion, which after a clamp keeps GCC from vectorising the loop, and nothing that
// -ffast-math could fold away (unlike (y + magic) - magic).
inline int round_to_int(float y) noexcept {
    const float shifted = y + 12582912.0f;  // 1.5 * 2^23
    std::int32_t b;
    std::memcpy(&b, &shifted, sizeof b);
    return b - 0x4B400000;
}
inline int round_to_int(double y) noexcept {
    const double shifted = y + 6755399441055744.0;  // 1.5 * 2^52
    std::int64_t b;
    std::memcpy(&b, &shifted, sizeof b);
    return static_cast<int>(b - 0x4338000000000000LL);
}

// exp(r) for |r| <= ln2 / 2. Float: a degree-6 near-minimax polynomial (Chebyshev fit with
// mpmath's chebyfit; approximation error 2.0e-9, one multiply-add fewer than the degree-7
// Taylor polynomial it replaces, which had 5e-9). Double: the degree-12 Taylor polynomial
// (truncation 1.3e-17). Horner form.
inline float exp_reduced(float r) noexcept {
    return 1.0f + r * (1.0000000377162138f + r * (0.50000000471177577f + r * (0.16666415514653275f +
           r * (0.041666352896775157f + r * (0.0083751263981533357f + r * 0.0013941108433972675f)))));
}
inline double exp_reduced(double r) noexcept {
    double p = 1.0 / 479001600.0;  // 1/12!
    const double c[] = {1.0 / 39916800.0, 1.0 / 3628800.0, 1.0 / 362880.0, 1.0 / 40320.0, 1.0 / 5040.0, 1.0 / 720.0,
                        1.0 / 120.0,      1.0 / 24.0,      1.0 / 6.0,      0.5,            1.0,          1.0};
    for (double k : c) p = p * r + k;
    return p;
}

// Hides a value from the optimiser (GCC, Clang); elsewhere a no-op.
template <class T>
inline void opaque(T& v) noexcept {
#if defined(__GNUC__)
    __asm__("" : "+m"(v));
#else
    (void)v;
#endif
}

// A copy of v whose value the optimiser cannot see: for loop-invariant limits (see
// exp_kernel). Only the local copy's address escapes, never the caller's object's, so
// stores through a loop's output pointer cannot alias what it is assigned to.
template <class T>
inline T runtime_constant(T v) noexcept {
    opaque(v);
    return v;
}

// exp with the range clamp and polynomial of exp_vectorizable / fast::exp. In loops
// (hide_limits = true, built once outside the loop) the clamp limits are members hidden from
// the optimiser: with literal limits GCC folds the clamped branch into a constant and then,
// under the default -ftrapping-math, cannot merge the branches back into vector selects
// ("control flow in loop"), so the loop stays scalar. Single calls pass false and pay
// nothing. `hi` may be lowered (to 0 for exp(-tau), tau >= 0). Results below the normal
// range are exactly 0 (pow2_bits).
template <class T, bool Fast>
struct exp_kernel {
    T lo = exp_constants<T>::min_x;
    T hi = exp_constants<T>::max_x;
    explicit exp_kernel(T upper = exp_constants<T>::max_x, bool hide_limits = true) noexcept : hi(upper) {
        if (hide_limits) {
            lo = runtime_constant(lo);
            hi = runtime_constant(hi);
        }
    }
    CLOUDMATH_ALWAYS_INLINE T operator()(T x_in) const noexcept {
        using C = exp_constants<T>;
        // Written as x86's maxps / minps are defined ((a > b) ? a : b), so they compile to one
        // instruction each without -ffast-math; NaN maps to lo.
        T x = x_in > lo ? x_in : lo;
        x = x < hi ? x : hi;
        const int n = round_to_int(x * C::log2e);
        const T nf = T(n);
        if constexpr (Fast) {
            const T r = x - nf * (C::ln2_hi + C::ln2_lo);
            return (T(1) + r * (T(1) + r * (T(0.5) + r * (T(1) / T(6) + r * (T(1) / T(24)))))) * pow2_bits<T>(n);
        } else {
            const T r = (x - nf * C::ln2_hi) - nf * C::ln2_lo;  // Cody-Waite: exact first product
            return exp_reduced(r) * pow2_bits<T>(n);
        }
    }
};

}  // namespace detail

// exp(x) in plain arithmetic (Cody-Waite range reduction, a near-minimax polynomial, the
// power of two from the exponent bits): the scalar form of the exp that the batch functions
// vectorise (batch.hpp; a plain loop over this function stays scalar in GCC 12, for the
// reason given at exp_kernel, so use the batch functions for arrays). Maximum error against
// the exact value: 1.4 ulp in float, 2.6 ulp in double (std::exp: 0.5 ulp) for x in
// [-87.33, 88] (float) / [-708.39, 708] (double). Below that range the result is 0 where
// std::exp returns denormals (an absolute difference below 1.2e-38 in float; it keeps
// products such as phase * transmittance out of slow denormal arithmetic); above, it is
// exp(88) = 1.65e38 (float) where std::exp overflows to Inf. The batch loops vectorise at
// -O3 (GCC 12's -O2 cost model vectorises nothing of this size). Under -ffast-math the compiler may merge the two steps of the range reduction, which
// raises the error to 131 ulp in float (1.6e-5 relative) and 1170 ulp in double (2.6e-13),
// measured by the fast-math build of tests/test_fast_math.cpp.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T exp_vectorizable(T x) noexcept {
    return detail::exp_kernel<T, false>(detail::exp_constants<T>::max_x, false)(x);
}

namespace fast {

// exp(x) with a degree-4 polynomial after the same range reduction: maximum relative error
// 6.0e-5 (float and double; 6.2e-5 under -ffast-math) for x in [-87.33, 88]; outside,
// clamped as exp_vectorizable.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T exp(T x) noexcept {
    return detail::exp_kernel<T, true>(detail::exp_constants<T>::max_x, false)(x);
}

// 1/sqrt(x) by the exponent-halving bit trick and one Newton step: maximum relative error
// 1.8e-3 (measured 1.752e-3, float and double).
// Domain: x in [2^-125, 2^124] in float (about 2.35e-38 to 2.13e37) and [2^-1021, 2^1020] in
// double (about 4.45e-308 to 1.12e307), in every build. In that range each partial product
// of the Newton step, 0.5 x y y with y ~ x^-1/2 (0.5 x, x y, y y, 0.5 y y, ...), is a normal
// number, whichever order -ffast-math's re-association picks. Outside it one of them can be
// a denormal, which -ffast-math's flush-to-zero makes 0, and the error reaches 55% (measured
// at x = 2.2e38 and in the lowest normal binade, with GCC 12). With IEEE arithmetic (no
// flush to zero) the 1.8e-3 also holds over the rest of the normal range. x <= 0, denormal
// x and Inf: unspecified. The library's callers (fast::phase_hg, the batch HG kernels)
// pass x in [1e-8, 4].
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T rsqrt(T x) noexcept {
    using C = detail::exp_constants<T>;
    typename C::bits b;
    std::memcpy(&b, &x, sizeof b);
    const typename C::bits magic =
        std::is_same_v<T, float> ? typename C::bits(0x5f375a86U) : typename C::bits(0x5fe6eb50c7b537a9ULL);
    b = magic - (b >> 1);
    T y;
    std::memcpy(&y, &b, sizeof y);
    return y * (T(1.5) - T(0.5) * x * y * y);
}

// HG with the fast rsqrt for (1 + g^2 - 2 g mu)^(-3/2) (same clamps and stable base as
// phase_hg): maximum relative error 5.3e-3 against phase_hg, any mu, |g| <= 0.9999.
template <class T>
[[nodiscard]] inline T phase_hg(T mu, T g) noexcept {
    mu = detail::clamp(mu, T(-1), T(1));
    g = detail::clamp(g, T(-0.9999), T(0.9999));
    const T d = g >= T(0) ? (T(1) - g) * (T(1) - g) + T(2) * g * (T(1) - mu)
                          : (T(1) + g) * (T(1) + g) - T(2) * g * (T(1) + mu);
    const T inv = fast::rsqrt(d);
    return inv_four_pi_v<T> * ((T(1) - g) * (T(1) + g)) * (inv * inv * inv);
}

// exp(-tau) with fast::exp: relative error <= 6.0e-5; tau < 0 clamped to 0.
template <class T>
[[nodiscard]] inline T beer_lambert(T tau) noexcept {
    return fast::exp(-detail::max(tau, T(0)));
}

// 1 - exp(-k tau) with fast::exp: absolute error <= 6.0e-5 (relative precision is lost for
// k tau below about 1e-3, where the exact powder keeps it).
template <class T>
[[nodiscard]] inline T powder(T tau, T k) noexcept {
    return T(1) - fast::exp(-detail::max(k * tau, T(0)));
}

// 2 e (1 - e^2) with one fast::exp (e = exp(-tau), so exp(-2 tau) = e^2): absolute error
// <= 4.0e-5 against beer_powder.
template <class T>
[[nodiscard]] inline T beer_powder(T tau) noexcept {
    const T e = fast::exp(-detail::max(tau, T(0)));
    return T(2) * e * (T(1) - e * e);
}

// Wrenninge octaves with fast::phase_hg and fast::exp: relative error <= 5.3e-3 against
// multiple_scattering.
template <class T>
[[nodiscard]] inline T multiple_scattering(T optical_depth, T mu, T g, T a, T b, T c, int octaves) noexcept {
    T sum = T(0), ai = T(1), bi = T(1), ci = T(1);
    for (int i = 0; i < octaves; ++i) {
        sum += bi * fast::phase_hg(mu, ci * g) * fast::exp(-detail::max(ai * optical_depth, T(0)));
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}

}  // namespace fast
}  // namespace cloudmath

#endif  // CLOUDMATH_FAST_MATH_HPP
