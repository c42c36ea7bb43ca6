#include "firmware/scanline/merging.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rtsim::scanline {

namespace {

constexpr int kPassBound = 2 * kWordSteps;

/// Step 1's key: line, then x, then z (the raster scan's order; nearer first at one point).
std::tuple<int, int, int> key(const Segment& s) { return {s.y, s.left.x, s.left.z}; }

/// a x + b z + c for the line through (x1, z1) and (x2, z2), x1 <= x2: positive in front (nearer,
/// smaller z) where x1 < x2 (L1413-L1419).
struct Line {
  std::int64_t a, b, c;
  Line(int x1, int z1, int x2, int z2)
      : a(z2 - z1),
        b(x1 - x2),
        c(static_cast<std::int64_t>(x2) * z1 - static_cast<std::int64_t>(x1) * z2) {}
  std::int64_t at(int x, int z) const { return a * x + b * z + c; }
};

}  // namespace

MergeTally& MergeTally::operator+=(const MergeTally& o) {
  for (std::size_t k = 0; k < passes.size(); ++k) passes[k] += o.passes[k];
  return *this;
}

std::uint64_t MergeTally::total() const {
  std::uint64_t n = 0;
  for (const auto p : passes) n += p;
  return n;
}

Segment cut(const Segment& s, int a, int b) {
  Segment out = s;
  out.left = point_at(s, a);
  out.right = point_at(s, b);
  return out;
}

void MergingProcessor::give(int k, const Segment& s) {
  held_[static_cast<std::size_t>(k)] = s;
  classified_ = false;
  since_fetch_ = 0;
}

MergingProcessor::Pass MergingProcessor::pass() {
  Pass p = step();
  if (p.out && !p.out->mark) last_line_ = std::max<int>(last_line_, p.out->y);
  return p;
}

MergingProcessor::Pass MergingProcessor::step() {
  Pass p;
  Segment& s0 = *held_[0];
  Segment& s1 = *held_[1];
  if (s0.dummy() && s1.dummy()) {
    finished_ = true;
    p.out = s0;
    p.dropped = s1.journey;
    held_[0].reset();
    held_[1].reset();
    return p;
  }
  const auto fetch = [&](int k) { held_[static_cast<std::size_t>(k)].reset(); };
  if (s0.mark || s1.mark) {
    // The earlier mark (either, if both are): its input sends nothing before its line.
    const int m = s0.mark && (!s1.mark || s0.y <= s1.y) ? 0 : 1;
    const Segment& mark = *held_[static_cast<std::size_t>(m)];
    const Segment& seg = *held_[static_cast<std::size_t>(1 - m)];
    if (!seg.mark && seg.y < mark.y) {
      p.kind = MergeCase::Apart;
      p.out = seg;
      p.from = 1 - m;
      fetch(1 - m);
      return p;
    }
    p.kind = MergeCase::Mark;
    if (mark.y > last_line_) {
      p.out = mark;
      p.from = m;
      last_line_ = mark.y;
    }
    fetch(m);
    return p;
  }
  if (!classified_) {
    visible_ = key(s1) < key(s0) ? 1 : 0;
    classified_ = true;
  }
  const int o = 1 - visible_;
  Segment& v = *held_[static_cast<std::size_t>(visible_)];
  Segment& other = *held_[static_cast<std::size_t>(o)];

  // 2: apart — V on an earlier line, or ending before O begins.
  if (v.y < other.y || (v.y == other.y && v.right.x < other.left.x) ||
      ++since_fetch_ > kPassBound) {
    p.kind = MergeCase::Apart;
    p.out = v;
    p.from = visible_;
    fetch(visible_);
    return p;
  }
  const Line lv(v.left.x, v.left.z, v.right.x, v.right.z);
  // 3: O's left end in front of V: V shows only up to it.
  if (other.left.x > v.left.x && lv.at(other.left.x, other.left.z) > 0) {
    p.kind = MergeCase::Disappears;
    p.out = cut(v, v.left.x, other.left.x - 1);
    p.from = p.shares = visible_;
    v = cut(v, other.left.x, v.right.x);
    visible_ = o;
    return p;
  }
  // 4: O's right end in front of V's line and of the line from O's left end to V's right end.
  const Line lov(other.left.x, other.left.z, v.right.x, v.right.z);
  if (lv.at(other.right.x, other.right.z) > 0 && lov.at(other.right.x, other.right.z) > 0) {
    const Line lo(other.left.x, other.left.z, other.right.x, other.right.z);
    const std::int64_t den = lv.a * lo.b - lo.a * lv.b;
    if (den != 0) {
      const double xi = static_cast<double>(lv.b * lo.c - lo.b * lv.c) / static_cast<double>(den);
      const int lo_x = std::max(v.left.x, other.left.x), hi_x = std::min(v.right.x, other.right.x);
      const int x = static_cast<int>(
          std::clamp(std::lround(std::isfinite(xi) ? xi : lo_x), long(lo_x), long(hi_x)));
      p.kind = MergeCase::Intersects;
      if (x - 1 >= v.left.x) {
        p.out = cut(v, v.left.x, x - 1);
        p.from = p.shares = visible_;
      }
      // Both keep the crossing's step (O's in front from there; V's is clipped or hidden by
      // it next): with whole steps, O starting a step after it (the seed's epsilon) would
      // leave the step to V's part, which O then hides — a one-step hole.
      v = cut(v, x, v.right.x);
      other = cut(other, x, other.right.x);
      visible_ = o;
      return p;
    }
  }
  // 5: O comes out from behind V.
  if (other.right.x > v.right.x) {
    p.kind = MergeCase::Protrudes;
    other = cut(other, v.right.x + 1, other.right.x);
    p.out = v;
    p.from = visible_;
    fetch(visible_);
    return p;
  }
  // 6: O is hidden.
  p.kind = MergeCase::Hidden;
  p.dropped = other.journey;
  fetch(o);
  return p;
}

std::vector<Segment> merge_streams(const std::vector<Segment>& a, const std::vector<Segment>& b,
                                   MergeTally* tally) {
  std::vector<Segment> out;
  out.reserve(a.size() + b.size());
  MergingProcessor mp;
  std::size_t next[2] = {0, 0};
  const std::vector<Segment>* in[2] = {&a, &b};
  while (!mp.finished()) {
    for (int k = 0; k < 2; ++k) {
      if (!mp.needs(k)) continue;
      const auto& s = *in[k];
      // A stream that ended without its dummy ends as if it had one.
      mp.give(k, next[k] < s.size() ? s[next[k]++] : dummy_segment());
    }
    const MergingProcessor::Pass p = mp.pass();
    if (tally) ++tally->passes[static_cast<std::size_t>(p.kind)];
    if (p.out) out.push_back(*p.out);
  }
  return out;
}

}  // namespace rtsim::scanline
