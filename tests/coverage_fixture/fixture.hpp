// Input for coverage.detects_untested (read by check_coverage.cmake, never compiled):
// two public functions, only foo_bar is called in test_fixture.cpp, so the check must fail
// and name multi_line_name.
// It also exercises the parse: a template on the line before the attribute, a return type
// containing "<" and ",", a parameter list spread over lines, and things that must not count.
#include <glm/vec2.hpp>

namespace fixture {

template <class T>
[[nodiscard]] constexpr T foo_bar(T x) noexcept;

template <class T>
[[nodiscard]] inline glm::vec<2, T> multi_line_name(
    T a,
    T b) noexcept {
    return glm::vec<2, T>(a, b);
}

// Not public functions: an operator, a detail helper without the attribute, and a comment
// that mentions [[nodiscard]] not_a_function(.
struct pair_value {
    int v;
    [[nodiscard]] constexpr bool operator==(const pair_value& o) const noexcept { return v == o.v; }
};
namespace detail {
template <class T> constexpr T helper(T x) noexcept { return x; }
}  // namespace detail

}  // namespace fixture
