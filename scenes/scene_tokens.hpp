#pragma once
// Scene text (NFF, .bpt) as a stream of whitespace-separated tokens, the way the reference NFF
// readers read it with scanf: line ends are whitespace like any other, so an entity may sit on
// one line or spread over several. Each token keeps its 1-based line for messages.
//
// The rules of the text (docs/scene-formats.md):
// - separators are space, tab and line ends; a line ends at "\n", "\r\n" or a lone "\r" (files
//   saved with classic Mac OS line ends), each counted as one line;
// - a '#' that starts a token begins a comment up to the end of its line ('#' inside a token is
//   part of it, so "1#2" is one bad number, not "1" and a comment);
// - a UTF-8 byte-order mark (EF BB BF) at the very start is skipped;
// - any other control byte anywhere, or a non-ASCII byte outside a comment, is an InputError at
//   its line and column: scene files are plain text.
#include <cstddef>
#include <string>
#include <string_view>

namespace rtsim::scenes {

/// One token: a view into the text given to the TokenCursor (which must outlive it) and the line
/// it is on.
struct SceneToken {
  std::string_view text;
  std::size_t line = 0;
};

/// Walks the tokens of a scene text lazily, one token of lookahead. The constructor scans the
/// whole text once: it rejects binary bytes before any declared count is looked at, and counts
/// the tokens so a declared count can be checked against what the file still holds
/// (tokens_left()) before anything is allocated for it.
class TokenCursor {
 public:
  TokenCursor(std::string_view text, std::string file);

  /// The next token, not consumed; nullptr at the end of the text. Valid until next()/skip().
  const SceneToken* peek() const { return has_next_ ? &next_ : nullptr; }
  /// Consumes the next token into `out`; false at the end of the text.
  bool next(SceneToken& out) {
    if (!has_next_) return false;
    out = next_;
    skip();
    return true;
  }
  /// Consumes the token peek() shows (none at the end of the text).
  void skip() {
    if (!has_next_) return;
    last_line_ = next_.line;
    ++consumed_;
    advance();
  }

  /// Tokens not consumed yet: an upper bound on the numbers the file can still give.
  std::size_t tokens_left() const { return total_tokens_ - consumed_; }
  /// Line of the last token consumed (0 before the first).
  std::size_t last_line() const { return last_line_; }
  /// Number of the last line of the text (for messages about the file as a whole).
  std::size_t last_line_number() const { return total_lines_; }
  /// `token` and the rest of its line, without the line end (for messages).
  std::string_view rest_of_line(const SceneToken& token) const;
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(std::size_t line, const std::string& message) const;

 private:
  void scan_all();
  void advance();

  std::string_view text_;
  std::string file_;
  std::size_t total_lines_ = 0;
  std::size_t total_tokens_ = 0;
  std::size_t consumed_ = 0;
  std::size_t last_line_ = 0;
  // Where advance() continues, the line there, and the token it found last.
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  SceneToken next_;
  bool has_next_ = false;
};

}  // namespace rtsim::scenes
