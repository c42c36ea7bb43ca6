#include "platform/machines/gaudet_pert/pert.hpp"

#include <string>

#include "platform/machines/gaudet_pert/bus_interface.hpp"
#include "platform/machines/gaudet_pert/local_data_set.hpp"

namespace rtsim::platform::gaudet {

namespace {

// A PERT's own parameters (pert.*), each named once.
const modules::TimeParam kFirstAccess(
    {.name = "memory.first_access",
     .default_value = "200 ns",
     .description = "Direct memory: first-access latency of a packet in a processor's own memory "
                    "(later words stream at one cycle each)",
     .source = "assumption: one SJ16 cycle; seed 001 L863 gives only the streamed rate"});
modules::CountParam queue(const char* link, const char* from_to) {
  return modules::CountParam(
      {.name = std::string("queue.") + link,
       .default_value = "4",
       .min = "1",
       .max = "100000",
       .unit = "messages",
       .description = std::string("Queue depth ") + from_to,
       .source = "assumption: queues inside a PERT are not described (note 001 §2.1)"});
}
// The queue at the end of each of Pert::kLinks.
const modules::CountParam kShadeToShell =
    queue(Pert::kLinks[0], "ShadeProcessor -> ShellProcessor");
const modules::CountParam kShellToPrim = queue(Pert::kLinks[1], "ShellProcessor -> PrimProcessor");
const modules::CountParam kPrimToShade = queue(Pert::kLinks[2], "PrimProcessor -> ShadeProcessor");
const modules::ChoiceParam kSync(
    {.name = "sync",
     .default_value = "interactions",
     .allowed = {"interactions", "computations"},
     .description =
         "When a PERT processor's program waits for simulated time to reach its own: only before "
         "it interacts with another module (its queues, its bus interface; interactions), or "
         "after every computation as well (computations: the reference). At quantum 0 the "
         "statistics and the image are the same either way (tests/gaudet_sync_test.cpp); the "
         "first waits about a third less. Above quantum 0 the quantum decides",
     .source = "simulator setting, not of the machine"});
/// Its three processors (their names and their parameters' paths), in ring order, and its links.
constexpr const char* kShade = "shade";
constexpr const char* kShell = "shell";
constexpr const char* kPrim = "prim";
constexpr const char* kLink = "link";

}  // namespace

void Pert::declare_params(const modules::ParamDecls& pert) {
  ShadeProcessor::declare_params(pert.sub(kShade));
  ShellProcessor::declare_params(pert.sub(kShell));
  PrimProcessor::declare_params(pert.sub(kPrim));
  pert.add(kFirstAccess);
  pert.add(kSync);
  for (const auto* q : {&kShadeToShell, &kShellToPrim, &kPrimToShade}) pert.add(*q);
  // The links the messages cross into those queues: FIFOs a 32-bit word wide, written a word
  // per cycle, so a message arrives as its sender writes its last word.
  for (const char* link : kLinks)
    modules::Link::declare_params(
        pert.sub(kLink).sub(link),
        {.latency = "0 s",
         .lanes = "32",
         .bit_rate = "5 Mbit/s",
         .source = "seed 001 L924 (FIFO words one per cycle), L951 (5 MHz); assumption: no "
                   "flight time beyond the words (queues inside a PERT are not described, "
                   "note 001 §2.1)"});
}

Pert::Pert(sc_core::sc_module_name name, int index, const PertContext& c)
    : sc_core::sc_module(name) {
  const modules::ModuleParams params(c.run.registry(), this->name());
  constexpr const char* kKinds[] = {kShade, kShell, kPrim};
  const DataSetImage* set_of[] = {&c.sets.shade, &c.sets.shell, &c.sets.prim};
  // Its own memory's first access: what a packet costs when the PERT holds the data sets.
  const sc_core::sc_time first_access = params.get(kFirstAccess);
  for (std::size_t k = 0; k < 3; ++k) {
    if (!c.buses.empty()) {
      // The ShellProcessor reads its packets SHELL record by SHELL record (`stream`).
      auto bic =
          std::make_unique<BusInterface>(params.sub(kKinds[k]).sub(PertProcessor::kBic),
                                         k == 1 ? ShellProcessor::record_words(c.words.shell) : 0);
      c.buses[k]->attach(*bic);
      ports[k] = std::move(bic);
    } else {
      ports[k] = std::make_unique<LocalDataSet>(first_access, set_of[k]->memory,
                                                set_of[k]->order.size(), c.words.id_list_entry);
    }
  }
  shade = std::make_unique<ShadeProcessor>(kShade, c, index, *ports[0], params.get(kPrimToShade));
  shell = std::make_unique<ShellProcessor>(kShell, c, *ports[1], params.get(kShadeToShell));
  prim = std::make_unique<PrimProcessor>(kPrim, c, *ports[2], params.get(kShellToPrim));
  for (std::size_t k = 0; k < 3; ++k)
    links[k] = std::make_unique<modules::Link>(params.sub(kLink).sub(kLinks[k]));
  shade->set_output_link(*links[0]);
  shell->set_output_link(*links[1]);
  prim->set_output_link(*links[2]);
  const auto sync = params.get(kSync) == "computations" ? PertProcessor::Sync::kComputations
                                                        : PertProcessor::Sync::kInteractions;
  shade->set_sync(sync);
  shell->set_sync(sync);
  prim->set_sync(sync);
  shade->set_probe(c.probe);
  shell->set_probe(c.probe);
  prim->set_probe(c.probe);
  // The ring: Shade -> Shell -> Prim -> Shade.
  shade->out.bind(shell->input.socket);
  shade->set_output_queue(shell->input.fifo);
  shell->out.bind(prim->input.socket);
  shell->set_output_queue(prim->input.fifo);
  prim->out.bind(shade->input.socket);
  prim->set_output_queue(shade->input.fifo);
  shade->wire(*ports[0], shade->input.fifo, shell->input.fifo);
  shell->wire(*ports[1], shell->input.fifo, prim->input.fifo);
  prim->wire(*ports[2], prim->input.fifo, shade->input.fifo);
}

void Pert::join(modules::WakeQueue& queue) {
  shade->join(queue);
  shell->join(queue);
  prim->join(queue);
}

}  // namespace rtsim::platform::gaudet
