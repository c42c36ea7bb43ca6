#pragma once
// Frame-buffer accumulation that does not depend on the order contributions arrive in.
// Each contribution is rounded to a fixed-point integer (kScale units per 1.0) and added as an
// integer, which is associative: a machine that delivers the contributions of a pixel in any
// order, from any number of processors, produces the same bits as the functional renderer.
// Resolution 2^-32 is far below what an 8-bit PNG or a 32-bit float EXR can show.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "firmware/math.hpp"

namespace rtsim::shading {

class PixelAccumulator {
 public:
  static constexpr double kScale = 4294967296.0;  // 2^32 units per 1.0
  /// Largest value one channel of one contribution may carry; larger values are clamped. Keeps
  /// the int64 sum far from overflow even for thousands of contributions per pixel.
  static constexpr double kMaxContribution = 1.0e6;

  PixelAccumulator(int width, int height)
      : width_(width), height_(height), sums_(static_cast<std::size_t>(width) * height * 3, 0) {}

  int width() const { return width_; }
  int height() const { return height_; }

  /// Told of every contribution's pixel as it is added (sampled simulation times the frame's
  /// windows by them), and when it landed if the caller says (notify: a processor whose own
  /// time is ahead of the simulation's), else nothing (now); empty: nothing is told.
  using Observer = std::function<void(std::uint32_t pixel, std::optional<std::uint64_t> at)>;
  void set_observer(Observer observer) { observer_ = std::move(observer); }

  void add(std::uint32_t pixel, const Color& c) {
    if (observer_) observer_(pixel, std::nullopt);
    std::int64_t* p = &sums_[static_cast<std::size_t>(pixel) * 3];
    p[0] += to_fixed(c.r);
    p[1] += to_fixed(c.g);
    p[2] += to_fixed(c.b);
  }

  /// The fixed-point sums of a pixel, as they are (a machine moves them between accumulators:
  /// a ray caster's samples to the frame buffer, with no rounding on the way).
  std::array<std::int64_t, 3> raw(std::uint32_t pixel) const {
    const std::int64_t* p = &sums_[static_cast<std::size_t>(pixel) * 3];
    return {p[0], p[1], p[2]};
  }
  void add_raw(std::uint32_t pixel, const std::array<std::int64_t, 3>& sums) {
    if (observer_) observer_(pixel, std::nullopt);
    std::int64_t* p = &sums_[static_cast<std::size_t>(pixel) * 3];
    p[0] += sums[0];
    p[1] += sums[1];
    p[2] += sums[2];
  }
  /// A contribution landed in a frame buffer elsewhere (a machine whose processors hold the
  /// frame buffer) at `at` (the machine's time units): the observer is told, nothing is added
  /// here.
  void notify(std::uint32_t pixel, std::uint64_t at) const {
    if (observer_) observer_(pixel, at);
  }
  /// Sums read out of such a frame buffer, added without telling the observer (they are not
  /// contributions landing now).
  void read_out(std::uint32_t pixel, const std::array<std::int64_t, 3>& sums) {
    std::int64_t* p = &sums_[static_cast<std::size_t>(pixel) * 3];
    p[0] += sums[0];
    p[1] += sums[1];
    p[2] += sums[2];
  }
  void clear(std::uint32_t pixel) {
    std::int64_t* p = &sums_[static_cast<std::size_t>(pixel) * 3];
    p[0] = p[1] = p[2] = 0;
  }

  /// Pixel value divided by the number of samples per pixel.
  Color value(std::uint32_t pixel, int samples) const {
    const std::int64_t* p = &sums_[static_cast<std::size_t>(pixel) * 3];
    const double k = 1.0 / (kScale * samples);
    return Color(static_cast<double>(p[0]) * k, static_cast<double>(p[1]) * k,
                 static_cast<double>(p[2]) * k);
  }

  static std::int64_t to_fixed(double x) {
    if (!(x > 0.0)) return 0;  // negatives and NaN contribute nothing (never happen by design)
    if (x > kMaxContribution) x = kMaxContribution;
    return static_cast<std::int64_t>(std::llround(x * kScale));
  }

 private:
  int width_;
  int height_;
  std::vector<std::int64_t> sums_;
  Observer observer_;
};

}  // namespace rtsim::shading
