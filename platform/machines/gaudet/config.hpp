#pragma once
// Gaudet's multi-PERT machine: its parameters as the modules use them (read once from the
// registry by platform/machines/gaudet_pert.cpp, where each is declared with its source).
#include <cstdint>
#include <systemc>

#include "modules/broadcast_processor.hpp"
#include "modules/processor_timing.hpp"

namespace rtsim::platform::gaudet {

/// How the processors get the data sets (seed 001 §5.1, Fig. 6-9).
enum class BroadcastMode {
  kAdaptive,     ///< only packets some BIC asked for are sent (§5.1.2, L835-L837)
  kNonAdaptive,  ///< every packet every cycle (L837, L1047)
  kDirect,       ///< no broadcast: every processor holds its whole data set (L806, L1103)
};

/// Order of the ID list in the Broadcast Processors' memories (Fig. 6-11, L1019).
enum class BroadcastOrder { kBreadth, kDepth, kRandom };

/// One kind of PERT processor (Shade, Shell or Prim): an SJ16 with its FPU and its BIC.
struct ProcessorConfig {
  modules::ProcessorTiming timing;
  std::size_t id_registers = 4;
  std::size_t buffers = 2;
  std::size_t rays_in_flight = 1;
};

struct PertConfig {
  int pert_count = 1;
  BroadcastMode mode = BroadcastMode::kAdaptive;
  BroadcastOrder order = BroadcastOrder::kBreadth;
  std::uint64_t order_seed = 1985;
  modules::BroadcastTiming bus;
  sc_core::sc_time load_word_time;  ///< control processor -> BP memories
  sc_core::sc_time first_access;    ///< direct memory: first-access latency
  ProcessorConfig shade, shell, prim;
  std::size_t shade_to_shell_depth = 4;  ///< messages
  std::size_t shell_to_prim_depth = 4;
  std::size_t prim_to_shade_depth = 4;

  bool broadcasting() const { return mode != BroadcastMode::kDirect; }
};

}  // namespace rtsim::platform::gaudet
