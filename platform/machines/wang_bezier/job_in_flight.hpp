#pragma once
// What travels between the Bezier pipeline's substages (note 002, "What a transaction-level
// model must include"): the job as stage 0 took it, the job the stages have made of it (the ray,
// its planes and buffer1) and the working sets of the stage it is in. Each hop's transaction
// carries the words the next substage needs (`words_after`); the model's bookkeeping (parameter
// indices, times) rides along uncounted.
#include <cstdint>
#include <systemc>

#include "firmware/kernels/bezier_wang.hpp"
#include "platform/machines/wang_bezier/messages.hpp"

namespace rtsim::platform::wang_bezier {

/// The work a substage does on the job it received (the firmware's blocks).
enum class SubstageWork {
  kPlanesSplitU,    ///< stage 0: PlaneGenerator, SplitInHalf in u of the input patch
  kSplitVOutput,    ///< stage 0: SplitInHalf in v -> buffer1
  kSubdivider,      ///< stage 0 on one DSP: PlaneGenerator and PatchSubdivider -> buffer1
  kSplitU,          ///< loop substage 1: buffer1's 4 patches in u -> 8 halves
  kSplitV,          ///< loop substage 2: 8 halves in v -> buffer2 (16)
  kHull,            ///< loop substage 3: HullClassification of 16 x 2 planes
  kCenterDistance,  ///< loop substage 4: PatchCenter + PatchDistance -> 16 keys
  kCull,            ///< loop substage 5: the Culler -> buffer1
};

struct JobInFlight {
  PatchJob job;               ///< as stage 0 received it: the ray's id, its slot, when it was sent
  kernels::WangJob<float> w;  ///< in the DSPs' single precision (bezier.arithmetic float32)
  kernels::WangStageWork<float> work;
  kernels::WangJob<double> wide;  ///< in double, or fixed point stored in double
  kernels::WangStageWork<double> wide_work;
  sc_core::sc_time accepted;  ///< when stage 0 took it
  bool waited = false;        ///< it waited at the input for stage 0 (the pipeline was full)
};

/// Words on the wire after a substage's work (32-bit words, L296): the ray and its planes
/// (O, D; N_U, E_U, N_V, E_V: 14 words), the patches (48 words each: 16 points x 3) and what
/// the next substage reads (a valid mask, hull verdicts, keys, centres).
constexpr std::uint64_t words_after(SubstageWork w) {
  constexpr std::uint64_t ray = 6 + 8, patch = 48, mask = 1;
  switch (w) {
    case SubstageWork::kPlanesSplitU:
      return ray + 2 * patch;
    case SubstageWork::kSplitVOutput:
    case SubstageWork::kSubdivider:
      return ray + 4 * patch + mask;
    case SubstageWork::kSplitU:
      return ray + 8 * patch + mask;
    case SubstageWork::kSplitV:
      return ray + 16 * patch + mask;
    case SubstageWork::kHull:
      return ray + 16 * patch + mask + 1;  // 16 verdict bits in one word
    case SubstageWork::kCenterDistance:
      return ray + 16 * patch + mask + 16 + 16 * 3;  // keys, centres
    case SubstageWork::kCull:
      return ray + 4 * patch + mask + 4 * 3;  // buffer1 and its centres
  }
  return 0;
}

}  // namespace rtsim::platform::wang_bezier
