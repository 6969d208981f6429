// tools/common/strict_number.hpp: the numbers of the tools' command lines and data files,
// parsed strictly, so that "0.067xyz", "nan", " 5", "0x10" or "-3" paths are errors rather
// than silently read as something else (strtod and stod stop at the first bad character and
// accept nan, inf, hexadecimal and leading spaces; strtoull wraps "-3" round to 2^64 - 3).
//
//   parse_finite("0.067")   -> 0.067      parse_finite("0.067xyz"), ("nan"), ("1e999") -> none
//   parse_integer<int>("-12") -> -12      parse_integer<unsigned>("-1"), ("1.5"), ("") -> none
//   parse_count("1e6")      -> 1000000    parse_count("-5"), ("2.5"), ("1e300") -> none
//
// The whole text must be the number: no spaces, no suffix. Decimal only, in the "C" locale
// (std::from_chars), a single leading '+' allowed. Callers check ranges and word messages.
#ifndef CLOUDMATH_TOOLS_COMMON_STRICT_NUMBER_HPP
#define CLOUDMATH_TOOLS_COMMON_STRICT_NUMBER_HPP

#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace cloudmath::tools {

namespace strict_number_detail {

// Drops one leading '+' when a digit or '.' follows (from_chars takes no '+').
constexpr std::string_view without_plus(std::string_view text) {
    if (text.size() >= 2 && text[0] == '+' && (text[1] == '.' || (text[1] >= '0' && text[1] <= '9')))
        return text.substr(1);
    return text;
}

}  // namespace strict_number_detail

// A finite decimal number (digits, optional fraction and exponent), the whole text.
[[nodiscard]] inline std::optional<double> parse_finite(std::string_view text) {
    text = strict_number_detail::without_plus(text);
    if (text.empty()) return std::nullopt;
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value, std::chars_format::general);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

// A decimal integer of type Int (a '-' only for signed types), in Int's range, the whole text.
template <class Int>
[[nodiscard]] std::optional<Int> parse_integer(std::string_view text) {
    static_assert(std::is_integral_v<Int> && !std::is_same_v<Int, bool>, "an integer type");
    text = strict_number_detail::without_plus(text);
    if (text.empty()) return std::nullopt;
    if constexpr (std::is_unsigned_v<Int>)
        if (text[0] == '-') return std::nullopt;
    Int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value, 10);
    if (ec != std::errc() || ptr != end) return std::nullopt;
    return value;
}

// The largest count parse_count reads in a fraction or exponent form: 2^53, up to which
// every whole number is a double.
inline constexpr std::uint64_t max_exact_count = std::uint64_t{1} << 53;

// A non-negative whole number: digits ("2000000", up to 2^64 - 1), or a decimal or exponent
// form whose value is whole ("2e6", "1.5e3", up to 2^53).
[[nodiscard]] inline std::optional<std::uint64_t> parse_count(std::string_view text) {
    if (!text.empty() && text[0] == '-') return std::nullopt;
    if (const auto exact = parse_integer<std::uint64_t>(text)) return exact;
    const std::optional<double> v = parse_finite(text);
    if (!v || !(*v >= 0.0) || *v > static_cast<double>(max_exact_count) || *v != std::floor(*v))
        return std::nullopt;
    return static_cast<std::uint64_t>(*v);
}

}  // namespace cloudmath::tools

#endif  // CLOUDMATH_TOOLS_COMMON_STRICT_NUMBER_HPP
