#pragma once
// A point on a line as its parameter t, kept as the rational t_n / t_d the plane processors
// compute (seed 000 L1765: "the plane processors can save a division ... simply by representing
// the parameter t as a rational number"; one divider at the pipe's end). Screen coordinates are
// integers, so t_n and t_d are exact 64-bit integers and two parameters are compared exactly by
// cross multiplication in 128 bits (L1783-L1787), the signs of the denominators taken into
// account. t_d = 0 stands for an end of the line: t_n > 0 is +infinity, t_n < 0 -infinity (as the
// cleanup processor's program writes its missing mates, Fig. 3-34).
#include <cstdint>

namespace rtsim::hiddenline {

struct LineParam {
  std::int64_t n = 0;
  std::int64_t d = 1;

  static constexpr LineParam zero() { return {0, 1}; }
  static constexpr LineParam one() { return {1, 1}; }
  static constexpr LineParam minus_infinity() { return {-1, 0}; }
  static constexpr LineParam plus_infinity() { return {1, 0}; }
  /// The value as a double (the pipe end's division); +-infinity for d = 0.
  double value() const;
};

/// -1, 0 or +1 as a is before, at or after b on the line (exact).
int compare(const LineParam& a, const LineParam& b);
inline bool operator<(const LineParam& a, const LineParam& b) { return compare(a, b) < 0; }
inline bool operator>(const LineParam& a, const LineParam& b) { return compare(a, b) > 0; }
inline bool operator<=(const LineParam& a, const LineParam& b) { return compare(a, b) <= 0; }
inline bool same(const LineParam& a, const LineParam& b) { return compare(a, b) == 0; }

}  // namespace rtsim::hiddenline
