#include "params/toml_file.hpp"

#include <utility>
#include <vector>

#include "common/input_error.hpp"

namespace rtsim::params {
namespace {

/// Walks a TOML text statement by statement, counting the parts of every key and adding those
/// of the header above it and of the keys of the inline tables around it. Iterative (an explicit
/// stack for arrays and inline tables), so no input can make it recurse.
class KeyDepthScanner {
 public:
  KeyDepthScanner(std::string_view text, std::size_t max_depth) : t_(text), max_(max_depth) {}

  std::size_t first_too_deep() {
    std::size_t header = 0;  // parts of the [table] or [[array]] header in force
    while (!at_end()) {
      const char ch = t_[i_];
      if (ch == ' ' || ch == '\t' || ch == '\r') {
        ++i_;
      } else if (ch == '\n') {
        ++line_;
        ++i_;
      } else if (ch == '#') {
        skip_to_line_end();
      } else if (ch == '[') {
        i_ += (i_ + 1 < t_.size() && t_[i_ + 1] == '[') ? 2 : 1;
        const std::size_t line = line_;
        const std::size_t parts = key_parts(']');
        if (parts == 0) return 0;
        if (parts > max_) return line;
        header = parts;
        skip_to_line_end();
      } else {
        const std::size_t line = line_;
        const std::size_t parts = key_parts('=');
        if (parts == 0) return 0;
        if (header + parts > max_) return line;
        ++i_;  // '='
        if (const std::size_t bad = value(header + parts); bad != 0 || lost_) return bad;
      }
    }
    return 0;
  }

 private:
  std::string_view t_;
  std::size_t max_;
  std::size_t i_ = 0;
  std::size_t line_ = 1;
  bool lost_ = false;  ///< the text is not TOML as this scanner reads it: toml++ will say why

  bool at_end() const { return i_ >= t_.size(); }
  void skip_blanks() {
    while (!at_end() && (t_[i_] == ' ' || t_[i_] == '\t')) ++i_;
  }
  void skip_to_line_end() {
    while (!at_end() && t_[i_] != '\n') ++i_;
  }
  static bool bare(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  }

  /// Skips the string whose opening quote is at i_ (basic or literal, one line or multi-line).
  bool skip_string() {
    const char q = t_[i_];
    const std::string_view three = q == '"' ? "\"\"\"" : "'''";
    if (t_.substr(i_, 3) == three) {
      i_ += 3;
      while (!at_end()) {
        if (q == '"' && t_[i_] == '\\') {
          if (i_ + 1 < t_.size() && t_[i_ + 1] == '\n') ++line_;
          i_ += 2;
        } else if (t_.substr(i_, 3) == three) {
          i_ += 3;
          // Up to two more quotes belong to the content (`"""a"""""`).
          for (int extra = 0; extra < 2 && !at_end() && t_[i_] == q; ++extra) ++i_;
          return true;
        } else {
          if (t_[i_] == '\n') ++line_;
          ++i_;
        }
      }
      return false;
    }
    ++i_;
    while (!at_end() && t_[i_] != '\n') {
      if (q == '"' && t_[i_] == '\\') {
        i_ += 2;
      } else if (t_[i_++] == q) {
        return true;
      }
    }
    return false;
  }

  /// Reads a dotted key up to `end` (left at i_); its number of parts, or 0 if it is no key.
  std::size_t key_parts(char end) {
    std::size_t parts = 0;
    for (;;) {
      skip_blanks();
      if (at_end()) return 0;
      if (t_[i_] == '"' || t_[i_] == '\'') {
        if (!skip_string()) return 0;
      } else {
        const std::size_t start = i_;
        while (!at_end() && bare(t_[i_])) ++i_;
        if (i_ == start) return 0;
      }
      ++parts;
      skip_blanks();
      if (!at_end() && t_[i_] == '.') {
        ++i_;
        continue;
      }
      return !at_end() && t_[i_] == end ? parts : 0;
    }
  }

  /// Reads the value after a key of depth `depth`, to the end of its statement; the line of a
  /// key inside it that is too deep, or 0.
  std::size_t value(std::size_t depth) {
    std::vector<std::pair<char, std::size_t>> open;  // '[' or '{', and the depth around it
    // A key of an inline table: its parts below the table's depth.
    const auto inline_key = [&]() -> std::size_t {
      skip_blanks();
      if (!at_end() && t_[i_] == '}') return 0;  // `{}` or a closing brace
      const std::size_t line = line_;
      const std::size_t parts = key_parts('=');
      if (parts == 0) {
        lost_ = true;
        return 0;
      }
      depth = open.back().second + parts;
      if (depth > max_) return line;
      ++i_;  // '='
      return 0;
    };
    while (!at_end()) {
      const char ch = t_[i_];
      if (ch == '\n') {
        ++line_;
        ++i_;
        if (open.empty()) return 0;
      } else if (ch == '#') {
        skip_to_line_end();
      } else if (ch == '"' || ch == '\'') {
        if (!skip_string()) {
          lost_ = true;
          return 0;
        }
      } else if (ch == '[' || ch == '{') {
        ++i_;
        open.emplace_back(ch, depth);
        if (ch == '{')
          if (const std::size_t bad = inline_key(); bad != 0 || lost_) return bad;
      } else if (ch == ']' || ch == '}') {
        if (open.empty() || open.back().first != (ch == ']' ? '[' : '{')) {
          lost_ = true;
          return 0;
        }
        depth = open.back().second;
        open.pop_back();
        ++i_;
      } else if (ch == ',') {
        ++i_;
        if (!open.empty() && open.back().first == '{')
          if (const std::size_t bad = inline_key(); bad != 0 || lost_) return bad;
      } else {
        ++i_;
      }
    }
    return 0;
  }
};

}  // namespace

std::size_t first_too_deep_key(std::string_view text, std::size_t max_depth) {
  return KeyDepthScanner(text, max_depth).first_too_deep();
}

toml::table parse_toml(std::string_view text, const std::string& origin) {
  if (const std::size_t line = first_too_deep_key(text))
    throw InputError(
        origin, line,
        "a key nested more than " + std::to_string(kMaxTomlKeyDepth) +
            " levels deep (counting its dotted parts, its [table] header's and "
            "those of the inline tables around it); rtsim's parameter names have at most 4 parts");
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw InputError(origin, e.source().begin.line, std::string(e.description()));
  }
}

}  // namespace rtsim::params
