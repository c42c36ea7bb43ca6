#include "firmware/hiddenline/plane_processor.hpp"

namespace rtsim::hiddenline {

void PlaneProcessor::send(const LineParam& t, bool v, std::vector<Message>& out) {
  out.push_back(Message::of(Intersection{t, v, plane_.last, p_}));
  p_ = true;
}

void PlaneProcessor::send_held(std::vector<Message>& out) {
  if (u_) send(t_, v_, out);
  u_ = false;
}

void PlaneProcessor::receive(const Message& m, std::vector<Message>& out) {
  switch (m.kind) {
    case Message::Kind::kEnd:
      send_held(out);
      out.push_back(m);
      return;
    case Message::Kind::kSegment: {
      // Fig. 3-32.
      send_held(out);
      out.push_back(m);
      const Segment& s = m.segment;
      const std::int64_t k1 = plane_.a * s.a[0] + plane_.b * s.a[1] + plane_.c * s.a[2];
      const std::int64_t k2 = plane_.a * s.b[0] + plane_.b * s.b[1] + plane_.c * s.b[2];
      multiplications_ += 6;
      const std::int64_t tn = k1 + plane_.d, td = k1 - k2;
      p_ = false;
      v_ = td > 0;
      if (td != 0) {
        u_ = true;
        t_ = {tn, td};
      } else {
        // Parallel: visible everywhere if on the visible side (the text's >=), else nothing.
        u_ = tn >= 0;
        t_ = LineParam::minus_infinity();
      }
      return;
    }
    case Message::Kind::kIntersection:
      break;
  }
  // Fig. 3-33.
  const Intersection& in = m.intersection;
  if (in.h) {
    out.push_back(m);  // a hidden part's end passes through
    return;
  }
  if (!u_) {
    u_ = true;
    t_ = in.t;
    v_ = in.v;
    return;
  }
  if (v_ == in.v) {
    multiplications_ += 2;
    // The positive end (v = 0) is visible from the smaller t on, the negative end up to the
    // larger: the other one is redundant.
    const bool better = in.v ? in.t > t_ : in.t < t_;
    if (better) t_ = in.t;
    ++redundant_;
    return;
  }
  if (!v_) {
    // Held the positive end's: send it on, keep the negative end's.
    send(t_, v_, out);
    t_ = in.t;
    v_ = in.v;
    return;
  }
  // Holding the negative end's: the positive end's goes on first.
  send(in.t, in.v, out);
}

}  // namespace rtsim::hiddenline
