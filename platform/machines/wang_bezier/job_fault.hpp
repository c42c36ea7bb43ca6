#pragma once
// A fault in flight on the Bezier pipeline: `--fault pipeline.input:WORD:XOR` corrupts word WORD
// of every ray/patch job as it enters stage 0 (a wire of the host's link stuck, or a bit flipped
// on the way), not the host's patch memory at rest. A job's 54 words (note 002 "Transactions"):
// 0-2 the ray's origin O, 3-5 its direction D, then the 16 control points P_ij, three words
// each (word 6 + 3 (4 i + j) + c). Every word is an IEEE single (L296), XORed.
#include <cstdint>
#include <string>
#include <vector>

#include "platform/machine.hpp"
#include "platform/machines/wang_bezier/messages.hpp"

namespace rtsim::platform::wang_bezier {

struct JobFault {
  std::uint64_t word = 0;
  std::uint32_t xor_mask = 0;
  std::uint64_t applied = 0;  ///< jobs corrupted

  void apply(PatchJob& job);
};

/// The faults of `faults` on the pipeline's input `input` ("pipeline.input"); the rest are left
/// for the memories. InputError for a word a job does not have.
std::vector<JobFault> job_faults(const std::string& input, std::vector<MemoryFault>& faults);

}  // namespace rtsim::platform::wang_bezier
