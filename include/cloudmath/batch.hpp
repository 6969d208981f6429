// cloudmath/batch.hpp: the lighting functions over arrays, written as loops that compilers
// vectorise with the default flags (no -ffast-math needed), for CPU-side lighting, baking
// and benchmarks.
//
// Use:      #include <cloudmath/batch.hpp>
//           cloudmath::batch::phase_hg(mu.data(), mu.size(), 0.8f, out.data());
//           cloudmath::batch::beer_lambert<cloudmath::fast_math>(tau, n, out);  // opt-in approximation
// Policies: exact_math (default): within float rounding of the scalar functions: the same
//           forms, with exp_vectorizable (<= 1.4 ulp in float) in place of std::exp, so the
//           results differ from the scalar ones by a few ulp (tests/test_batch.cpp).
//           fast_math: the approximations of fast_math.hpp, with their documented errors.
//           Under -ffast-math, the compiler may fold exp_vectorizable's two-step range
//           reduction: the exponential terms then carry up to 1.6e-5 relative error in float
//           (2.6e-13 in double), measured by the fast-math build of the tests.
// Layout:   inputs and outputs are separate arrays of n elements (structure of arrays);
//           out may alias an input of the same length. All functions are void and noexcept.
// Dispatch: on x86-64 with GCC or Clang, each function is compiled twice, for the flags of
//           the translation unit and for AVX2 + FMA (8 floats per vector instead of SSE2's
//           4), and picks the second at run time on CPUs that have it (batch::active_isa()).
//           The two agree within the error budgets above; they may differ from each other in
//           the last bits. batch::restrict_to_baseline(true) makes every machine run the
//           baseline code (bit-identical results across CPUs for one binary).
//           #define CLOUDMATH_BATCH_DISPATCH 0 (the same in every translation unit) before
//           the include to compile only the baseline; it is 0 already where the compiler
//           targets AVX2 and FMA itself (-march=x86-64-v3 or later) and on other compilers
//           and architectures.
// Speed:    measured against the naive scalar loop and a memory copy in docs/bench.md
//           (bash scripts/bench.sh).
#ifndef CLOUDMATH_BATCH_HPP
#define CLOUDMATH_BATCH_HPP

#include <atomic>
#include <cstddef>
#include <type_traits>

#include "core.hpp"
#include "fast_math.hpp"
#include "phase.hpp"

#ifndef CLOUDMATH_BATCH_DISPATCH
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__) && !(defined(__AVX2__) && defined(__FMA__))
#define CLOUDMATH_BATCH_DISPATCH 1
#else
#define CLOUDMATH_BATCH_DISPATCH 0
#endif
#endif

// A lambda whose body the compiler must inline into its caller (see detail::dispatch).
#if defined(__GNUC__)
#define CLOUDMATH_LAMBDA_INLINE __attribute__((always_inline))
#else
#define CLOUDMATH_LAMBDA_INLINE
#endif

namespace cloudmath {
namespace batch {

// The instruction sets the batch loops are compiled for (see Dispatch above).
enum class isa {
    baseline,  // the translation unit's own flags (SSE2 on plain x86-64)
    avx2_fma,  // x86-64-v3's AVX2 and FMA, chosen at run time
};

}  // namespace batch

namespace detail {

// Set by batch::restrict_to_baseline. A function-local static of an inline function: one
// flag per program, whichever translation units include this header.
inline std::atomic<bool>& baseline_only() noexcept {
    static std::atomic<bool> flag{false};
    return flag;
}

#if CLOUDMATH_BATCH_DISPATCH
// GCC's and Clang's CPU test reads a table that their runtime fills before main (it also
// checks that the OS saves the AVX registers).
inline bool cpu_has_avx2_fma() noexcept { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

// The loop body, inlined (always_inline) into a function compiled for AVX2 and FMA: the
// vectoriser then uses 8-float vectors. Inlining the baseline-compiled body into a function
// with a superset of its target is what GCC and Clang allow.
template <class Body>
__attribute__((target("avx2,fma"))) void run_avx2_fma(const Body& body) noexcept {
    body();
}
#endif

// True when the batch functions run their AVX2 + FMA copy: compiled in, present on this CPU,
// and allowed by restrict_to_baseline.
inline bool use_avx2_fma() noexcept {
#if CLOUDMATH_BATCH_DISPATCH
    return !baseline_only().load(std::memory_order_relaxed) && cpu_has_avx2_fma();
#else
    return false;
#endif
}

// Runs body with the widest instruction set this CPU has (and restrict_to_baseline allows).
template <class Body>
CLOUDMATH_ALWAYS_INLINE void dispatch(const Body& body) noexcept {
#if CLOUDMATH_BATCH_DISPATCH
    if (use_avx2_fma()) {
        run_avx2_fma(body);
        return;
    }
#endif
    body();
}

// The exp of a policy, as a kernel to construct outside the loop (see exp_kernel).
template <class Policy, class T>
using policy_exp = exp_kernel<T, std::is_same_v<Policy, fast_math>>;

// (1 - exp(-x)) / x for x >= 0, vectorisable: its Taylor polynomial sum (-x)^k / (k+1)!
// below 0.5, of degree 8 for float and 16 for double (truncation 5e-10 and 1.3e-21), and
// the quotient above (cancellation at most a factor 2.5). `split` is 0.5 passed in at run
// time, for the same reason as exp_kernel's limits.
template <class Policy, class T>
CLOUDMATH_ALWAYS_INLINE T one_minus_exp_neg_over_x_vec(T x_in, const policy_exp<Policy, T>& ex, T split) noexcept {
    // Both sides are evaluated on clamped arguments (finite everywhere) and blended with a
    // 0/1 weight: a ternary select here is turned back into branches that keep GCC from
    // vectorising (as in exp_kernel).
    const T x = x_in < split ? x_in : split;       // Taylor side, in [0, split]
    const T safe_x = x_in > split ? x_in : split;  // quotient side, >= split
    const T use_taylor = T(x_in < split);
    T taylor;
    if constexpr (std::is_same_v<T, float>) {
        taylor = 1.0f + x * (-1.0f / 2 + x * (1.0f / 6 + x * (-1.0f / 24 + x * (1.0f / 120 + x * (-1.0f / 720 +
                 x * (1.0f / 5040 + x * (-1.0f / 40320 + x * (1.0f / 362880))))))));
    } else {
        // c_k = (-1)^k / (k + 1)!, k = 16 .. 0, Horner from the top.
        static constexpr T c[] = {1.0 / 355687428096000.0, -1.0 / 20922789888000.0, 1.0 / 1307674368000.0,
                                  -1.0 / 87178291200.0,    1.0 / 6227020800.0,      -1.0 / 479001600.0,
                                  1.0 / 39916800.0,        -1.0 / 3628800.0,        1.0 / 362880.0,
                                  -1.0 / 40320.0,          1.0 / 5040.0,            -1.0 / 720.0,
                                  1.0 / 120.0,             -1.0 / 24.0,             1.0 / 6.0,
                                  -1.0 / 2.0,              1.0};
        taylor = c[0];
        for (std::size_t k = 1; k < sizeof c / sizeof c[0]; ++k) taylor = taylor * x + c[k];
    }
    const T quotient = (T(1) - ex(-safe_x)) / safe_x;
    return quotient + use_taylor * (taylor - quotient);
}

// HG with the g-dependent terms hoisted out of the loop: p = k d^(-3/2) with
// d = base + slope (1 -+ mu) (the stable base of phase.hpp).
template <class Policy, class T>
struct hg_kernel {
    T k, base, slope, sign;
    T lo = runtime_constant(T(-1)), hi = runtime_constant(T(1));  // mu's clamp (see exp_kernel)
    explicit hg_kernel(T g) noexcept {
        g = clamp_g(g);
        k = inv_four_pi_v<T> * ((T(1) - g) * (T(1) + g));
        base = g >= T(0) ? (T(1) - g) * (T(1) - g) : (T(1) + g) * (T(1) + g);
        slope = T(2) * (g >= T(0) ? g : -g);
        sign = g >= T(0) ? T(-1) : T(1);  // 1 - mu for g >= 0, 1 + mu for g < 0
    }
    // mu clamped to [-1, 1], as maxps / minps (see exp_kernel).
    CLOUDMATH_ALWAYS_INLINE T clamp_mu(T mu) const noexcept {
        mu = mu > lo ? mu : lo;
        return mu < hi ? mu : hi;
    }
    CLOUDMATH_ALWAYS_INLINE T operator()(T mu) const noexcept { return at_clamped(clamp_mu(mu)); }
    // HG for an already clamped mu (loops that need the clamped value themselves).
    CLOUDMATH_ALWAYS_INLINE T at_clamped(T mu) const noexcept {
        const T d = base + slope * (T(1) + sign * mu);
        // d^(-1/2) without std::sqrt: with the default -fmath-errno GCC guards sqrt with an
        // errno branch that keeps the loop scalar. fast_math: fast::rsqrt as is (the same
        // values as fast::phase_hg, 5.3e-3). exact_math: refined by two (float) or three
        // (double) more Newton steps, which reach float rounding: batch HG is within 5.5 ulp
        // of the exact value in float (scalar phase_hg: 3.7 ulp).
        T y = fast::rsqrt(d);
        if constexpr (!std::is_same_v<Policy, fast_math>) {
            y = y * (T(1.5) - T(0.5) * d * y * y);
            y = y * (T(1.5) - T(0.5) * d * y * y);
            if constexpr (std::is_same_v<T, double>) y = y * (T(1.5) - T(0.5) * d * y * y);
        }
        return k * (y * y * y);
    }
};

}  // namespace detail

namespace batch {

// The instruction set the batch functions run with on this machine, now.
[[nodiscard]] inline isa active_isa() noexcept { return detail::use_avx2_fma() ? isa::avx2_fma : isa::baseline; }

// A short name for reports: "baseline" or "avx2+fma".
[[nodiscard]] inline const char* isa_name(isa i) noexcept { return i == isa::avx2_fma ? "avx2+fma" : "baseline"; }

// true: every batch function runs its baseline code from now on, on every CPU (for results
// identical across machines, or to measure the baseline); false (the default): dispatch.
// Thread-safe; calls already running finish with the code they started with.
inline void restrict_to_baseline(bool on) noexcept { detail::baseline_only().store(on, std::memory_order_relaxed); }

// out[i] = phase_hg(mu[i], g).
template <class Policy = exact_math, class T>
void phase_hg(const T* mu, std::size_t n, T g, T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        const detail::hg_kernel<Policy, T> hg(g);
        for (std::size_t i = 0; i < n; ++i) out[i] = hg(mu[i]);
    });
}

// out[i] = phase_cornette_shanks(mu[i], g).
template <class Policy = exact_math, class T>
void phase_cornette_shanks(const T* mu, std::size_t n, T g, T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        const detail::hg_kernel<Policy, T> hg(g);
        const T gc = detail::clamp_g(g);
        // CS = HG * 3 (1 + mu^2) / (2 (2 + g^2)).
        const T factor = T(3) / (T(2) * (T(2) + gc * gc));
        for (std::size_t i = 0; i < n; ++i) {
            const T m = hg.clamp_mu(mu[i]);
            out[i] = hg.at_clamped(m) * factor * (T(1) + m * m);
        }
    });
}

// out[i] = phase_mie_approx(mu[i], p).
template <class T>
void phase_mie_approx(const T* mu, std::size_t n, const mie_approx_parameters<T>& p, T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        const detail::hg_kernel<exact_math, T> hg(p.g_hg);
        const detail::hg_kernel<exact_math, T> hd(p.g_draine);
        const T gd = detail::clamp_g(p.g_draine);
        const T alpha = detail::max(p.alpha, T(0));
        // Draine = HG(g_D) (1 + alpha mu^2) / (1 + alpha (1 + 2 g_D^2) / 3).
        const T draine_norm = T(1) / (T(1) + alpha * (T(1) + T(2) * gd * gd) / T(3));
        for (std::size_t i = 0; i < n; ++i) {
            const T m = hg.clamp_mu(mu[i]);
            out[i] = (T(1) - p.w_draine) * hg.at_clamped(m) + p.w_draine * hd.at_clamped(m) * (T(1) + alpha * m * m) * draine_norm;
        }
    });
}

// out[i] = beer_lambert(tau[i]).
template <class Policy = exact_math, class T>
void beer_lambert(const T* tau, std::size_t n, T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        const detail::policy_exp<Policy, T> ex(T(0));  // exp(x) for x <= 0: tau < 0 clamps to 0
        for (std::size_t i = 0; i < n; ++i) out[i] = ex(-tau[i]);
    });
}

// out[i] = beer_powder(tau[i]). Domain: every finite tau (and +Inf in IEEE builds); the
// result is in [0, 0.7698] and 0 for tau beyond the exponential's range. tau is clamped to
// [0, -exp_constants<T>::min_x] (103 in float, 745 in double), where the kernel's exp(-tau)
// is already exactly 0, so the clamp changes no result and keeps 2 tau finite: for
// tau > FLT_MAX / 2 (DBL_MAX / 2) 2 tau overflowed, and Inf * 0 made the result NaN.
template <class Policy = exact_math, class T>
void beer_powder(const T* tau, std::size_t n, T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        const detail::policy_exp<Policy, T> ex(T(0));
        const T zero = detail::runtime_constant(T(0)), split = detail::runtime_constant(T(0.5));
        const T tau_max = detail::runtime_constant(-detail::exp_constants<T>::min_x);
        for (std::size_t i = 0; i < n; ++i) {
            T t = tau[i] > zero ? tau[i] : zero;
            t = t < tau_max ? t : tau_max;
            const T e = ex(-t);
            if constexpr (std::is_same_v<Policy, fast_math>) {
                out[i] = T(2) * e * (T(1) - e * e);
            } else {
                const T x = T(2) * t;
                out[i] = T(2) * e * (x * detail::one_minus_exp_neg_over_x_vec<Policy>(x, ex, split));
            }
        }
    });
}

// out[i] = nubis_attenuation(tau[i]).
template <class Policy = exact_math, class T>
void nubis_attenuation(const T* tau, std::size_t n, T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        const detail::policy_exp<Policy, T> ex(T(0));
        for (std::size_t i = 0; i < n; ++i) {
            const T a = ex(-tau[i]), b = T(0.7) * ex(T(-0.25) * tau[i]);
            out[i] = a < b ? b : a;
        }
    });
}

// out[i] = integrate_scattering(S[i], sigma_t[i], ds).
template <class T>
void integrate_scattering(const T* S, const T* sigma_t, std::size_t n, T ds, T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        const detail::policy_exp<exact_math, T> ex(T(0));
        const T zero = detail::runtime_constant(T(0)), split = detail::runtime_constant(T(0.5));
        for (std::size_t i = 0; i < n; ++i) {
            const T x = sigma_t[i] * ds;
            out[i] = S[i] * ds * detail::one_minus_exp_neg_over_x_vec<exact_math>(x > zero ? x : zero, ex, split);
        }
    });
}

// out[i] = multiple_scattering(tau[i], mu[i], g, a, b, c, octaves). Octaves are the outer
// loop, so the inner loop over elements vectorises.
template <class Policy = exact_math, class T>
void multiple_scattering(const T* tau, const T* mu, std::size_t n, T g, T a, T b, T c, int octaves,
                         T* out) noexcept {
    detail::dispatch([&]() CLOUDMATH_LAMBDA_INLINE {
        for (std::size_t i = 0; i < n; ++i) out[i] = T(0);
        T ai = T(1), bi = T(1), ci = T(1);
        for (int o = 0; o < octaves; ++o) {
            const detail::hg_kernel<Policy, T> hg(ci * g);
            const detail::policy_exp<Policy, T> ex(T(0));
            for (std::size_t i = 0; i < n; ++i) out[i] += bi * hg(mu[i]) * ex(-ai * tau[i]);
            ai *= a;
            bi *= b;
            ci *= c;
        }
    });
}

}  // namespace batch
}  // namespace cloudmath

#endif  // CLOUDMATH_BATCH_HPP
