#include "scenes/scene_tokens.hpp"

#include <array>
#include <cstdio>

#include "common/input_error.hpp"
#include "scenes/scene_text.hpp"

namespace rtsim::scenes {

namespace {

/// What a byte is to the tokenizer. The two classes a token is made of come first, so "inside a
/// token" is one comparison (<= kHash).
enum ByteClass : unsigned char {
  kWordByte,  // part of a token (printable ASCII but '#')
  kHash,      // '#': a comment when it starts a token, else part of the token
  kBlank,     // space, tab
  kLineFeed,  // '\n'
  kReturn,    // '\r': a line end of its own unless "\r\n"
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

/// A byte that continues a token.
bool in_token(char c) { return byte_class(c) <= kHash; }

bool is_line_end(char c) { return c == '\n' || c == '\r'; }

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
  const auto fail_byte = [&](std::size_t i) {
    const auto c = static_cast<unsigned char>(p[i]);
    const std::size_t column = i - line_start + 1;
    if (byte_class(p[i]) == kControl) {
      fail(line, cat("non-printable byte ", hex_byte(c), " at column ", column,
                     "; scene files are plain text"));
    }
    const bool utf16 = i == 0 && n >= 2 &&
                       ((p[0] == '\xFF' && p[1] == '\xFE') || (p[0] == '\xFE' && p[1] == '\xFF'));
    fail(line, cat("non-ASCII byte ", hex_byte(c), " at column ", column,
                   " outside a comment; scene files are plain ASCII text",
                   utf16 ? " (this file starts with a UTF-16 byte-order mark: save it as ASCII or "
                           "UTF-8)"
                         : ""));
  };
  std::size_t i = pos_;
  while (i < n) {
    switch (byte_class(p[i])) {
      case kWordByte:
        ++total_tokens_;
        while (++i < n && in_token(p[i])) {
        }
        break;
      case kBlank:
        ++i;
        break;
      case kLineFeed:
        ++i;
        ++line;
        line_start = i;
        break;
      case kReturn:
        ++i;
        if (i < n && p[i] == '\n') ++i;
        ++line;
        line_start = i;
        break;
      case kHash:  // a comment: any byte but a control byte, up to the line end
        while (++i < n && !is_line_end(p[i])) {
          if (byte_class(p[i]) == kControl) fail_byte(i);
        }
        break;
      default:
        fail_byte(i);
    }
  }
  // A last line without a line end still counts.
  const bool open_last_line = n > pos_ && !is_line_end(p[n - 1]);
  total_lines_ = (line - 1) + (open_last_line ? 1 : 0);
}

void TokenCursor::advance() {
  // The text passed scan_all(): outside comments there are only token bytes, blanks and line
  // ends.
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
        while (++i < n && !is_line_end(p[i])) {
        }
        continue;
      default:
        break;
    }
    const std::size_t start = i;
    while (++i < n && in_token(p[i])) {
    }
    next_ = SceneToken{text_.substr(start, i - start), line};
    has_next_ = true;
    break;
  }
  pos_ = i;
  line_ = line;
}

std::string_view TokenCursor::rest_of_line(const SceneToken& token) const {
  const auto start = static_cast<std::size_t>(token.text.data() - text_.data());
  std::size_t end = text_.find_first_of("\r\n", start);
  if (end == std::string_view::npos) end = text_.size();
  return text_.substr(start, end - start);
}

}  // namespace rtsim::scenes
