#pragma once
#include <cstdint>

namespace rtsim {

/// Machine-neutral cost of a piece of firmware work. A task reports these counts; a processor
/// module turns them into time with its own parameters (cycles per op class, memory cycle).
/// The functional renderer adds them up for statistics only.
struct Cost {
  std::uint64_t fp_add = 0;  ///< additions, subtractions, comparisons
  std::uint64_t fp_mul = 0;
  std::uint64_t fp_div = 0;
  std::uint64_t fp_sqrt = 0;
  std::uint64_t mem_words = 0;     ///< 32-bit words read or written
  std::uint64_t instructions = 0;  ///< integer / control instructions

  constexpr Cost& operator+=(const Cost& o) {
    fp_add += o.fp_add;
    fp_mul += o.fp_mul;
    fp_div += o.fp_div;
    fp_sqrt += o.fp_sqrt;
    mem_words += o.mem_words;
    instructions += o.instructions;
    return *this;
  }
  /// What was added since `earlier` (a running total's growth; earlier <= *this in each class).
  constexpr Cost& operator-=(const Cost& earlier) {
    fp_add -= earlier.fp_add;
    fp_mul -= earlier.fp_mul;
    fp_div -= earlier.fp_div;
    fp_sqrt -= earlier.fp_sqrt;
    mem_words -= earlier.mem_words;
    instructions -= earlier.instructions;
    return *this;
  }
  friend constexpr Cost operator+(Cost a, const Cost& b) { return a += b; }
  friend constexpr Cost operator*(Cost a, std::uint64_t k) {
    a.fp_add *= k;
    a.fp_mul *= k;
    a.fp_div *= k;
    a.fp_sqrt *= k;
    a.mem_words *= k;
    a.instructions *= k;
    return a;
  }
  constexpr std::uint64_t fp_ops() const { return fp_add + fp_mul + fp_div + fp_sqrt; }
};

}  // namespace rtsim
