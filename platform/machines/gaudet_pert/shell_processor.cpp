#include "platform/machines/gaudet_pert/shell_processor.hpp"

#include <stdexcept>
#include <string>

#include "firmware/accel/gaudet_data_sets.hpp"
#include "firmware/tasks/pert_task_costs.hpp"

namespace rtsim::platform::gaudet {

namespace {
const modules::CountParam kRaysInFlight(
    {.name = "rays_in_flight",
     .default_value = "1",
     .min = "1",
     .max = "100000",
     .unit = "rays",
     .description = "Rays a ShellProcessor searches at a time",
     .source = "assumption: not stated (note 001 §6.4); one, as \"no parallelism until the first "
               "packet is retrieved\" (L1060) suggests, brings Figs. 6-10 and 6-11 nearest the "
               "thesis (scripts/gaudet_sensitivity.py, docs/validation.md)"});
const modules::FlagParam kRootLocal(
    {.name = "root_local",
     .default_value = "true",
     .description = "The ShellProcessor holds packet 0 (the root's children) in its local memory "
                    "and reads it there for every ray, not off the bus",
     .source = "seed 001 L662 (every ray needs the root's children), L863 (the local memory "
               "holds the globals)"});
}  // namespace

void ShellProcessor::declare_params(const modules::ParamDecls& shell) {
  PertProcessor::declare_params(
      shell, {.value = "1",
              .description = "ID registers of the ShellProcessor's BIC (more IDs wait in its "
                             "memory)",
              .source = "assumption: not stated (L910: the ShellProcessor stores IDs continually, "
                        "\"may potentially overflow\" and stacks the overflow in its own "
                        "memory); 1 brings Fig. 6-10's latencies nearest the thesis's "
                        "(scripts/gaudet_sensitivity.py, docs/validation.md)"});
  shell.add(kRaysInFlight);
  shell.add(kRootLocal);
  BusInterface::declare_stream_param(
      shell.sub(kBic), "true",
      "seed 001 L920 (the hit line sets the buffer to start copying), L924 (the buffers are "
      "FIFOs the SJ16 reads a word a cycle): a SHELL record is tested once its words are in");
}

ShellProcessor::ShellProcessor(sc_core::sc_module_name name, const PertContext& c, PacketPort& port,
                               std::size_t input_depth)
    : PertProcessor(name, c.run, c.on_queue),
      input("input", input_depth, ring_queue("shade_to_shell")),
      out("out"),
      tree_(c.tree),
      packet_words_(c.sets.shell.packet_words),
      record_words_(ShellProcessor::record_words(c.words.shell)),
      port_(port),
      counters_(c.run.frame().counters()),
      searches_(std::max<std::size_t>(params_.get(kRaysInFlight), 1)) {
  // Loaded with the globals before the frame (L863): its time is not part of the frame.
  root_local_ = params_.get(kRootLocal) && !packet_words_.empty();
  if (root_local_) {
    // Packet 0: the root's children (L662).
    const auto root = c.sets.shell.image.packet(0);
    local_root_.assign(root.begin(), root.end());
  }
  start_program(program());
}

modules::Resumable ShellProcessor::ask(std::uint32_t packet, int search) {
  co_await compute_for(searches_[static_cast<std::size_t>(search)].ticket, Stage::kShell,
                       tasks::kAskPacketCost, "ask");
  if (packet >= waiting_.size()) waiting_.resize(std::size_t{packet} + 1);
  auto& w = waiting_[packet];
  w.push_back(search);
  if (w.size() > 1) co_return;  // already asked for by another ray
  ++packets_awaited_;
  co_await settle();
  if (!port_.request(packet, clock_.now())) {
    overflow_.push_back(packet);
    overflow_peak_.note(overflow_.size());
  }
}

modules::Resumable ShellProcessor::begin(ShadeToShell msg) {
  int slot = 0;
  while (searches_[static_cast<std::size_t>(slot)].active) ++slot;
  Search& s = searches_[static_cast<std::size_t>(slot)];
  s.active = true;
  s.ticket = msg.ticket;
  s.leaves.clear();
  s.outstanding = 0;
  const Ray& ray = s.ticket.ray.ray;
  s.inv_dir = Vec3(1.0 / ray.direction.x, 1.0 / ray.direction.y, 1.0 / ray.direction.z);
  // Until now (taken) the ray waited in the input queue.
  probe_->to(s.ticket, Stage::kShadeToShell, RayProbe::Part::kQueueing, clock_.now());
  co_await compute_for(s.ticket, Stage::kShell,
                       tasks::words_cost(ShadeToShell::kWords) + accel::kShellRaySetupCost, "ray");
  if (!accel::shell_search_possible(tree_, ray, s.ticket.t_min, s.ticket.ray.t_max)) {
    co_await finish(slot);
    co_return;
  }
  s.outstanding = 1;
  if (!root_local_) {
    co_await ask(0, slot);  // SHELL_ARRAY[0]: the root's children (L662)
    co_return;
  }
  // SHELL_ARRAY[0] from its own memory, read at one cycle a word as a FIFO's (L863).
  const std::vector<int> rays{slot};
  const ReceivedPacket root{
      .id = 0, .arrival = clock_.now(), .transfer_start = clock_.now(), .words = local_root_};
  co_await read_and_test(root, &rays);
}

modules::Resumable ShellProcessor::process(const ReceivedPacket& p) {
  const std::vector<int>* rays = nullptr;
  if (p.id < waiting_.size() && !waiting_[p.id].empty()) {
    // Taken out (a ray reading it may ask for it again); its place keeps an empty list's room.
    caught_for_.clear();
    caught_for_.swap(waiting_[p.id]);
    --packets_awaited_;
    rays = &caught_for_;
  }
  co_await read_and_test(p, rays);
  co_await settle();
  port_.release(p, clock_.now());
}

modules::Resumable ShellProcessor::read_and_test(const ReceivedPacket& p,
                                                 const std::vector<int>* rays) {
  ++packets_;
  const sc_core::sc_time read_start = clock_.now();
  co_await compute(tasks::words_cost(packet_words_[p.id]) + tasks::kPacketBookkeepingCost,
                   "packet");
  const sc_core::sc_time read_end = clock_.now();
  if (rays) {
    // The packet's SHELL records, read once for every ray waiting for it (as its words were).
    shells_.clear();
    for (std::size_t at = 0; at + record_words_ <= p.words.size(); at += record_words_) {
      const accel::Shell shell = accel::decode_shell(p.words.subspan(at, record_words_));
      if (shell.child_index < (shell.leaf ? tree_.prim_packet_count() : tree_.shell_packet_count()))
        shells_.emplace_back(shell, at + record_words_);
      else
        ++rejected_;
    }
    const std::size_t sharing = rays->size();
    for (std::size_t i = 0; i < sharing; ++i) {
      const int slot = (*rays)[i];
      Search& s = searches_[static_cast<std::size_t>(slot)];
      ++packet_uses_;
      // The packet was read once for every ray waiting for it: each gets its share.
      probe_->packet_gap(s.ticket, Stage::kShell, Stage::kShellBus, p, read_start);
      probe_->shared(s.ticket, Stage::kShell, read_start, read_end, i, sharing);
      // SHELL by SHELL: a hit parent's child packet is asked for as soon as its box test is
      // done, so the bus can bring it while the packet's other SHELLs are tested (L755-L757).
      for (const auto& [shell, end] : shells_) {
        // A streamed packet: its record is tested once its words are in (the first ray waits,
        // the others find them in). Nothing else can be done meanwhile: latency.
        co_await idle_until(p.words_in(end), Wait::kData);
        children_.clear();
        const std::size_t before = s.leaves.size();
        accel::shell_box_task(shell, s.ticket.ray.ray, s.inv_dir, s.ticket.t_min,
                              s.ticket.ray.t_max, s.leaves, children_);
        ++box_tests_;
        ++counters_.box_tests;
        co_await compute_for(
            s.ticket, Stage::kShell,
            accel::kShellBoxTestCost + tasks::kLeafShellAppendCost * (s.leaves.size() - before),
            "box test");
        s.outstanding += static_cast<int>(children_.size());
        for (const std::uint32_t c : children_) co_await ask(c, slot);
      }
      if (--s.outstanding == 0) co_await finish(slot);
    }
  }
}

modules::Resumable ShellProcessor::finish(int slot) {
  Search& s = searches_[static_cast<std::size_t>(slot)];
  co_await compute_for(s.ticket, Stage::kShell, tasks::leaf_shell_sort_cost(s.leaves.size()),
                       "sort");
  accel::sort_leaf_shell_list(s.leaves);
  leaf_shells_ += s.leaves.size();
  if (s.leaves.size() > accel::kLeafShellListCapacity) ++over_capacity_;
  done_.push_back(slot);
}

modules::Resumable ShellProcessor::program() {
  co_await begin_frame();
  // What it idles on: a packet, a ray, or (with a list to send) room in the output queue.
  constexpr unsigned starved_on = kPort | kInput;
  constexpr unsigned idle_on = kPort | kInput | kRoom;
  for (;;) {
    co_await settle();
    const sc_core::sc_time now = clock_.now();
    // A finished search goes on to the PrimProcessor when its queue has room.
    if (!done_.empty() && out_queue_->has_room_by(now)) {
      Search& s = searches_[static_cast<std::size_t>(done_.front())];
      done_.pop_front();
      ShellToPrim msg{s.ticket, std::move(s.leaves)};
      s.leaves = {};
      s.active = false;
      // Ready since its sort: until the queue had room it waited for the queue, then for
      // this processor.
      if (const auto room = out_queue_->next_room_time())
        probe_->to(msg.ticket, Stage::kShellToPrim, RayProbe::Part::kQueueing, *room);
      const WritingAhead ahead(*this);
      const sc_core::sc_time since = clock_.now();
      co_await compute_for(msg.ticket, Stage::kShell, tasks::words_cost(msg.words()), "send");
      const sc_core::sc_time arrival = over_link(msg.words(), since, msg.ticket);
      // A put into a full queue would wait for a take (TimedFifo::put): the loop looked for room
      // (has_room_by) and the send waits for nothing, so it never does.
      if (out_queue_->full())
        throw std::logic_error(std::string(name()) + ": sent into a full queue");
      modules::send_message(out, msg, arrival, std::uint64_t{32} * msg.words());
      ++rays_;
      continue;
    }
    if (auto p = port_.take(now)) {
      co_await process(*p);
      continue;
    }
    if (!overflow_.empty() && port_.register_free(now)) {
      const std::uint32_t id = overflow_.back();
      const sc_core::sc_time ask_start = clock_.now();
      co_await compute(tasks::kAskPacketCost, "ask");
      // Asked for every ray waiting for the ID, which till now waited for an ID register.
      if (id < waiting_.size()) {
        const std::vector<int>& w = waiting_[id];
        for (std::size_t i = 0; i < w.size(); ++i) {
          RayTicket& t = searches_[static_cast<std::size_t>(w[i])].ticket;
          probe_->to(t, Stage::kShellBus, RayProbe::Part::kQueueing, ask_start);
          probe_->shared(t, Stage::kShell, ask_start, clock_.now(), i, w.size());
        }
      }
      co_await settle();
      if (port_.request(id, clock_.now())) overflow_.pop_back();
      continue;
    }
    const bool slot_free =
        std::any_of(searches_.begin(), searches_.end(), [](const Search& s) { return !s.active; });
    if (slot_free && input.fifo.has_item_by(now)) {
      sc_core::sc_time taken;
      ShadeToShell msg = input.fifo.get(now, taken);
      co_await catch_up(taken);
      co_await begin(std::move(msg));
      continue;
    }
    // Nothing to do now: wait for a packet, a ray, or room in the output queue.
    std::optional<sc_core::sc_time> next = port_.next_arrival();
    auto earliest = [&next](std::optional<sc_core::sc_time> t) {
      if (t && (!next || *t < *next)) next = t;
    };
    if (slot_free) earliest(input.fifo.next_item_time());
    if (!done_.empty()) earliest(out_queue_->next_room_time());
    // Waiting for a packet is latency only when the processor has nothing else it could do:
    // with a ray slot free and no ray in its input queue, it is starved of rays instead
    // (L1060-L1062: waiting that a new ray could overlap is not latency).
    const bool for_bus = packets_awaited_ > 0;
    if (for_bus && slot_free && done_.empty())
      co_await idle_starved(next, starved_on);
    else
      co_await idle(next, idle_on, for_bus);
  }
}

}  // namespace rtsim::platform::gaudet
