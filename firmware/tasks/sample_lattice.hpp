#pragma once
// The lattice of screen samples of VOL2's ray casters on Pixel-Planes 5 (seed 004 L360-L379):
// rays are cast at most every `finest` pixels (one per 4 x 4 at the finest level, L369), at the
// pixel positions (i finest, j finest); the SIMD renderers resample the lattice to display
// pixels (L282, L308). The lattice reaches one position past the image's last row and column
// when the image does not end on one, so that every display pixel lies between four positions.
// At finest = 1 the lattice is the image's pixels and resampling changes no bit.
//
// A position's value is a pixel's fixed-point radiance sum (shading::PixelAccumulator): the ray
// tree of the `spp` vision rays a pixel would have at that position. Positions a caster filled
// in between samples rather than cast carry `cast = false`.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rtsim::tasks {

/// One lattice position's value as the ring carries it (a sample, L352-L360), or, in a pixels
/// message, a display pixel's.
struct LatticeSample {
  std::uint32_t index = 0;  ///< j nx + i on the lattice (in a pixels message: y width + x)
  std::array<std::int64_t, 3> sum{};
  std::int32_t id = -1;  ///< the primitive the position's primary ray hit (-1: none, or filled)
  bool cast = true;      ///< a ray was cast here (false: filled in between samples)
};

/// Which of two copies of a position to keep, whatever order they arrive in (squares replicate
/// their edges, L360, so a position can come from two casters): a cast sample over a filled
/// one; of two filled ones the smaller (r, g, b). Two cast copies are the same ray's answer.
inline bool better_copy(const LatticeSample& in, const LatticeSample& kept) {
  if (in.cast != kept.cast) return in.cast;
  if (in.cast) return false;
  return in.sum < kept.sum;
}

/// Keeps `in` at a position whose kept copy was written in frame `written`: the frame's first
/// copy replaces an earlier frame's (partial updating keeps the rest, L379); a replicated copy
/// in the same frame keeps the better (better_copy). The compositors and the functional twin.
inline void keep_copy(LatticeSample& kept, int& written, const LatticeSample& in, int frame) {
  if (written != frame || better_copy(in, kept)) kept = in;
  written = frame;
}

class SampleLattice {
 public:
  /// `align`: the lattice's extent, in positions less one, is a multiple of it, so that a
  /// coarser grid of every `align`-th position (successive refinement, refinement_schedule.hpp)
  /// also reaches past the image's last row and column.
  SampleLattice(int width, int height, int finest, int align = 1)
      : width_(width),
        height_(height),
        finest_(finest),
        nx_(((width + finest * align - 2) / (finest * align)) * align + 1),
        ny_(((height + finest * align - 2) / (finest * align)) * align + 1) {}

  int width() const { return width_; }
  int height() const { return height_; }
  int finest() const { return finest_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  std::size_t size() const { return static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_); }
  std::uint32_t index(int i, int j) const {
    return static_cast<std::uint32_t>(j) * static_cast<std::uint32_t>(nx_) +
           static_cast<std::uint32_t>(i);
  }
  int i_of(std::uint32_t index) const {
    return static_cast<int>(index % static_cast<std::uint32_t>(nx_));
  }
  int j_of(std::uint32_t index) const {
    return static_cast<int>(index / static_cast<std::uint32_t>(nx_));
  }

  /// The image pixel (y width + x) position (i, j) lies on, or -1 for one past the image's last
  /// column or row.
  std::int64_t pixel(int i, int j) const {
    const int x = i * finest_, y = j * finest_;
    return x < width_ && y < height_ ? static_cast<std::int64_t>(y) * width_ + x : -1;
  }

  /// The lattice columns [first, last] a display pixel column range [x0, x1) reads.
  int first_for(int x0) const { return x0 / finest_; }
  int last_for(int x1) const { return (x1 - 1 + finest_ - 1) / finest_; }

  /// resample() on the grid of every `step`-th position (a coarser refinement level): the
  /// positions around the pixel on that grid.
  template <class At>
  std::array<std::int64_t, 3> resample(int x, int y, int step, At&& at) const {
    if (step == 1) return resample(x, y, at);
    const SampleLattice coarse(width_, height_, finest_ * step);
    return coarse.resample(x, y,
                           [&](int i, int j) -> decltype(auto) { return at(i * step, j * step); });
  }

  /// Display pixel (x, y): bilinear between the four positions around it, in double, rounded
  /// to the fixed point; a pixel on a position takes that position's value as it is. `at(i, j)`
  /// gives a position's sums. The renderers and the functional twin both call this.
  template <class At>
  std::array<std::int64_t, 3> resample(int x, int y, At&& at) const {
    const int i = x / finest_, a = x % finest_;
    const int j = y / finest_, b = y % finest_;
    const std::array<std::int64_t, 3>& v00 = at(i, j);
    if (a == 0 && b == 0) return v00;
    const double u = static_cast<double>(a) / finest_, v = static_cast<double>(b) / finest_;
    std::array<double, 3> acc{};
    for (int c = 0; c < 3; ++c) acc[c] = static_cast<double>(v00[c]) * ((1 - u) * (1 - v));
    if (a != 0) {
      const auto& v10 = at(i + 1, j);
      for (int c = 0; c < 3; ++c) acc[c] += static_cast<double>(v10[c]) * (u * (1 - v));
    }
    if (b != 0) {
      const auto& v01 = at(i, j + 1);
      for (int c = 0; c < 3; ++c) acc[c] += static_cast<double>(v01[c]) * ((1 - u) * v);
    }
    if (a != 0 && b != 0) {
      const auto& v11 = at(i + 1, j + 1);
      for (int c = 0; c < 3; ++c) acc[c] += static_cast<double>(v11[c]) * (u * v);
    }
    return {std::llround(acc[0]), std::llround(acc[1]), std::llround(acc[2])};
  }

 private:
  int width_, height_, finest_, nx_, ny_;
};

}  // namespace rtsim::tasks
