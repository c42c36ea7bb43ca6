#include "firmware/hiddenline/line_param.hpp"

#include <limits>

namespace rtsim::hiddenline {

namespace {
__extension__ typedef __int128 Wide;  // GCC and clang; -Wpedantic knows no __int128
/// -1 for -infinity, +1 for +infinity, 0 for a finite value.
int infinity_of(const LineParam& p) { return p.d != 0 ? 0 : (p.n > 0 ? 1 : -1); }
int sign(Wide v) { return v < 0 ? -1 : (v > 0 ? 1 : 0); }
}  // namespace

double LineParam::value() const {
  if (d == 0)
    return n > 0 ? std::numeric_limits<double>::infinity()
                 : -std::numeric_limits<double>::infinity();
  return static_cast<double>(n) / static_cast<double>(d);
}

int compare(const LineParam& a, const LineParam& b) {
  const int ia = infinity_of(a), ib = infinity_of(b);
  if (ia != 0 || ib != 0) return ia == ib ? 0 : (ia < ib ? -1 : 1);
  // a.n / a.d - b.n / b.d has the sign of (a.n b.d - b.n a.d) times that of a.d b.d (L1785).
  const Wide cross = static_cast<Wide>(a.n) * b.d - static_cast<Wide>(b.n) * a.d;
  return sign(cross) * ((a.d < 0) == (b.d < 0) ? 1 : -1);
}

}  // namespace rtsim::hiddenline
