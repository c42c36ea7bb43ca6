#pragma once
// The N of a generated scene's name "PREFIX-N": decimal, no sign, no leading zero, at most 18
// digits (no overflow; the generator's range check says what is too large). Shared by the
// builtin:ullner-sheets-N and builtin:ullner-mosaic-N names.
#include <charconv>
#include <cstddef>
#include <optional>
#include <string_view>

namespace rtsim::scenes {

inline std::optional<std::size_t> number_after_prefix(std::string_view name,
                                                      std::string_view prefix) {
  if (name.substr(0, prefix.size()) != prefix) return std::nullopt;
  const std::string_view digits = name.substr(prefix.size());
  if (digits.empty() || digits.size() > 18 || (digits.size() > 1 && digits[0] == '0'))
    return std::nullopt;
  std::size_t n = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (ec != std::errc() || ptr != digits.data() + digits.size()) return std::nullopt;
  return n;
}

}  // namespace rtsim::scenes
