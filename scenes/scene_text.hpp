#pragma once
// Reading untrusted scene text (NFF, .bpt): the file itself, messages, and locale-independent
// number parsing with std::from_chars. The text is walked as tokens by TokenCursor
// (scene_tokens.hpp). Every failure is an rtsim::InputError naming the file and the 1-based line.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

#include "common/input_error.hpp"
#include "scenes/scene_tokens.hpp"

namespace rtsim::scenes {

/// Largest scene file read_nff/read_bpt accept (1 GiB). A bound so a wrong path (a disk image,
/// /dev/zero) fails with a message instead of exhausting memory.
inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{1} << 30;

/// Largest magnitude any number in a scene file may have. Real scenes stay far below it; above
/// it, products of three coordinates (determinants, the quadratic of a sphere test) approach the
/// double range and a kernel could produce inf/NaN. Values larger than this are an InputError.
inline constexpr double kMaxSceneNumberMagnitude = 1e15;

/// Reads a whole scene file. Throws InputError(path, 0, "cannot open scene file ...") when the
/// path is missing, not a regular file, unreadable or larger than kMaxSceneFileBytes.
std::string read_scene_file(const std::string& path);

/// Builds a message from strings, string views, C strings and integers. (Also avoids GCC 12's
/// false -Wrestrict on `"literal" + std::string&&`, GCC bug 105651.)
namespace detail {
inline void append_part(std::string& out, std::string_view part) { out.append(part); }
inline void append_part(std::string& out, const char* part) { out.append(part); }
inline void append_part(std::string& out, const std::string& part) { out.append(part); }
template <typename Int>
requires std::is_integral_v<Int>
void append_part(std::string& out, Int value) { out.append(std::to_string(value)); }
}  // namespace detail

template <typename... Parts>
std::string cat(const Parts&... parts) {
  std::string out;
  (detail::append_part(out, parts), ...);
  return out;
}

/// Quotes a token for a message, shortened to a readable length.
std::string quote_token(std::string_view token);

/// What try_parse_number found.
enum class NumberStatus { kOk, kNotANumber, kOutOfRange, kNotFinite, kTooLarge };

/// Parses a whole token as a decimal floating-point number (optional sign, fraction, exponent)
/// with std::from_chars, without a message: the fast path of the readers, which build a message
/// only when it fails. Refuses anything but the whole token, NaN, infinity, values outside the
/// range of a double (overflow and underflow) and magnitudes above kMaxSceneNumberMagnitude.
NumberStatus try_parse_number(std::string_view token, double& value);

/// The InputError, at the token's line, for a token try_parse_number refused with `status`.
/// `what` names the quantity; `value_no` > 0 adds " (value N)" to it. Messages:
///   "expected a number for sphere centre and radius (x y z r) (value 2), got 'abc'"
///   "'nan' for ... is not a finite number", "number '1e400' for ... is outside the range of a
///   double", "number '1e16' for ... exceeds the magnitude limit of 1e15 ..."
[[noreturn]] void fail_number(const TokenCursor& cursor, const SceneToken& token,
                              NumberStatus status, std::string_view what, std::size_t value_no = 0);

/// try_parse_number, then fail_number when it fails.
double parse_number(const TokenCursor& cursor, const SceneToken& token, std::string_view what);

/// Parses an integer: decimal digits with an optional sign, or a decimal number with an integral
/// value ("3.0", "8e0", as programs that print every number as a float write counts). Refuses a
/// fraction ("3.5"), values outside int64 and what parse_number refuses. Range checks are the
/// caller's.
std::int64_t parse_integer(const TokenCursor& cursor, const SceneToken& token,
                           std::string_view what);

}  // namespace rtsim::scenes
