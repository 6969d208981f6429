// Input of glsl.twins_detects_missing (read by check_twins.cmake, never compiled): four
// public functions, one void member that twins.txt may still list.
namespace fixture {

[[nodiscard]] constexpr float fixture_alpha(float x) noexcept { return x; }
[[nodiscard]] constexpr float fixture_beta(float x) noexcept { return x; }
[[nodiscard]] constexpr float fixture_gamma(float x) noexcept { return x; }
[[nodiscard]] constexpr float fixture_zeta(float x) noexcept { return x; }

struct accumulator {
    float sum = 0.0f;
    void fixture_add(float x) noexcept { sum += x; }  // no [[nodiscard]]: not parsed as public
};

}  // namespace fixture
