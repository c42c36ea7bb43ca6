#include "firmware/hiddenline/cleanup_processor.hpp"

#include <utility>

namespace rtsim::hiddenline {

void CleanupProcessor::receive(const Message& m, std::vector<Message>& out) {
  switch (m.kind) {
    case Message::Kind::kEnd:
      flush(out);
      have_segment_ = false;
      out.push_back(m);
      return;
    case Message::Kind::kSegment:
      // Dispose of the prior segment before accepting this one.
      flush(out);
      sent_ = false;
      suppress_ = false;
      p_ = true;
      segment_ = m.segment;
      have_segment_ = true;
      return;
    case Message::Kind::kIntersection:
      break;
  }
  Intersection in = m.intersection;
  if (!have_segment_) return;  // an intersection with no segment before it: nothing to mark
  if (in.h) {
    // Ensure that nothing is missing (L1803).
    if (in.p == p_) insert({LineParam::minus_infinity(), true, true, true}, out);
    if (!in.p && in.v) {
      insert({LineParam::plus_infinity(), false, true, false}, out);
      in.p = true;
    }
    insert(in, out);
    return;
  }
  // Not ready for cleanup: it follows its segment on.
  flush(out);
  if (!suppress_) out.push_back(m);
}

void CleanupProcessor::insert(const Intersection& i, std::vector<Message>& out) {
  if (n_ == 4) make_space(out);
  part_[static_cast<std::size_t>(n_)] = i;
  ++n_;
  p_ = i.p;
  if (n_ == 4) sort_merge();
}

void CleanupProcessor::sort_merge() {
  // Two parts, each [lower, upper] = [int2, int1], [int4, int3]: the one with the larger upper
  // end first; merged if they overlap.
  if (less(part_[0].t, part_[2].t)) {
    std::swap(part_[0], part_[2]);
    std::swap(part_[1], part_[3]);
  }
  if (less(part_[1].t, part_[2].t)) {
    if (less(part_[3].t, part_[1].t)) part_[1] = part_[3];
    n_ -= 2;
    ++merged_;
  }
}

void CleanupProcessor::make_space(std::vector<Message>& out) {
  // The first part, restricted to the segment [0, 1].
  if (LineParam::one() < part_[0].t) part_[0].t = LineParam::one();
  if (part_[1].t < LineParam::zero()) part_[1].t = LineParam::zero();
  comparisons_ += 2;
  if (less(part_[1].t, part_[0].t)) {
    if (same(part_[0].t, LineParam::one()) && same(part_[1].t, LineParam::zero()) && !sent_) {
      suppress_ = true;
      ++suppressed_;
    }
    if (!sent_ && !suppress_) {
      out.push_back(Message::of(segment_));
      sent_ = true;
    }
    if (!suppress_) {
      out.push_back(Message::of(part_[0]));
      out.push_back(Message::of(part_[1]));
    }
  } else {
    ++dropped_;  // the visible regions overlap, or the part lies off the segment
  }
  part_[0] = part_[2];
  part_[1] = part_[3];
  n_ -= 2;
}

void CleanupProcessor::flush(std::vector<Message>& out) {
  while (n_ > 1) make_space(out);
  if (n_ == 1) {
    insert({LineParam::minus_infinity(), true, true, true}, out);
    make_space(out);
  }
  if (have_segment_ && !sent_ && !suppress_) {
    out.push_back(Message::of(segment_));
    sent_ = true;
  }
}

}  // namespace rtsim::hiddenline
