#include "scenes/scene_text.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include "common/input_file.hpp"
#include "common/leading_plus.hpp"

namespace rtsim::scenes {

namespace {

/// Longest token quoted verbatim in a message; longer ones are cut with "...".
constexpr std::size_t kMaxQuotedTokenChars = 40;

}  // namespace

std::string read_scene_file(const std::string& path) {
  return read_input_file(path, "scene file", kMaxSceneFileBytes, "kMaxSceneFileBytes");
}

std::string quote_token(std::string_view token) {
  if (token.size() <= kMaxQuotedTokenChars) return cat("'", token, "'");
  return cat("'", token.substr(0, kMaxQuotedTokenChars), "...'");
}

NumberStatus try_parse_number(std::string_view token, double& value) {
  const std::string_view t = strip_leading_plus(token);
  const auto [ptr, ec] =
      std::from_chars(t.data(), t.data() + t.size(), value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) return NumberStatus::kOutOfRange;
  if (ec != std::errc{} || ptr != t.data() + t.size()) return NumberStatus::kNotANumber;
  if (!std::isfinite(value)) return NumberStatus::kNotFinite;
  if (std::fabs(value) > kMaxSceneNumberMagnitude) return NumberStatus::kTooLarge;
  return NumberStatus::kOk;
}

void fail_number(const TokenCursor& cursor, const SceneToken& token, NumberStatus status,
                 std::string_view what_base, std::size_t value_no) {
  const std::string what =
      value_no > 0 ? cat(what_base, " (value ", value_no, ")") : std::string(what_base);
  const std::string quoted = quote_token(token.text);
  switch (status) {
    case NumberStatus::kOutOfRange:
      cursor.fail(token.line,
                  cat("number ", quoted, " for ", what, " is outside the range of a double"));
    case NumberStatus::kTooLarge:
      cursor.fail(token.line,
                  cat("number ", quoted, " for ", what,
                      " exceeds the magnitude limit of 1e15 (kMaxSceneNumberMagnitude)"));
    case NumberStatus::kNotFinite:
      cursor.fail(token.line, cat(quoted, " for ", what, " is not a finite number"));
    default:
      cursor.fail(token.line, cat("expected a number for ", what, ", got ", quoted));
  }
}

double parse_number(const TokenCursor& cursor, const SceneToken& token, std::string_view what) {
  double value = 0.0;
  const NumberStatus status = try_parse_number(token.text, value);
  if (status != NumberStatus::kOk) fail_number(cursor, token, status, what);
  return value;
}

std::int64_t parse_integer(const TokenCursor& cursor, const SceneToken& token,
                           std::string_view what) {
  const std::string_view t = strip_leading_plus(token.text);
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value, 10);
  if (ec == std::errc{} && ptr == t.data() + t.size()) return value;
  if (ec == std::errc::result_out_of_range) {
    cursor.fail(token.line,
                cat("integer ", quote_token(token.text), " for ", what, " is far too large"));
  }
  // Not plain digits: a decimal number with an integral value ("3.0") is an integer too.
  double d = 0.0;
  const NumberStatus status = try_parse_number(token.text, d);
  if (status == NumberStatus::kNotANumber || (status == NumberStatus::kOk && d != std::trunc(d))) {
    cursor.fail(token.line,
                cat("expected an integer for ", what, ", got ", quote_token(token.text)));
  }
  if (status != NumberStatus::kOk) fail_number(cursor, token, status, what);
  // |d| <= kMaxSceneNumberMagnitude: exact in int64.
  return static_cast<std::int64_t>(d);
}

}  // namespace rtsim::scenes
