#include "common/seed_citation.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace rtsim {

namespace {

// The seeds (../shared/reference/notes/ has each one's extraction).
constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kSeeds = {{
    {"000", "Ullner 1983"},                   // Parallel Machines for Computer Graphics
    {"001", "Gaudet 1985"},                   // A Parallel Architecture for Ray Tracing
    {"002", "Wang, Lewis & Hung c. 2000"},    // A Pipelined Architecture for Ray/Bezier ...
    {"004", "Interactive 3D Graphics 1995"},  // the 1995 symposium's papers
}};

bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

/// Reads the digits at `at` into `number` and moves `at` past them; false if there are none.
bool digits_at(std::string_view text, std::size_t& at, std::string& number) {
  std::size_t end = at;
  while (end < text.size() && digit(text[end])) ++end;
  if (end == at) return false;
  number.assign(text.substr(at, end - at));
  at = end;
  return true;
}

/// Reads "L123" at `at`; false if there is none.
bool line_ref(std::string_view text, std::size_t& at, std::string& number) {
  if (at >= text.size() || text[at] != 'L') return false;
  std::size_t after = at + 1;
  if (!digits_at(text, after, number)) return false;
  at = after;
  return true;
}

/// `chunk` with each line reference ("L859", "L2084-L2108") written "line 859", "lines
/// 2084-2108": the text after a seed's citation, whose references are that seed's lines.
std::string lines_for_reader(std::string_view chunk) {
  const auto alnum = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
  std::string out;
  std::size_t i = 0;
  while (i < chunk.size()) {
    std::size_t k = i;
    std::string from, to;
    if ((i == 0 || !alnum(chunk[i - 1])) && line_ref(chunk, k, from)) {
      if (k < chunk.size() && chunk[k] == '-') {  // a range
        std::size_t r = k + 1;
        if (r < chunk.size() && chunk[r] == 'L') ++r;
        if (digits_at(chunk, r, to)) k = r;
      }
      if (k >= chunk.size() || !alnum(chunk[k])) {  // a whole word only: "L9X" is no line
        out += to.empty() ? "line " : "lines ";
        out += from;
        if (!to.empty()) {
          out += '-';
          out += to;
        }
        i = k;
        continue;
      }
    }
    out += chunk[i++];
  }
  return out;
}

constexpr std::string_view kSeed = "seed ";

/// The number of the seed cited at `at` (where "seed " starts): three digits of a seed this
/// project has, not followed by another digit; "" otherwise.
std::string_view seed_at(std::string_view text, std::size_t at) {
  const std::size_t from = at + kSeed.size();
  if (from + 3 > text.size() || (from + 3 < text.size() && digit(text[from + 3]))) return {};
  const std::string_view number = text.substr(from, 3);
  return seed_author(number).empty() ? std::string_view() : number;
}

}  // namespace

std::vector<std::string> cited_seeds(std::string_view text) {
  std::vector<std::string> out;
  for (std::size_t at = text.find(kSeed); at != std::string_view::npos;
       at = text.find(kSeed, at + 1)) {
    const std::string_view number = seed_at(text, at);
    if (!number.empty() && std::find(out.begin(), out.end(), number) == out.end())
      out.emplace_back(number);
  }
  return out;
}

std::string_view seed_author(std::string_view number) {
  for (const auto& [n, who] : kSeeds)
    if (n == number) return who;
  return {};
}

std::string cite_seeds(std::string_view text) {
  std::string out;
  std::size_t i = 0;
  bool cited = false;  // a seed was cited: later bare line references are its lines
  const auto copy = [&](std::string_view chunk) {
    out += cited ? lines_for_reader(chunk) : std::string(chunk);
  };
  while (i < text.size()) {
    const std::size_t at = text.find(kSeed, i);
    if (at == std::string_view::npos) break;
    const std::string_view number = seed_at(text, at);
    if (number.empty()) {
      copy(text.substr(i, at + kSeed.size() - i));
      i = at + kSeed.size();
      continue;
    }
    copy(text.substr(i, at - i));
    out.append(seed_author(number));
    cited = true;
    std::size_t j = at + kSeed.size() + 3;
    // The lines cited right after: "L883, L961", "L572-L588", "L572-588".
    std::string lines;
    int count = 0;
    std::size_t k = j;
    if (k < text.size() && text[k] == ' ') ++k;
    std::string n;
    while (line_ref(text, k, n)) {
      if (count++ > 0) lines += ", ";
      lines += n;
      if (k < text.size() && text[k] == '-') {  // a range: "L572-L588" or "L572-588"
        std::size_t r = k + 1;
        if (r < text.size() && text[r] == 'L') ++r;
        std::string to;
        if (digits_at(text, r, to)) {
          lines += '-';
          lines += to;
          ++count;
          k = r;
        }
      }
      j = k;
      if (k + 2 < text.size() && text[k] == ',' && text[k + 1] == ' ' && text[k + 2] == 'L') {
        k += 2;
        continue;
      }
      break;
    }
    if (count > 0) out.append(count > 1 ? ", lines " : ", line ").append(lines);
    i = j;
  }
  copy(text.substr(std::min(i, text.size())));
  return out;
}

}  // namespace rtsim
