#include "scenes/scene_tokens.hpp"

#include <array>
#include <cstdio>

#include "common/input_error.hpp"
#include "scenes/scene_text.hpp"

namespace rtsim::scenes {

namespace {

/// What a byte is to the tokenizer.
enum ByteClass : unsigned char {
  kWordByte,  // part of a token (printable ASCII but '#')
  kBlank,     // space, tab
  kLineFeed,  // '\n'
  kReturn,    // '\r': a line end of its own unless "\r\n"
  kHash,      // '#': a comment when it starts a token
  kControl,   // any other control byte, and DEL
  kNonAscii,  // 0x80..0xFF: allowed in comments only
};

constexpr std::array<ByteClass, 256> make_byte_classes() {
  std::array<ByteClass, 256> classes{};
  for (std::size_t c = 0; c < classes.size(); ++c) {
    classes[c] = c < 0x20 || c == 0x7F ? kControl : c >= 0x80 ? kNonAscii : kWordByte;
  }
  classes[' '] = classes['\t'] = kBlank;
  classes['\n'] = kLineFeed;
  classes['\r'] = kReturn;
  classes['#'] = kHash;
  return classes;
}

constexpr std::array<ByteClass, 256> kByteClass = make_byte_classes();

ByteClass byte_class(char c) { return kByteClass[static_cast<unsigned char>(c)]; }

/// Separators between tokens: blanks and line ends.
bool is_separator(char c) {
  const ByteClass k = byte_class(c);
  return k == kBlank || k == kLineFeed || k == kReturn;
}

constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

std::string hex_byte(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(c));
  return buf;
}

}  // namespace

TokenCursor::TokenCursor(std::string_view text, std::string file)
    : text_(text), file_(std::move(file)) {
  if (text_.starts_with(kUtf8ByteOrderMark)) pos_ = kUtf8ByteOrderMark.size();
  scan_all();
  advance();
}

void TokenCursor::fail(std::size_t line, const std::string& message) const {
  throw InputError(file_, line, message);
}

void TokenCursor::scan_all() {
  // One pass over the whole text: count the lines and the tokens outside comments, and reject
  // binary bytes wherever they are, before any declared count is looked at.
  const char* p = text_.data();
  const std::size_t n = text_.size();
  std::size_t line = 1;
  std::size_t line_start = pos_;
  bool in_token = false;
  bool in_comment = false;
  for (std::size_t i = pos_; i < n; ++i) {
    switch (byte_class(p[i])) {
      case kWordByte:
        if (!in_token && !in_comment) {
          in_token = true;
          ++total_tokens_;
        }
        break;
      case kBlank:
        in_token = false;
        break;
      case kLineFeed:
        ++line;
        line_start = i + 1;
        in_token = in_comment = false;
        break;
      case kReturn:
        in_token = false;
        if (i + 1 < n && p[i + 1] == '\n') break;  // "\r\n": the '\n' ends the line
        ++line;
        line_start = i + 1;
        in_comment = false;
        break;
      case kHash:
        if (!in_token && !in_comment) in_comment = true;
        break;
      case kControl:
        fail(line, cat("non-printable byte ", hex_byte(static_cast<unsigned char>(p[i])),
                       " at column ", i - line_start + 1, "; scene files are plain text"));
      case kNonAscii:
        if (in_comment) break;
        {
          const bool utf16 =
              i == 0 && n >= 2 &&
              ((p[0] == '\xFF' && p[1] == '\xFE') || (p[0] == '\xFE' && p[1] == '\xFF'));
          fail(line,
               cat("non-ASCII byte ", hex_byte(static_cast<unsigned char>(p[i])), " at column ",
                   i - line_start + 1, " outside a comment; scene files are plain ASCII text",
                   utf16 ? " (this file starts with a UTF-16 byte-order mark: save it as "
                           "ASCII or UTF-8)"
                         : ""));
        }
    }
  }
  // A last line without a line end still counts.
  const bool open_last_line = n > pos_ && p[n - 1] != '\n' && p[n - 1] != '\r';
  total_lines_ = (line - 1) + (open_last_line ? 1 : 0);
}

void TokenCursor::advance() {
  const char* p = text_.data();
  const std::size_t n = text_.size();
  std::size_t i = pos_;
  std::size_t line = line_;
  has_next_ = false;
  while (i < n) {
    switch (byte_class(p[i])) {
      case kBlank:
        ++i;
        continue;
      case kLineFeed:
        ++i;
        ++line;
        continue;
      case kReturn:
        ++i;
        if (i < n && p[i] == '\n') ++i;
        ++line;
        continue;
      case kHash:
        while (i < n && p[i] != '\n' && p[i] != '\r') ++i;
        continue;
      default:
        break;
    }
    const std::size_t start = i;
    while (i < n && !is_separator(p[i])) ++i;
    next_ = SceneToken{text_.substr(start, i - start), line};
    has_next_ = true;
    break;
  }
  pos_ = i;
  line_ = line;
}

void TokenCursor::skip() {
  if (!has_next_) return;
  last_line_ = next_.line;
  ++consumed_;
  advance();
}

std::string_view TokenCursor::rest_of_line(const SceneToken& token) const {
  const auto start = static_cast<std::size_t>(token.text.data() - text_.data());
  std::size_t end = text_.find_first_of("\r\n", start);
  if (end == std::string_view::npos) end = text_.size();
  return text_.substr(start, end - start);
}

}  // namespace rtsim::scenes
