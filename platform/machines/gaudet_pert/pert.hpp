#pragma once
// One PERT (seed 001 §2.1, §5.2, L841-L863): a ring of a ShadeProcessor, a ShellProcessor and a
// PrimProcessor with the queues between them, each processor with its port to its data set (a
// Bus Interface Controller on its broadcast bus, or its own memory for the direct-memory
// baseline). A SystemC module of its own, so the processors' names are pert0.shade,
// pert0.shell, pert0.prim — the names of their parameters (pert.shade.clock sets every PERT's,
// pert3.shade.clock one), statistics and trace tracks.
#include <array>
#include <memory>
#include <systemc>
#include <vector>

#include "firmware/cost.hpp"
#include "modules/link.hpp"
#include "modules/module_params.hpp"
#include "modules/wake_queue.hpp"
#include "platform/machines/gaudet_pert/broadcast_processor.hpp"
#include "platform/machines/gaudet_pert/data_sets.hpp"
#include "platform/machines/gaudet_pert/pert_context.hpp"
#include "platform/machines/gaudet_pert/prim_processor.hpp"
#include "platform/machines/gaudet_pert/shade_processor.hpp"
#include "platform/machines/gaudet_pert/shell_processor.hpp"

namespace rtsim::platform::gaudet {

class Pert : public sc_core::sc_module {
 public:
  /// The PERT's parameters under `pert`: its three processors' (and their BICs'), the queues
  /// of the ring and the first-access time of its own memory (direct memory).
  static void declare_params(const modules::ParamDecls& pert);

  /// PERT number `index` (it renders scanlines index, index + N, ..., L938).
  Pert(sc_core::sc_module_name name, int index, const PertContext& context);

  /// Elaboration (the context's on_queue): its processors join `queue`.
  void join(modules::WakeQueue& queue);

  /// The ring's links, in front of those queues: shade_to_shell, shell_to_prim, prim_to_shade
  /// (pert0.link.shade_to_shell, ...).
  static constexpr const char* kLinks[] = {"shade_to_shell", "shell_to_prim", "prim_to_shade"};
  std::array<std::unique_ptr<modules::Link>, 3> links;

  /// Shade, Shell and Prim: each processor's port to its data set.
  std::array<std::unique_ptr<PacketPort>, 3> ports;
  std::unique_ptr<ShadeProcessor> shade;
  std::unique_ptr<ShellProcessor> shell;
  std::unique_ptr<PrimProcessor> prim;
};

}  // namespace rtsim::platform::gaudet
