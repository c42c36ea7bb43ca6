#include "firmware/hiddenline/pipe.hpp"

#include <algorithm>
#include <utility>

namespace rtsim::hiddenline {

std::vector<Stage> build_chain(const std::vector<std::vector<ScreenPoint>>& polygons,
                               int trailing_cleanups) {
  std::vector<std::vector<Plane>> planes;
  for (const auto& poly : polygons)
    if (std::vector<Plane> p = boundary_planes(poly); !p.empty()) planes.push_back(std::move(p));
  return build_chain(planes, trailing_cleanups);
}

std::vector<Stage> build_chain(const std::vector<std::vector<Plane>>& polygon_planes,
                               int trailing_cleanups) {
  std::vector<Stage> chain;
  for (const auto& planes : polygon_planes) {
    for (const Plane& p : planes) chain.emplace_back(PlaneProcessor(p));
    chain.emplace_back(CleanupProcessor());
  }
  for (int i = 0; i < trailing_cleanups; ++i) chain.emplace_back(CleanupProcessor());
  return chain;
}

std::vector<Message> segment_stream(const std::vector<Segment>& segments) {
  std::vector<Message> out;
  out.reserve(segments.size() + 1);
  for (const Segment& s : segments) out.push_back(Message::of(s));
  out.push_back(Message::end());
  return out;
}

std::vector<Message> run_chain(std::vector<Stage>& chain, std::vector<Message> in) {
  std::vector<Message> out;
  for (Stage& stage : chain) {
    out.clear();
    out.reserve(in.size());
    std::visit(
        [&](auto& processor) {
          for (const Message& m : in) processor.receive(m, out);
        },
        stage);
    std::swap(in, out);
  }
  return in;
}

std::vector<VisiblePiece> divide(const std::vector<Message>& out, std::uint64_t* divisions) {
  std::vector<VisiblePiece> pieces;
  const Segment* seg = nullptr;
  std::vector<std::pair<double, double>> hidden;  // [lower, upper], in t
  std::pair<double, double> part{0.0, 0.0};
  bool have_upper = false;
  std::uint64_t div = 0;
  const auto finish = [&] {
    if (!seg) return;
    std::sort(hidden.begin(), hidden.end());
    double from = 0.0;
    const auto emit = [&](double t0, double t1) {
      if (!(t1 > t0)) return;
      const auto at = [&](int k, double t) {
        return seg->a[static_cast<std::size_t>(k)] +
               t * (seg->b[static_cast<std::size_t>(k)] - seg->a[static_cast<std::size_t>(k)]);
      };
      pieces.push_back(
          {seg->edge, at(0, t0), at(1, t0), at(2, t0), at(0, t1), at(1, t1), at(2, t1), t0, t1});
    };
    for (const auto& [lo, hi] : hidden) {
      emit(from, std::min(lo, 1.0));
      from = std::max(from, hi);
      if (from >= 1.0) break;
    }
    if (from < 1.0) emit(from, 1.0);
    hidden.clear();
    seg = nullptr;
  };
  for (const Message& m : out) {
    switch (m.kind) {
      case Message::Kind::kSegment:
        finish();
        seg = &m.segment;
        have_upper = false;
        break;
      case Message::Kind::kIntersection: {
        const Intersection& i = m.intersection;
        if (!seg || !i.h) break;  // unmarked: no polygon's part
        ++div;
        const double t = std::clamp(i.t.value(), -1.0, 2.0);
        if (!i.v) {
          part.second = t;  // the upper end comes first
          have_upper = true;
        } else if (have_upper) {
          part.first = t;
          if (part.first < part.second) hidden.push_back(part);
          have_upper = false;
        }
        break;
      }
      case Message::Kind::kEnd:
        finish();
        break;
    }
  }
  finish();
  if (divisions) *divisions += div;
  return pieces;
}

}  // namespace rtsim::hiddenline
