#include "platform/machines/gaudet_pert/pert.hpp"

#include <string>

#include "platform/machines/gaudet_pert/bus_interface.hpp"
#include "platform/machines/gaudet_pert/local_data_set.hpp"

namespace rtsim::platform::gaudet {

void Pert::declare_params(const modules::ParamDecls& pert) {
  ShadeProcessor::declare_params(pert.sub("shade"));
  ShellProcessor::declare_params(pert.sub("shell"));
  PrimProcessor::declare_params(pert.sub("prim"));
  pert.time("memory.first_access", "200 ns",
            "Direct memory: first-access latency of a packet in a processor's own memory "
            "(later words stream at one cycle each)",
            "assumption: one SJ16 cycle; seed 001 L863 gives only the streamed rate");
  const char* queue_src = "assumption: queues inside a PERT are not described (note 001 §2.1)";
  pert.count("queue.shade_to_shell", "4", "1", "100000", "messages",
             "Queue depth ShadeProcessor -> ShellProcessor", queue_src);
  pert.count("queue.shell_to_prim", "4", "1", "100000", "messages",
             "Queue depth ShellProcessor -> PrimProcessor", queue_src);
  pert.count("queue.prim_to_shade", "4", "1", "100000", "messages",
             "Queue depth PrimProcessor -> ShadeProcessor", queue_src);
  // The links the messages cross into those queues: FIFOs a 32-bit word wide, written a word
  // per cycle, so a message arrives as its sender writes its last word.
  for (const char* link : kLinks)
    modules::Link::declare_params(
        pert.sub("link").sub(link),
        {.latency = "0 s",
         .lanes = "32",
         .bit_rate = "5 Mbit/s",
         .source = "seed 001 L924 (FIFO words one per cycle), L951 (5 MHz); assumption: no "
                   "flight time beyond the words (queues inside a PERT are not described, "
                   "note 001 §2.1)"});
}

Pert::Pert(sc_core::sc_module_name name, int index, const PertContext& c)
    : sc_core::sc_module(name) {
  const modules::ModuleParams params(c.registry, this->name());
  constexpr const char* kKinds[] = {"shade", "shell", "prim"};
  const DataSetImage* set_of[] = {&c.sets.shade, &c.sets.shell, &c.sets.prim};
  // Its own memory's first access: what a packet costs when the PERT holds the data sets.
  const sc_core::sc_time first_access = params.get_time("memory.first_access");
  for (std::size_t k = 0; k < 3; ++k) {
    if (!c.buses.empty()) {
      // The ShellProcessor reads its packets SHELL record by SHELL record (`stream`).
      auto bic =
          std::make_unique<BusInterface>(params.sub(kKinds[k]).sub("bic"),
                                         k == 1 ? ShellProcessor::record_words(c.words.shell) : 0);
      c.buses[k]->attach(*bic);
      ports[k] = std::move(bic);
    } else {
      ports[k] = std::make_unique<LocalDataSet>(first_access, set_of[k]->memory,
                                                set_of[k]->order.size(), c.words.id_list_entry);
    }
  }
  shade =
      std::make_unique<ShadeProcessor>("shade", c.registry, index, c.pert_count, c.shade, *ports[0],
                                       params.get_count("queue.prim_to_shade"), c.trace);
  shell = std::make_unique<ShellProcessor>(
      "shell", c.registry, c.tree, c.sets.shell.packet_words, c.words.shell,
      c.sets.shell.image.packet_count() > 0 ? c.sets.shell.image.packet(0)
                                            : std::span<const std::uint32_t>{},
      *ports[1], params.get_count("queue.shade_to_shell"), c.counters, c.trace);
  prim = std::make_unique<PrimProcessor>(
      "prim", c.registry, c.geometry, c.words, c.sets.prim.packet_words, c.test_cost, *ports[2],
      params.get_count("queue.shell_to_prim"), c.counters, c.trace);
  for (std::size_t k = 0; k < 3; ++k)
    links[k] = std::make_unique<modules::Link>(params.sub("link").sub(kLinks[k]));
  shade->set_output_link(*links[0]);
  shell->set_output_link(*links[1]);
  prim->set_output_link(*links[2]);
  shade->set_probe(c.probe);
  shell->set_probe(c.probe);
  prim->set_probe(c.probe);
  // The ring: Shade -> Shell -> Prim -> Shade.
  shade->out.bind(shell->input.socket);
  shade->set_output_queue(shell->input.fifo);
  shell->out.bind(prim->input.socket);
  shell->set_output_queue(prim->input.fifo);
  prim->out.bind(shade->input.socket);
}

}  // namespace rtsim::platform::gaudet
