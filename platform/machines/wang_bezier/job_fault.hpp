#pragma once
// Faults in flight on the Bezier pipeline (a wire stuck, or a bit flipped on the way), not the
// host's patch memory at rest. Every word is an IEEE single (L296), XORed.
//
// `--fault pipeline.input:WORD:XOR` corrupts word WORD of every ray/patch job as it enters
// stage 0. A job's 54 words (note 002 "Transactions"): 0-2 the ray's origin O, 3-5 its
// direction D, then the 16 control points P_ij, three words each (word 6 + 3 (4 i + j) + c).
//
// `--fault pipeline.loopK.in:WORD:XOR` corrupts word WORD of every job as it enters loop stage
// K (what stage K - 1 handed on): 0-2 O, 3-5 D, 6-13 the planes (N_U, E_U, N_V, E_V), 14-205
// buffer1's four patches (48 words each, as above). Buffer1's count is not a word a fault may
// change (a count past 4 would address patches that do not exist); a patch slot the job does not
// use is corrupted to no effect.
#include <cstdint>
#include <string>
#include <vector>

#include "platform/machine.hpp"
#include "platform/machines/wang_bezier/messages.hpp"

namespace rtsim::platform::wang_bezier {

struct JobFault {
  int stage = 0;  ///< 0: the pipeline's input; K: loop stage K's
  std::uint64_t word = 0;
  std::uint32_t xor_mask = 0;
  std::uint64_t applied = 0;  ///< jobs corrupted

  /// Where it strikes: "pipeline.input" or "pipeline.loopK.in".
  std::string at(const std::string& pipeline) const;
  void apply(PatchJob& job);
  template <typename T>
  void apply(kernels::WangJob<T>& job);
};

/// The faults of `faults` on the pipeline `pipeline` ("pipeline") of `loop_stages` loop stages;
/// the rest are left for the memories. InputError for a stage or a word a job does not have.
std::vector<JobFault> job_faults(const std::string& pipeline, int loop_stages,
                                 std::vector<MemoryFault>& faults);

}  // namespace rtsim::platform::wang_bezier
