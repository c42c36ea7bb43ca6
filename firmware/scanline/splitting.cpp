#include "firmware/scanline/splitting.hpp"

#include <stdexcept>

namespace rtsim::scanline {

namespace {
/// A part in its half's coordinates: steps [a, b] of the whole become [2(a - o), 2(b - o) + 1].
Segment rescaled(Segment part, int origin) {
  part.left.x = static_cast<std::int16_t>(2 * (part.left.x - origin));
  part.right.x = static_cast<std::int16_t>(2 * (part.right.x - origin) + 1);
  return part;
}
}  // namespace

SplitParts split_segment(const Segment& s) {
  SplitParts out;
  if (s.dummy()) {
    out.left = s;
    out.right = s;
    return out;
  }
  // Fig. 3-25: x_R <= 1/2 left, x_L > 1/2 right, else break at 1/2 and 1/2 + epsilon.
  if (s.right.x < kSplitAt) {
    out.left = rescaled(s, 0);
  } else if (s.left.x >= kSplitAt) {
    out.right = rescaled(s, kSplitAt);
  } else {
    out.left = rescaled(cut(s, s.left.x, kSplitAt - 1), 0);
    out.right = rescaled(cut(s, kSplitAt, s.right.x), kSplitAt);
    out.broken = true;
  }
  return out;
}

SplittingProcessor::Sent SplittingProcessor::take(const Segment& s) {
  Sent out;
  if (s.mark) {
    // Nothing comes before line y: each output that has not reached it learns so.
    for (int k = 0; k < 2; ++k)
      if (last_line_[k] < s.y) {
        out.to[k] = s;
        last_line_[k] = s.y;
      }
    return out;
  }
  const SplitParts p = split_segment(s);
  out.to[0] = p.left;
  out.to[1] = p.right;
  out.broken = p.broken;
  if (s.dummy()) return out;
  for (int k = 0; k < 2; ++k) {
    // The other output has nothing of this line yet: it learns the line has begun.
    if (!out.to[k] && last_line_[k] < s.y) out.to[k] = line_mark(s.y);
    if (out.to[k]) last_line_[k] = s.y;
  }
  return out;
}

std::pair<std::vector<Segment>, std::vector<Segment>> split_stream(const std::vector<Segment>& in,
                                                                   std::uint64_t* broken) {
  std::pair<std::vector<Segment>, std::vector<Segment>> out;
  SplittingProcessor sp;
  for (const Segment& s : in) {
    const SplittingProcessor::Sent sent = sp.take(s);
    if (sent.to[0]) out.first.push_back(*sent.to[0]);
    if (sent.to[1]) out.second.push_back(*sent.to[1]);
    if (broken && sent.broken) ++*broken;
    if (s.dummy()) return out;
  }
  // A stream that ended without its dummy ends as if it had one.
  out.first.push_back(dummy_segment());
  out.second.push_back(dummy_segment());
  return out;
}

std::vector<std::pair<std::size_t, std::size_t>> subtree_ranges(std::size_t leaves, int levels) {
  if (levels < 0 || leaves < (std::size_t{1} << levels))
    throw std::invalid_argument("subtree_ranges: fewer leaves than subtrees");
  std::vector<std::pair<std::size_t, std::size_t>> ranges{{0, leaves}};
  for (int l = 0; l < levels; ++l) {
    std::vector<std::pair<std::size_t, std::size_t>> next;
    for (const auto& [lo, hi] : ranges) {
      const std::size_t mid = (lo + hi) / 2;
      next.emplace_back(lo, mid);
      next.emplace_back(mid, hi);
    }
    ranges = std::move(next);
  }
  return ranges;
}

SplitCounts split_counts(int levels) {
  if (levels <= 0) return {};
  const std::uint64_t streams = std::uint64_t{1} << levels;
  return {.splitters = static_cast<std::uint64_t>(levels) * streams,
          .extra_merging = static_cast<std::uint64_t>(levels - 1) * streams + 1};
}

std::vector<SplitPair> split_stage(int levels, int stage) {
  const std::size_t strips = std::size_t{1} << stage;
  const std::size_t per_strip = std::size_t{1} << (levels - stage);  // streams a strip, before
  std::vector<SplitPair> pairs;
  for (std::size_t strip = 0; strip < strips; ++strip) {
    // After the stage, strip k's halves are strips 2k and 2k + 1, each of per_strip / 2 streams.
    const std::size_t base = strip * per_strip;
    for (std::size_t j = 0; j < per_strip / 2; ++j)
      pairs.push_back({.first = base + 2 * j,
                       .second = base + 2 * j + 1,
                       .left = (2 * strip) * (per_strip / 2) + j,
                       .right = (2 * strip + 1) * (per_strip / 2) + j});
  }
  return pairs;
}

std::vector<std::vector<Segment>> split_network(std::vector<std::vector<Segment>> roots, int levels,
                                                MergeTally* tally, std::uint64_t* broken) {
  for (int stage = 0; stage < levels; ++stage) {
    std::vector<std::vector<Segment>> next(roots.size());
    for (const SplitPair& p : split_stage(levels, stage)) {
      auto a = split_stream(roots[p.first], broken);
      auto b = split_stream(roots[p.second], broken);
      next[p.left] = merge_streams(a.first, b.first, tally);
      next[p.right] = merge_streams(a.second, b.second, tally);
    }
    roots = std::move(next);
  }
  return roots;
}

}  // namespace rtsim::scanline
