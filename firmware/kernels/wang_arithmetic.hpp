#pragma once
// The arithmetic of Wang, Lewis & Hung's pipeline (bezier.arithmetic): the TMS320C6701's single
// precision (L296, the default), double precision, or fixed point of a chosen width (a what-if:
// a fixed-point DSP). The words a job carries in and out are singles whatever the arithmetic
// (the host's patch memory and its link, L296); stage 0 converts them.
//
// Fixed point is modelled as word storage: a block computes in wide precision (a fixed-point
// DSP's accumulators) and every word it writes (the planes, the subpatches' control points, the
// centres and the sort keys) is rounded to the nearest multiple of 2^-(bits - integer_bits) and
// saturates at +-2^(integer_bits - 1), two's complement words of `bits` bits. The twin stores
// alike, so a machine and its twin give the same image at every width.
#include <algorithm>
#include <cmath>
#include <string>

#include "firmware/kernels/bezier_patch_math.hpp"
#include "firmware/math.hpp"

namespace rtsim::kernels {

/// Fixed-point words: `bits` wide, `integer_bits` of them (the sign's included) above the point.
struct FixedWords {
  int bits = 24;
  int integer_bits = 8;

  /// x as such a word: NaN as 0 (a fixed word has none), beyond the range the nearest end.
  double operator()(double x) const {
    if (std::isnan(x)) return 0.0;
    const double scale = std::ldexp(1.0, bits - integer_bits);
    const double limit = std::ldexp(1.0, bits - 1);
    return std::clamp(std::nearbyint(x * scale), -limit, limit - 1.0) / scale;
  }
};

/// bezier.arithmetic.
struct WangArithmetic {
  enum class Kind { kFloat32, kFloat64, kFixed };
  Kind kind = Kind::kFloat32;
  FixedWords fixed;

  /// Computed in double (float64 and fixed) rather than in the DSPs' single precision.
  bool wide() const { return kind != Kind::kFloat32; }
  /// The word format, for fixed point; none otherwise.
  const FixedWords* words() const { return kind == Kind::kFixed ? &fixed : nullptr; }
  std::string name() const {
    if (kind == Kind::kFloat32) return "float32";
    if (kind == Kind::kFloat64) return "float64";
    return "fixed" + std::to_string(fixed.bits) + "." +
           std::to_string(fixed.bits - fixed.integer_bits);
  }
};

// Storing words in the format (nothing to do without one).
template <typename T>
void store_words(const FixedWords* f, T& x) {
  if (f) x = static_cast<T>((*f)(static_cast<double>(x)));
}
template <typename T>
void store_words(const FixedWords* f, Vec3T<T>& v) {
  if (f)
    for (int c = 0; c < 3; ++c) store_words(f, v[c]);
}
template <typename T>
void store_words(const FixedWords* f, ControlNet<T>& net) {
  if (f)
    for (auto& row : net.p)
      for (auto& point : row) store_words(f, point);
}

}  // namespace rtsim::kernels
