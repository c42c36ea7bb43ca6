#pragma once
// The transactions between the host of Wang, Lewis & Hung's machine and its pipeline (note 002,
// "Transactions"): a ray/patch job (the ray in the pipeline's single precision and the patch's
// control net, L296) and its result (the centre of the closest surviving subpatch, or none).
#include <cstdint>
#include <systemc>

#include "firmware/kernels/bezier_wang.hpp"

namespace rtsim::platform::wang_bezier {

struct PatchJob {
  std::uint64_t ray = 0;             ///< the host's ray it belongs to
  std::uint32_t slot = 0;            ///< the patch (its shape slot)
  Vec3T<float> o{0.0f}, d{0.0f};     ///< the ray as the pipeline takes it
  kernels::ControlNet<float> net{};  ///< the patch's 16 control points
  sc_core::sc_time sent;             ///< when the host issued it
  sc_core::sc_time arrived;          ///< when it reached the pipeline's input
  /// O, D (6 words) and 16 x 3 control-point words (192 bytes, note 002 "Transactions").
  static constexpr std::uint64_t kWireBits = 32 * (6 + 48);
};

struct JobResult {
  std::uint64_t ray = 0;
  std::uint32_t slot = 0;
  /// What left the last stage (its single or wide words; a single is exact in double).
  kernels::WangResult<double> result;
  sc_core::sc_time sent;  ///< when its job was issued (job latency)
  /// When stage 0 took its job, and when it left the last stage (--latency-probe: timing
  /// metadata, not on the wire).
  sc_core::sc_time accepted, left;
  /// The centre (3 words), (u, v) and a hit flag.
  static constexpr std::uint64_t kWireBits = 32 * 6;
};

}  // namespace rtsim::platform::wang_bezier
