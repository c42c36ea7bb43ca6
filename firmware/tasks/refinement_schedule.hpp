#pragma once
// Which lattice positions VOL2's ray casters cast in each frame of an interactive session, and at
// what resolution the frame is displayed (seed 004 L288, L373-L379):
//   - successive refinement (L288): a coarse image while the view changes, finer ones while it
//     rests. Level 0, the coarsest, has a position every 2^(levels-1) lattice positions; each
//     level halves the spacing; the finest is the lattice. A resting frame casts the next level's
//     new positions (those not on the coarser grid) and, once they are all in, is displayed at it;
//   - partial updating (L373-L379): a level's positions are cast a fraction 1/period a frame, on
//     a regular grid ("a simple modulus of the sample coordinates with the frame number"), so a
//     level is complete after `period` frames at the same view ("an image at the lowest
//     successive refinement level will have filled in after four frames", L375);
//   - the first frame casts every position of level 0 (the compositors' array starts empty).
// A frame after one during which the user moved sees a new view: every level is stale again and
// the frame casts level 0 (its phase only). Stale positions still show until they are cast
// again: the compositors keep them (L379). The ray casters, the compositors, the renderers and
// the functional twin all follow the same schedule.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace rtsim::tasks {

struct FramePlan {
  int cast_level = 0;     ///< the level whose positions this frame casts; -1: none
  int phase = -1;         ///< the phase cast (partial updating); -1: every position of it
  int display_level = 0;  ///< the finest level complete at this view (0 if none is)
  bool new_view = true;   ///< the view differs from the frame before's (or it is the first)
};

/// Partial updating's phase of grid position (a, b): a checkerboard at period 2, each position of
/// a 2 x 2 block in turn at period 4 (L377).
inline int update_phase(int a, int b, int period) {
  if (period <= 1) return 0;
  return period == 2 ? (a + b) % 2 : (a % 2) + 2 * (b % 2);
}

class RefinementSchedule {
 public:
  RefinementSchedule() : RefinementSchedule(std::vector<bool>{}, 1, 1) {}
  /// `moving[f]`: the user moves during frame f, so frame f + 1 sees a new view.
  RefinementSchedule(const std::vector<bool>& moving, int levels, int period)
      : levels_(levels < 1 ? 1 : levels), period_(period < 1 ? 1 : period) {
    const unsigned full = (1u << period_) - 1u;
    std::vector<unsigned> done(static_cast<std::size_t>(levels_), 0u);
    for (std::size_t f = 0; f < moving.size(); ++f) {
      FramePlan p;
      p.new_view = f == 0 || moving[f - 1];
      const int phase = period_ == 1 ? -1 : static_cast<int>(f % static_cast<std::size_t>(period_));
      const unsigned bit = phase < 0 ? full : 1u << phase;
      if (f == 0) {
        // Cold start: every position of the coarsest level.
        std::fill(done.begin(), done.end(), 0u);
        p.cast_level = 0;
        p.phase = -1;
        done[0] = full;
      } else if (p.new_view) {
        std::fill(done.begin(), done.end(), 0u);
        p.cast_level = 0;
        p.phase = phase;
        done[0] |= bit;
      } else {
        p.cast_level = -1;
        for (int l = 0; l < levels_; ++l)
          if (done[static_cast<std::size_t>(l)] != full) {
            p.cast_level = l;
            p.phase = phase;
            done[static_cast<std::size_t>(l)] |= bit;
            break;
          }
      }
      p.display_level = 0;
      for (int l = 0; l < levels_ && done[static_cast<std::size_t>(l)] == full; ++l)
        p.display_level = l;
      plans_.push_back(p);
    }
  }

  int levels() const { return levels_; }
  int period() const { return period_; }
  int frames() const { return static_cast<int>(plans_.size()); }
  const FramePlan& plan(int frame) const { return plans_[static_cast<std::size_t>(frame)]; }

  /// Lattice positions between two of level `level`'s.
  int step(int level) const { return 1 << (levels_ - 1 - level); }
  /// The spacing of the coarsest level: the lattice's extent is a multiple of it.
  int align() const { return step(0); }
  /// Whether lattice position (i, j) is on level `level`'s grid.
  bool on_level(int i, int j, int level) const {
    const int s = step(level);
    return i % s == 0 && j % s == 0;
  }
  /// Whether frame `frame` casts lattice position (i, j): on its level's grid, not on the
  /// coarser one (cast already at this view), and, with partial updating, in its phase (level
  /// 0's by the position, a finer level's by its coarse cell, so that each frame takes a share).
  bool casts(int i, int j, int frame) const {
    const FramePlan& p = plan(frame);
    if (p.cast_level < 0) return false;
    const int s = step(p.cast_level);
    if (i % s != 0 || j % s != 0) return false;
    const int a = i / s, b = j / s;
    if (p.cast_level > 0 && a % 2 == 0 && b % 2 == 0) return false;
    if (p.phase < 0) return true;
    return p.cast_level == 0 ? update_phase(a, b, period_) == p.phase
                             : update_phase(a / 2, b / 2, period_) == p.phase;
  }

 private:
  int levels_, period_;
  std::vector<FramePlan> plans_;
};

}  // namespace rtsim::tasks
