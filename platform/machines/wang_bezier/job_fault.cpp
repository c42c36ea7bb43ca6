#include "platform/machines/wang_bezier/job_fault.hpp"

#include <bit>

#include "common/input_error.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform::wang_bezier {

namespace {
/// Words of a job on the wire.
constexpr std::uint64_t kJobWords = PatchJob::kWireBits / 32;

void flip(float& x, std::uint32_t mask) {
  x = std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) ^ mask);
}
}  // namespace

void JobFault::apply(PatchJob& job) {
  ++applied;
  if (word < 3) return flip(job.o[static_cast<int>(word)], xor_mask);
  if (word < 6) return flip(job.d[static_cast<int>(word - 3)], xor_mask);
  const std::uint64_t w = word - 6;
  const std::uint64_t point = w / 3;
  flip(job.net.p[point / 4][point % 4][static_cast<int>(w % 3)], xor_mask);
}

std::vector<JobFault> job_faults(const std::string& input, std::vector<MemoryFault>& faults) {
  std::vector<JobFault> out;
  for (const MemoryFault& f :
       take_faults(faults, [&](const std::string& name) { return name == input; })) {
    if (f.word >= kJobWords)
      throw InputError("--fault " + input + ":" + std::to_string(f.word), 0,
                       "a ray/patch job has " + std::to_string(kJobWords) +
                           " words (0-2 O, 3-5 D, 6-53 the 16 control points, 3 words each)");
    out.push_back({.word = f.word, .xor_mask = f.xor_mask});
  }
  return out;
}

}  // namespace rtsim::platform::wang_bezier
