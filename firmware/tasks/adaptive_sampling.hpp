#pragma once
// Adaptive sampling of a square screen region by recursive square subdivision, as VOL2's ray
// casters do on Pixel-Planes 5 (seed 004 L358, L362):
//
//   conventional  a square whose four corner samples differ (any pair, by the caller's test)
//                 is fully subdivided: five new samples, the four edge midpoints and the
//                 centre, and each quarter is examined in turn;
//   partial       only the midpoints of the edges whose two end samples differ are computed,
//                 and the centre if any pair differs; a midpoint not computed takes the value
//                 between its (alike) ends, and each quarter is examined in turn on its corners,
//                 computed or taken.
//
// Fig. 8 (L358) shows a curve boundary crossing a square refined three levels: 51 samples
// conventional, 29 partial (tests/adaptive_sampling_test.cpp reproduces both; for any single
// boundary crossing such a square the counts are related as partial = (conventional + 7) / 2).
//
// The square is a grid of (size / finest + 1)^2 sample positions (`finest` apart); refinement
// starts from its four corners and stops at squares of side `finest`. After run(), every
// position has a value: sampled, or filled by bilinear interpolation between the corners of the
// smallest square that was not subdivided (the values the resampling would see).
//
// Used by pxpl5-raytrace's ray casters (sample squares) and by its functional twin.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace rtsim::tasks {

enum class Subdivision { kConventional, kPartial };

/// V: a sample value with V + V and V * double (a colour, a number).
template <class V>
class AdaptiveSquare {
 public:
  /// `size` and `finest`: powers of two, finest <= size, in pixels.
  AdaptiveSquare(int size, int finest, Subdivision scheme)
      : size_(size), finest_(finest), n_(size / finest + 1), scheme_(scheme) {
    if (size < 1 || finest < 1 || finest > size || (size & (size - 1)) != 0 ||
        (finest & (finest - 1)) != 0)
      throw std::invalid_argument("adaptive square: size and finest must be powers of two");
    values_.resize(static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_));
    state_.assign(values_.size(), kUnknown);
  }

  /// Runs the subdivision: `sample(x, y)` computes the sample at pixel offset (x, y) of the
  /// square (each position at most once), `differs(a, b)` is the subdivision criterion.
  template <class Sample, class Differs>
  void run(Sample&& sample, Differs&& differs) {
    const int last = n_ - 1;
    for (const auto& [i, j] : {Corner{0, 0}, Corner{last, 0}, Corner{0, last}, Corner{last, last}})
      take(i, j, sample);
    refine(0, 0, last, sample, differs);
  }

  /// Samples computed.
  std::size_t samples() const { return samples_; }
  /// Positions per side: size / finest + 1.
  int positions() const { return n_; }
  /// The value at grid position (i, j) (pixel offset (i finest, j finest)).
  const V& value(int i, int j) const { return values_[index(i, j)]; }
  /// Whether position (i, j) was sampled (not filled).
  bool sampled(int i, int j) const { return state_[index(i, j)] == kSampled; }

 private:
  enum State : std::uint8_t { kUnknown, kSampled, kTaken };
  struct Corner {
    int i, j;
  };
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(i);
  }
  template <class Sample>
  void take(int i, int j, Sample& sample) {
    const std::size_t k = index(i, j);
    if (state_[k] == kSampled) return;
    values_[k] = sample(i * finest_, j * finest_);
    state_[k] = kSampled;
    ++samples_;
  }
  /// A position not sampled takes the value halfway between (a) and (b).
  void between(int i, int j, int ai, int aj, int bi, int bj) {
    const std::size_t k = index(i, j);
    if (state_[k] != kUnknown) return;
    values_[k] = value(ai, aj) * 0.5 + value(bi, bj) * 0.5;
    state_[k] = kTaken;
  }
  /// The square with corner (i, j) and side s (grid units).
  template <class Sample, class Differs>
  void refine(int i, int j, int s, Sample& sample, Differs& differs) {
    const Corner c[4] = {{i, j}, {i + s, j}, {i + s, j + s}, {i, j + s}};
    bool any = false;
    bool edge[4];
    for (int e = 0; e < 4; ++e) {
      const Corner a = c[e], b = c[(e + 1) % 4];
      edge[e] = differs(value(a.i, a.j), value(b.i, b.j));
      any = any || edge[e];
    }
    // The diagonals too: "any pair of four corner values" (L362).
    any = any || differs(value(c[0].i, c[0].j), value(c[2].i, c[2].j)) ||
          differs(value(c[1].i, c[1].j), value(c[3].i, c[3].j));
    if (!any || s == 1) {
      fill(i, j, s);
      return;
    }
    const int h = s / 2;
    const Corner mid[4] = {{i + h, j}, {i + s, j + h}, {i + h, j + s}, {i, j + h}};
    for (int e = 0; e < 4; ++e) {
      const Corner a = c[e], b = c[(e + 1) % 4];
      if (scheme_ == Subdivision::kConventional || edge[e])
        take(mid[e].i, mid[e].j, sample);
      else
        between(mid[e].i, mid[e].j, a.i, a.j, b.i, b.j);
    }
    take(i + h, j + h, sample);
    refine(i, j, h, sample, differs);
    refine(i + h, j, h, sample, differs);
    refine(i, j + h, h, sample, differs);
    refine(i + h, j + h, h, sample, differs);
  }
  /// Positions inside an unsubdivided square: bilinear between its corners.
  void fill(int i, int j, int s) {
    if (s == 1) return;
    const V& v00 = value(i, j);
    const V& v10 = value(i + s, j);
    const V& v01 = value(i, j + s);
    const V& v11 = value(i + s, j + s);
    for (int b = 0; b <= s; ++b)
      for (int a = 0; a <= s; ++a) {
        const std::size_t k = index(i + a, j + b);
        if (state_[k] != kUnknown) continue;
        const double u = static_cast<double>(a) / s, v = static_cast<double>(b) / s;
        values_[k] =
            v00 * ((1 - u) * (1 - v)) + v10 * (u * (1 - v)) + v01 * ((1 - u) * v) + v11 * (u * v);
        state_[k] = kTaken;
      }
  }

  int size_, finest_, n_;
  Subdivision scheme_;
  std::vector<V> values_;
  std::vector<State> state_;
  std::size_t samples_ = 0;
};

}  // namespace rtsim::tasks
