#include "common/suggest.hpp"

#include <algorithm>
#include <tuple>

namespace rtsim {
namespace {

std::string_view last_segment(std::string_view name) {
  const std::size_t dot = name.rfind('.');
  return dot == std::string_view::npos ? name : name.substr(dot + 1);
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // d[i][j] = distance between the first i bytes of a and the first j bytes of b; three rows
  // suffice because a transposition looks back two rows.
  const std::size_t n = b.size();
  std::vector<std::size_t> before(n + 1), previous(n + 1), current(n + 1);
  for (std::size_t j = 0; j <= n; ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= n; ++j) {
      const std::size_t substitution = a[i - 1] == b[j - 1] ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[n];
}

std::vector<std::string> closest_names(std::string_view unknown,
                                       const std::vector<std::string_view>& candidates,
                                       std::size_t max_count) {
  const std::string_view leaf = last_segment(unknown);
  const std::size_t whole_limit = std::max<std::size_t>(1, unknown.size() / 4);
  const std::size_t leaf_limit = leaf.size() / 4;

  std::vector<std::tuple<std::size_t, std::size_t, std::string_view>> scored;  // score, whole, name
  const auto length_gap = [](std::string_view a, std::string_view b) {
    return a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
  };
  for (std::string_view name : candidates) {
    // An edit distance is at least the difference of the lengths: a candidate that cannot be
    // close by either measure is skipped before its distances are computed (each costs the
    // product of the lengths, seconds for a megabyte-long unknown name).
    const std::size_t whole_gap = length_gap(unknown, name);
    const bool whole_may_be_close = whole_gap <= whole_limit && whole_gap < unknown.size();
    if (!whole_may_be_close && length_gap(leaf, last_segment(name)) > leaf_limit) continue;
    const std::size_t whole = edit_distance(unknown, name);
    const std::size_t leaf_distance = edit_distance(leaf, last_segment(name));
    const bool close =
        (whole <= whole_limit && whole < unknown.size()) || leaf_distance <= leaf_limit;
    if (!close) continue;
    scored.emplace_back(std::min(whole, leaf_distance + 1), whole, name);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scored.size() && i < max_count; ++i) {
    out.emplace_back(std::get<2>(scored[i]));
  }
  return out;
}

std::string did_you_mean(std::string_view unknown,
                         const std::vector<std::string_view>& candidates) {
  const auto near = closest_names(unknown, candidates, 1);
  if (near.empty()) return {};
  std::string tail = "; did you mean '";
  tail += near.front();
  tail += "'?";
  return tail;
}

}  // namespace rtsim
