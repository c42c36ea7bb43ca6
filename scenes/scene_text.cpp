#include "scenes/scene_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
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

// --- Line-oriented reading, until the .bpt reader reads tokens too ----------------------------

namespace {

bool is_line_separator(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string line_hex_byte(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(c));
  return buf;
}

[[noreturn]] void fail_number(const LineCursor& cursor, const SceneLine& line, NumberStatus status,
                              std::string_view token, const std::string& what) {
  switch (status) {
    case NumberStatus::kOutOfRange:
      cursor.fail(line.number, cat("number ", quote_token(token), " for ", what,
                                   " is outside the range of a double"));
    case NumberStatus::kTooLarge:
      cursor.fail(line.number,
                  cat("number ", quote_token(token), " for ", what,
                      " exceeds the magnitude limit of 1e15 (kMaxSceneNumberMagnitude)"));
    case NumberStatus::kNotFinite:
      cursor.fail(line.number, cat(quote_token(token), " for ", what, " is not a finite number"));
    default:
      cursor.fail(line.number, cat("expected a number for ", what, ", got ", quote_token(token)));
  }
}

}  // namespace

LineCursor::LineCursor(std::string_view text, std::string file)
    : text_(text), file_(std::move(file)) {
  // One pass over the whole text first: count the lines (the budget lines_left() reports) and
  // reject binary bytes wherever they are, before any declared count is looked at.
  std::size_t line = 1;
  std::size_t column = 0;
  bool comment = false;       // the current line's first non-blank character is '#'
  bool seen_content = false;  // the current line has a non-blank character
  for (char ch : text_) {
    const auto c = static_cast<unsigned char>(ch);
    ++column;
    if (c == '\n') {
      ++line;
      column = 0;
      comment = seen_content = false;
      continue;
    }
    if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7F) {
      fail(line, cat("non-printable byte ", line_hex_byte(c), " at column ", column,
                     "; scene files are plain text"));
    }
    if (!seen_content && !is_line_separator(ch)) {
      seen_content = true;
      comment = (ch == '#');
    }
    if (c >= 0x80 && !comment) {
      fail(line, cat("non-ASCII byte ", line_hex_byte(c), " at column ", column,
                     " outside a comment; scene files are plain ASCII text"));
    }
  }
  // A final line without '\n' still counts.
  total_lines_ = (line - 1) + ((!text_.empty() && text_.back() != '\n') ? 1 : 0);
}

void LineCursor::fail(std::size_t line, const std::string& message) const {
  throw InputError(file_, line, message);
}

bool LineCursor::next(SceneLine& out) {
  const std::size_t save_pos = pos_;
  const std::size_t save_line = line_no_;
  const std::size_t save_consumed = lines_consumed_;
  while (pos_ < text_.size()) {
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    const std::string_view raw = text_.substr(pos_, end - pos_);
    pos_ = (end < text_.size()) ? end + 1 : end;
    ++line_no_;
    ++lines_consumed_;

    std::size_t first = 0;
    while (first < raw.size() && is_line_separator(raw[first])) ++first;
    const bool comment = first < raw.size() && raw[first] == '#';
    if (comment || first == raw.size()) continue;

    std::size_t text_end = raw.size();
    while (text_end > 0 && raw[text_end - 1] == '\r') --text_end;
    out.number = line_no_;
    out.text = raw.substr(0, text_end);
    out.tokens.clear();
    std::size_t i = first;
    while (i < raw.size()) {
      while (i < raw.size() && is_line_separator(raw[i])) ++i;
      if (i == raw.size()) break;
      const std::size_t start = i;
      while (i < raw.size() && !is_line_separator(raw[i])) ++i;
      out.tokens.push_back(raw.substr(start, i - start));
    }
    prev_pos_ = save_pos;
    prev_line_no_ = save_line;
    prev_lines_consumed_ = save_consumed;
    return true;
  }
  return false;
}

void LineCursor::unread() {
  pos_ = prev_pos_;
  line_no_ = prev_line_no_;
  lines_consumed_ = prev_lines_consumed_;
}

double parse_number(const LineCursor& cursor, const SceneLine& line, std::string_view token,
                    std::string_view what) {
  double value = 0.0;
  const NumberStatus status = try_parse_number(token, value);
  if (status != NumberStatus::kOk) fail_number(cursor, line, status, token, std::string(what));
  return value;
}

std::int64_t parse_integer(const LineCursor& cursor, const SceneLine& line, std::string_view token,
                           std::string_view what) {
  const std::string_view t = strip_leading_plus(token);
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value, 10);
  if (ec == std::errc::result_out_of_range) {
    cursor.fail(line.number,
                cat("integer ", quote_token(token), " for ", what, " is far too large"));
  }
  if (ec != std::errc{} || ptr != t.data() + t.size()) {
    cursor.fail(line.number, cat("expected an integer for ", what, ", got ", quote_token(token)));
  }
  return value;
}

void parse_numbers(const LineCursor& cursor, const SceneLine& line, std::size_t first,
                   std::size_t count, std::string_view what, double* out) {
  const std::size_t got = line.tokens.size() > first ? line.tokens.size() - first : 0;
  const std::size_t n = got < count ? got : count;
  for (std::size_t i = 0; i < n; ++i) {
    const NumberStatus status = try_parse_number(line.tokens[first + i], out[i]);
    if (status != NumberStatus::kOk) {
      fail_number(cursor, line, status, line.tokens[first + i], cat(what, " (value ", i + 1, ")"));
    }
  }
  if (got != count) {
    std::string msg = cat("expected ", count, " numbers for ", what, ", got ", got);
    if (got > count) {
      msg += cat(" (unexpected trailing ", quote_token(line.tokens[first + count]), ")");
    }
    cursor.fail(line.number, msg);
  }
}

}  // namespace rtsim::scenes
