#pragma once
// How a ray caster samples the screen region the master GP gave it (seed 004 L352-L369):
//   uniform   a ray at every lattice position of the region (sample rows, L352, and squares
//             without adaptive sampling), or at those partial updating picks this frame
//             (L375-L379);
//   adaptive  a square region (L360) starts with a ray every `start` pixels (one per 16 x 16,
//             L369) and each start x start cell is refined by recursive square subdivision
//             (adaptive_sampling.hpp, L362) down to `finest` (one per 4 x 4) where its corner
//             samples differ by more than `threshold` in any colour channel, or, with
//             `object_edges`, hit different primitives (the polygon analogue of VOL2's
//             isosurface encoding, L364). The square includes its right and bottom edges (65 x
//             65 pixels for 64: "two edges of replicated rays", L360), so it is sampled with no
//             seam and no neighbour; positions not cast are filled bilinearly and sent as well,
//             marked filled.
#include <cstdint>
#include <vector>

#include "firmware/shading/pixel_accumulator.hpp"
#include "firmware/tasks/adaptive_sampling.hpp"
#include "firmware/tasks/sample_lattice.hpp"

namespace rtsim::tasks {

struct SamplingRule {
  int finest = 1;           ///< pixels between rays at the finest level
  int start = 1;            ///< pixels between rays before refinement (squares); == finest: uniform
  double threshold = 0.05;  ///< colour difference (radiance, any channel) that refines
  bool object_edges = true;
  Subdivision subdivision = Subdivision::kPartial;
  bool adaptive() const { return start > finest; }
};

/// A region's lattice positions [i0, i1) x [j0, j1); an adaptive square also needs its side in
/// lattice units (its positions are [i0, i0 + side] x [j0, j0 + side], cut to the lattice).
struct LatticeRange {
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  int side = 0;
};

namespace detail {
/// A sample as the subdivision sees it: radiance sums in double, and the primitive hit.
struct Radiance {
  std::array<double, 3> c{};
  std::int32_t id = -1;
  Radiance operator+(const Radiance& o) const {
    return {{c[0] + o.c[0], c[1] + o.c[1], c[2] + o.c[2]}, id == o.id ? id : -1};
  }
  Radiance operator*(double k) const { return {{c[0] * k, c[1] * k, c[2] * k}, id}; }
};
}  // namespace detail

/// Samples region `r` of `lattice`: `cast(i, j)` traces a position (LatticeSample), each at most
/// once; `update(i, j)` says whether a uniform region casts a position this frame; `out(s)`
/// receives every position the region sends, in lattice order. Returns the rays cast (positions).
template <class Cast, class Update, class Out>
std::size_t sample_region(const SampleLattice& lattice, const SamplingRule& rule,
                          const LatticeRange& r, int spp, Cast&& cast, Update&& update, Out&& out) {
  std::size_t rays = 0;
  if (!rule.adaptive()) {
    for (int j = r.j0; j < r.j1; ++j)
      for (int i = r.i0; i < r.i1; ++i)
        if (update(i, j)) {
          out(cast(i, j));
          ++rays;
        }
    return rays;
  }
  using detail::Radiance;
  const int n = r.side + 1;  // positions a side, replicated edge included
  const auto at = [n](int a, int b) {
    return static_cast<std::size_t>(b) * static_cast<std::size_t>(n) + static_cast<std::size_t>(a);
  };
  std::vector<LatticeSample> grid(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  enum : std::uint8_t { kNone, kFilled, kCast };
  std::vector<std::uint8_t> state(grid.size(), kNone);
  const auto radiance = [](const LatticeSample& s) {
    return Radiance{{static_cast<double>(s.sum[0]), static_cast<double>(s.sum[1]),
                     static_cast<double>(s.sum[2])},
                    s.id};
  };
  const double threshold = rule.threshold * shading::PixelAccumulator::kScale * spp;
  const auto differs = [&](const Radiance& a, const Radiance& b) {
    if (rule.object_edges && a.id != b.id) return true;
    for (int c = 0; c < 3; ++c)
      if (std::abs(a.c[c] - b.c[c]) > threshold) return true;
    return false;
  };
  const int cell = rule.start / rule.finest;  // lattice units
  for (int cb = 0; cb < r.side; cb += cell)
    for (int ca = 0; ca < r.side; ca += cell) {
      AdaptiveSquare<Radiance> sq(rule.start, rule.finest, rule.subdivision);
      sq.run(
          [&](int x, int y) {
            const int a = ca + x / rule.finest, b = cb + y / rule.finest;
            LatticeSample& s = grid[at(a, b)];
            if (state[at(a, b)] != kCast) {
              s = cast(r.i0 + a, r.j0 + b);
              state[at(a, b)] = kCast;
              ++rays;
            }
            return radiance(s);
          },
          differs);
      for (int b = 0; b <= cell; ++b)
        for (int a = 0; a <= cell; ++a) {
          const std::size_t k = at(ca + a, cb + b);
          if (state[k] == kCast || sq.sampled(a, b)) continue;
          const Radiance& v = sq.value(a, b);
          LatticeSample s;
          s.index = lattice.index(r.i0 + ca + a, r.j0 + cb + b);
          s.sum = {std::llround(v.c[0]), std::llround(v.c[1]), std::llround(v.c[2])};
          s.cast = false;
          if (state[k] == kNone || better_copy(s, grid[k])) grid[k] = s;
          state[k] = kFilled;
        }
    }
  for (int b = 0; b < n && r.j0 + b < lattice.ny(); ++b)
    for (int a = 0; a < n && r.i0 + a < lattice.nx(); ++a) out(grid[at(a, b)]);
  return rays;
}

}  // namespace rtsim::tasks
