#include "firmware/deferred/simd_stream.hpp"

namespace rtsim::deferred::simd {

std::uint32_t InstructionMix::total() const {
  std::uint32_t n = float_to_long + long_to_float;
  for (const auto& row : ops)
    for (const std::uint32_t k : row) n += k;
  return n;
}

InstructionMix& InstructionMix::operator+=(const InstructionMix& o) {
  for (std::size_t a = 0; a < ops.size(); ++a)
    for (std::size_t r = 0; r < ops[a].size(); ++r) ops[a][r] += o.ops[a][r];
  float_to_long += o.float_to_long;
  long_to_float += o.long_to_float;
  return *this;
}

double InstructionTimes::time_of(const InstructionMix& mix) const {
  double t = mix.float_to_long * float_to_long + mix.long_to_float * long_to_float;
  for (std::size_t a = 0; a < seconds.size(); ++a)
    for (std::size_t r = 0; r < seconds[a].size(); ++r) t += mix.ops[a][r] * seconds[a][r];
  return t;
}

}  // namespace rtsim::deferred::simd
