#include "platform/machines/ullner_array/array_node.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "firmware/accel/grid_traversal.hpp"
#include "firmware/kernels/ullner_quad_words.hpp"
#include "modules/activations.hpp"
#include "modules/prefetch.hpp"
#include "modules/sim_time.hpp"
#include "platform/machines/ullner_array/broadcast_record.hpp"

namespace rtsim::platform::ullner_array {

using modules::Direction;
using modules::GridNode;
using modules::plus;
using modules::times;

namespace {

std::size_t type_index(MessageType t) { return static_cast<std::size_t>(t); }

/// std::llround (half away from zero) inline for a non-negative x below 2^62, where it is the
/// same: x - trunc(x) is exact. The library's is a call, 1.9 M of them at 32 x 32 (spend).
std::int64_t round_half_away(double x) {
  if (!(x >= 0.0 && x < 0x1p62)) return std::llround(x);
  const auto whole = static_cast<std::int64_t>(x);
  return whole + (x - static_cast<double>(whole) >= 0.5 ? 1 : 0);
}

}  // namespace

std::vector<std::size_t> load_words_needed(const accel::UniformGrid& grid,
                                           const SubvolumeMapping& mapping,
                                           const modules::MeshTopology& topology,
                                           const functional::SceneGeometry& geometry,
                                           std::size_t attribute_words, std::size_t view_words) {
  // The memory fills in the order the records come: lines, attributes, lists, view; each
  // record is received into the next free words first.
  auto normals = [&](std::uint32_t slot) {
    return std::get<kernels::UllnerQuadKernel>(geometry.shapes[slot].shape).has_corner_normals;
  };
  const auto nodes = static_cast<std::size_t>(topology.nodes());
  std::vector<std::vector<std::uint32_t>> kept(nodes);
  std::vector<std::size_t> lists(nodes, 0);
  const accel::GridDivisions n = grid.divisions();
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        const accel::CellIndex c{x, y, z};
        const auto slots = grid.cell(c);
        if (slots.empty()) continue;
        const auto k = static_cast<std::size_t>(topology.index(mapping.node_of(c)));
        lists[k] += 1 + slots.size();
        kept[k].insert(kept[k].end(), slots.begin(), slots.end());
      }
  // A polygon it discards still passes through the buffer above the lines kept so far.
  std::size_t largest = 0;
  for (std::size_t slot = 0; slot < geometry.shapes.size(); ++slot)
    largest = std::max(largest, polygon_record_words(normals(static_cast<std::uint32_t>(slot))));
  std::vector<std::size_t> need(nodes);
  for (std::size_t k = 0; k < nodes; ++k) {
    std::sort(kept[k].begin(), kept[k].end());
    kept[k].erase(std::unique(kept[k].begin(), kept[k].end()), kept[k].end());
    std::size_t lines = 0;
    for (const std::uint32_t slot : kept[k]) lines += polygon_line_words(normals(slot));
    need[k] = std::max(lines + largest, lines + attribute_words + lists[k] + view_words);
  }
  return need;
}

namespace {

// A processor's parameters, each named once (every processor alike: the class `node`).
const char* const kCpuSource =
    "assumption: the thesis gives no MC68000 timings (seed 000 L835; note 000 §7.6): a few dozen "
    "instructions of 4-10 cycles each";

modules::CountParam cycles(const char* what, const char* value, const char* description) {
  return modules::CountParam({.name = std::string("cycles.") + what,
                              .default_value = value,
                              .max = "1000000000",
                              .unit = "cycles",
                              .description = description,
                              .source = kCpuSource});
}

const modules::FrequencyParam kClock(
    {.name = "clock",
     .default_value = "8 MHz",
     .min = "1 Hz",
     .description = "Clock of a processor's MC68000-class CPU",
     .source = "seed 000 L835 (MC68000); assumption: 8 MHz, the part of 1982"});
const modules::CountParam kMessageCycles = cycles(
    "message", "120", "CPU cycles to take a message from a port buffer and dispatch on its type");
const modules::CountParam kRouteCycles =
    cycles("route", "80",
           "CPU cycles to choose the port toward a processor and start the port's copy (routing "
           "is in software, L854)");
const modules::CountParam kSubvolumeCycles =
    cycles("subvolume", "100",
           "CPU cycles to step to the next subvolume along a ray (Appendix B) and start the "
           "intersection unit on its polygons (L852)");
const modules::CountParam kShadeCycles =
    cycles("shade", "400",
           "CPU cycles to shade a hit with the lighting unit (ambient, lights, reflection and "
           "refraction terms, L809-L817)");
const modules::CountParam kSpawnCycles = cycles(
    "spawn", "80", "CPU cycles to format a new message (result, shadow, reflected, refracted)");
const modules::CountParam kResultCycles =
    cycles("result", "60", "CPU cycles to add a result's colour into the frame buffer (L809)");
const modules::CountParam kNewRayCycles =
    cycles("new_ray", "150", "CPU cycles to make a new ray for one of its pixels (L801)");
const modules::CountParam kKeepTestCycles =
    cycles("keep_test", "200",
           "CPU cycles to decide whether a broadcast polygon touches its subvolumes (L787)");
const modules::CountParam kSortCycles =
    cycles("sort", "60",
           "CPU cycles to enter one kept polygon into one of its subvolume lists after the load "
           "(the sort that simulates the third dimension, L858)");
const modules::TimeParam kMemoryCycle(
    {.name = "memory_cycle",
     .default_value = "333.333 ns",
     .description = "One 16-bit transfer of a processor's memory, shared by the CPU's ports and "
                    "the intersection unit (a 32-bit word is two)",
     .source = "seed 000 L835, L891 (16-bit path); assumption: the peripheral's 1/3 us cycle, as "
               "L891's 40-processor estimate supposes"});
const modules::RealParam kCpuMemoryShare(
    {.name = "cpu_memory_share",
     .default_value = "0.6",
     .min = "0",
     .max = "1",
     .unit = "",
     .description =
         "Share of the CPU's computing time its bus cycles hold the shared memory (it is "
         "shared with the microprocessor, L839), interleaved with what the memory owes the "
         "ports' copies and the intersection unit: the CPU is done when its own time has passed "
         "and the memory has served it",
     .source = "assumption: an MC68000 runs a 4-clock bus cycle (500 ns at 8 MHz) for nearly "
               "every instruction slot (prefetch), each holding the 1/3 us memory for one cycle: "
               "about 0.9 x 333/500 = 0.6"});
const modules::CountParam kMemoryWords(
    {.name = "memory_words",
     .default_value = "32768",
     .min = "1",
     .max = "1000000000",
     .unit = "words",
     .description = "Words of a processor's memory for its polygons (128 KB)",
     .source = "seed 000 L835"});
const modules::TimeParam kStageTime(
    {.name = "pipeline.stage_time",
     .default_value = "333.333 ns",
     .description = "Stage time of the intersection pipeline (one test issued per stage time at "
                    "most)",
     .source = "assumption: custom shift-and-add units (L837) pipelined to keep pace with the "
               "memory, as L891 assumes"});
const modules::ChoiceParam kFetchPriority(
    {.name = "pipeline.fetch_priority",
     .default_value = "later_stages",
     .allowed = {"later_stages", "earlier_stages"},
     .description = "Which waiting fetch of the intersection pipeline the memory serves first: "
                    "the latest stage's, as the thesis has it to prevent log jams, or the "
                    "earliest's (an ablation)",
     .source = "seed 000 L850"});
const modules::TimeParam kCreditQuietTime(
    {.name = "credit_quiet_time",
     .default_value = "300 us",
     .description = "Termination: a processor out of work keeps the credit it holds (its own and "
                    "what other processors sent it on their way to the detector) until it has "
                    "been idle this long, then sends it all one hop toward the detector in one "
                    "message. Longer: fewer credit messages, a later end of frame (each hop to "
                    "the detector can wait this long once the last ray is done)",
     .source = "assumption: the thesis gives no termination mechanism (L827); 300 us, with "
               "credit carried on messages, keeps credit under 5% of message hops on "
               "builtin:ullner-cubes at 64x64 (1.9-2.5% from 8x8 to 32x32; alone 3.1-5.2%), "
               "where returning it at once made half the hops"});
const modules::ChoiceParam kCreditTravel(
    {.name = "credit_travel",
     .default_value = "carried",
     .allowed = {"carried", "alone"},
     .description =
         "Termination: how held credit goes toward the detector. carried: it also rides on any "
         "message this processor sends over the link toward the detector (every message has a "
         "credit word, so this costs nothing), and goes alone only when the quiet time ends "
         "with credit still held; alone: only in credit messages",
     .source = "assumption: the thesis gives no termination mechanism (L827); carried: "
               "credit on messages that travel anyway costs no bits and, at 32x32, halves "
               "the credit messages"});
const modules::ChoiceParam kProcess(
    {.name = "process",
     .default_value = "queue",
     .allowed = {"queue", "method", "thread"},
     .description =
         "How the simulator runs each processor: event-driven, handling what is due at its "
         "time and computing ahead, activated by the array's own event queue (queue) or by "
         "SystemC as an SC_METHOD each (method); or as a SystemC thread that waits wherever it "
         "spends time (thread: the reference). The statistics and the image are the same "
         "(tests/ullner_array_test.cpp)",
     .source = "simulator setting, not of the machine"});
/// Its links to the neighbours (the class's: node.link.*).
constexpr const char* kLinkClass = "link";

}  // namespace

void ArrayNode::declare_params(const modules::ParamDecls& node) {
  node.add(kClock);
  for (const auto* p :
       {&kMessageCycles, &kRouteCycles, &kSubvolumeCycles, &kShadeCycles, &kSpawnCycles,
        &kResultCycles, &kNewRayCycles, &kKeepTestCycles, &kSortCycles})
    node.add(*p);
  node.add(kMemoryCycle);
  node.add(kCpuMemoryShare);
  node.add(kMemoryWords);
  node.add(kStageTime);
  node.add(kFetchPriority);
  node.add(kCreditQuietTime);
  node.add(kCreditTravel);
  node.add(kProcess);
  modules::Link::declare_params(
      node.sub(kLinkClass),
      {.latency = "0 s",
       .lanes = "16",
       .bit_rate = "",
       .bit_time = "333.333 ns",
       .source = "assumption: the thesis gives no link width or rate (L854); a port copies 16 "
                 "bits a memory cycle, the memory's own path"});
}

namespace {
/// One cycle of the CPU's clock, whole picoseconds.
sc_core::sc_time cpu_cycle(const modules::ModuleParams& p) {
  return modules::from_ps(
      static_cast<std::int64_t>(std::max(1.0, std::round(1e12 / p.get(kClock).hz))));
}
}  // namespace

std::string ArrayNode::process_kind(const params::ParamRegistry& registry) {
  return modules::ModuleParams(registry, kClass).get(kProcess);
}

std::size_t ArrayNode::memory_words(const params::ParamRegistry& registry) {
  return modules::ModuleParams(registry, kClass).get(kMemoryWords);
}

std::string ArrayNode::memory_words_name(const params::ParamRegistry& registry) {
  return modules::ModuleParams(registry, kClass).path_of(kMemoryWords.name());
}

ArrayNode::ArrayNode(sc_core::sc_module_name name, const params::ParamRegistry& registry,
                     const ArrayContext& context, ArrayTally& tally, GridNode position,
                     MachineTrace& trace)
    : modules::Processor(name, trace),
      ctx_(context),
      tally_(tally),
      position_(position),
      memory("memory", memory_words(registry), 1, sc_core::SC_ZERO_TIME, sc_core::SC_ZERO_TIME),
      broadcast_in("broadcast_in"),
      frame_buffer("frame_buffer", block_words(context, position), 1, sc_core::SC_ZERO_TIME,
                   sc_core::SC_ZERO_TIME),
      shade_(local_, context.shade),
      dda_(*context.grid),
      memory_port_("memory_port"),
      frame_buffer_port_("frame_buffer_port"),
      pipeline_(std::string(this->name()) + ".pipeline") {
  const modules::ModuleParams p(registry, kClass);
  timing_ = Timing{.message = p.get(kMessageCycles),
                   .route = p.get(kRouteCycles),
                   .subvolume = p.get(kSubvolumeCycles),
                   .shade = p.get(kShadeCycles),
                   .spawn = p.get(kSpawnCycles),
                   .result = p.get(kResultCycles),
                   .new_ray = p.get(kNewRayCycles),
                   .keep_test = p.get(kKeepTestCycles),
                   .sort = p.get(kSortCycles),
                   .memory_cycle = p.get(kMemoryCycle),
                   .cpu_memory_share = p.get(kCpuMemoryShare),
                   .pipeline = {.memory_cycle = p.get(kMemoryCycle),
                                .stage_time = p.get(kStageTime),
                                .priority = p.get(kFetchPriority) == "earlier_stages"
                                                ? FetchPriority::kEarlierStages
                                                : FetchPriority::kLaterStages},
                   .credit_quiet = p.get(kCreditQuietTime),
                   .credit_carried = p.get(kCreditTravel) == "carried"};
  cycle_ = cpu_cycle(p);
  memory_port_.bind(memory.socket);
  frame_buffer_port_.bind(frame_buffer.socket);
  broadcast_in.register_b_transport(this, &ArrayNode::receive_record);
  const modules::MeshTopology& topo = *ctx_.topology;
  // Only a thread waits on its ports' put events; an event-driven processor is woken by
  // item_put.
  const bool thread = p.get(kProcess) == "thread";
  waits_on_ports_ = thread;
  if (ctx_.ring) {
    in[kRingPort] = std::make_unique<modules::MessageQueue<RayMessage>>(
        "in_ring", modules::TimedFifo<RayMessage>::kUnbounded);
    in[kRingPort]->fifo.listen(this, thread, kRingPort);
  }
  for (const Direction d : modules::kDirections) {
    if (ctx_.ring || !topo.neighbour(position_, d)) continue;
    const std::string dir(modules::direction_name(d));
    // A port's buffer holds the node's stockpile of untraced messages (L825): not bounded here.
    in[static_cast<int>(d)] = std::make_unique<modules::MessageQueue<RayMessage>>(
        ("in_" + dir).c_str(), modules::TimedFifo<RayMessage>::kUnbounded);
    in[static_cast<int>(d)]->fifo.listen(this, thread, static_cast<int>(d));
    out_[static_cast<int>(d)] =
        std::make_unique<tlm_utils::simple_initiator_socket<ArrayNode>>(("out_" + dir).c_str());
    links_[static_cast<int>(d)] =
        std::make_unique<modules::Link>(std::string(this->name()) + ".link_" + dir,
                                        modules::ModuleParams(registry, kClass).sub(kLinkClass));
    if (ctx_.message_faults)
      for (MessageFault& f : *ctx_.message_faults)
        if (f.node == topo.index(position_) && f.direction == d)
          link_faults_[static_cast<int>(d)].push_back(&f);
    sent_by_link_[static_cast<int>(d)] = std::make_unique<modules::CounterArray>(
        *links_[static_cast<int>(d)], "messages_", message_type_names(),
        "messages through the link, by type");
  }
  // Its ports in the broadcast's spanning tree (broadcast_children()).
  auto hop = [&](const GridNode& child, const char* name, modules::Link* link) {
    BroadcastHop h;
    h.child = child;
    h.socket = std::make_unique<tlm_utils::simple_initiator_socket<ArrayNode>>(name);
    h.link = link;
    broadcast_out_.push_back(std::move(h));
  };
  if (ctx_.ring) {
    if (topo.index(position_) + 1 < topo.nodes())
      hop(topo.node(topo.index(position_) + 1), "broadcast_ring", nullptr);
  } else {
    if (position_.row == 0 && position_.col + 1 < topo.cols())
      hop({0, position_.col + 1}, "broadcast_e", links_[static_cast<int>(Direction::kEast)].get());
    if (position_.row + 1 < topo.rows())
      hop({position_.row + 1, position_.col}, "broadcast_s",
          links_[static_cast<int>(Direction::kSouth)].get());
  }
  // Its frame-buffer block: the image rows and columns whose processor it is (L781).
  block_ = block_of(context, position_);
  if (thread) {
    SC_THREAD(run);
  } else if (p.get(kProcess) == "queue") {
    if (!ctx_.queue) throw std::logic_error("ullner-array: node.process = queue without a queue");
    make_queue_driven("activate");
    queue_slot_ = ctx_.queue->add(*this);  // its first activation when the view has been sent
  } else {
    make_event_driven();
    SC_METHOD(activate);
    sensitive << *ctx_.loaded;  // its first activation; each sets its next itself
    dont_initialize();
  }
}

ArrayNode::Block ArrayNode::block_of(const ArrayContext& ctx, const GridNode& at) {
  // The image rows and columns whose processor it is (pixel_owner's rule): a block, possibly
  // empty on an array with more processors than pixels along a side.
  const int w = ctx.frame->width(), h = ctx.frame->height();
  const int rows = ctx.topology->rows(), cols = ctx.topology->cols();
  Block b;
  b.first_row = (at.row * h + rows - 1) / rows;
  b.end_row = ((at.row + 1) * h + rows - 1) / rows;
  b.first_col = (at.col * w + cols - 1) / cols;
  b.end_col = ((at.col + 1) * w + cols - 1) / cols;
  return b;
}

std::size_t ArrayNode::block_words(const ArrayContext& ctx, const GridNode& at) {
  const Block b = block_of(ctx, at);
  // One word at least: a Memory of no words is not a memory.
  return std::max<std::size_t>(1, static_cast<std::size_t>(b.end_row - b.first_row) *
                                      static_cast<std::size_t>(b.end_col - b.first_col) *
                                      kPixelWords);
}

void ArrayNode::connect(Direction d, ArrayNode& neighbour) {
  out_[static_cast<int>(d)]->bind(neighbour.in[static_cast<int>(modules::opposite(d))]->socket);
  neighbour_[static_cast<std::size_t>(d)] = &neighbour;
}

void ArrayNode::prepare_receive(Direction from) const {
  // A hint to the cache, no more: what the put into that port and item_put() touch.
  in[static_cast<std::size_t>(from)]->fifo.prepare_put();
  modules::prefetch_object(front_);
  modules::prefetch_object(idle_);
}

std::vector<GridNode> ArrayNode::broadcast_children() const {
  std::vector<GridNode> out;
  for (const auto& hop : broadcast_out_) out.push_back(hop.child);
  return out;
}

void ArrayNode::connect_broadcast(std::size_t k, ArrayNode& child) {
  broadcast_out_.at(k).socket->bind(child.broadcast_in);
}

void ArrayNode::spend(std::uint64_t cycles, std::string_view what) {
  const sc_core::sc_time t = times(cycle_, cycles);
  if (t == sc_core::SC_ZERO_TIME) return;
  // Its bus cycles hold the memory for a share of the time (L839), interleaved with what the
  // memory already owes the ports' copies and the unit's fetches: it computes meanwhile, and is
  // done when its own time has passed and the memory has served it too (it waits for the rest).
  const auto hold = modules::from_ps(static_cast<std::int64_t>(
      round_half_away(static_cast<double>(t.value()) * timing_.cpu_memory_share)));
  memory_free_ = plus(std::max(clock_.now(), memory_free_), hold);
  memory_busy_ += hold;
  cpu_memory_busy_ += hold;
  compute_for(t, what);
  if (memory_free_ > clock_.now()) {
    memory_waited_ += memory_free_ - clock_.now();
    idle_until(memory_free_, Wait::kData);
  }
}

GridNode pixel_processor(int x, int y, int width, int height,
                         const modules::MeshTopology& topology) {
  return {y * topology.rows() / height, x * topology.cols() / width};
}

GridNode ArrayNode::pixel_owner(std::uint32_t pixel) const {
  const int w = ctx_.frame->width();
  return pixel_processor(static_cast<int>(pixel % static_cast<std::uint32_t>(w)),
                         static_cast<int>(pixel / static_cast<std::uint32_t>(w)), w,
                         ctx_.frame->height(), *ctx_.topology);
}

void ArrayNode::receive_record(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  const auto* copy = gp.get_extension<BroadcastCopy>();
  const std::size_t n = gp.get_data_length() / 4;
  if (!copy || n == 0 || gp.get_data_length() % 4 != 0) {
    gp.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return;
  }
  // No room for it (only a fault can bring this about: a record read as the wrong kind keeps
  // more than the load's check counted): the port cannot take it, and it goes no further.
  if (next_free_ + n > memory.size_words()) {
    ++records_dropped_;
    gp.set_response_status(tlm::TLM_OK_RESPONSE);
    return;
  }
  // The copy starts when the sender offers it and this processor's buffer and memory are free;
  // the port writes the record into the buffer (a fault in this memory applies there).
  const sc_core::sc_time now = modules::sim_now();
  const sc_core::sc_time start = std::max({plus(now, delay), buffer_free_, memory_free_});
  const sc_core::sc_time arrived = plus(start, copy->duration);
  memory_free_ = arrived;
  load_memory_busy_ += copy->duration;
  sc_core::sc_time unused = sc_core::SC_ZERO_TIME;
  modules::write_words(memory_port_, next_free_,
                       reinterpret_cast<const std::uint32_t*>(gp.get_data_ptr()), n, unused);
  ++records_;
  delay = start - now;
  handle_record(next_free_, n, arrived);
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

void ArrayNode::handle_record(std::uint64_t at, std::size_t n, const sc_core::sc_time& arrived) {
  const std::span<const std::uint32_t> record(memory.contents().data() + at, n);
  const sc_core::sc_time began = std::max(arrived, load_cpu_free_);
  sc_core::sc_time t = plus(began, times(cycle_, timing_.message));
  // Pass it on down the tree first (routing in software, L854), then decide on it (L787).
  for (auto& hop : broadcast_out_) {
    t = plus(t, times(cycle_, timing_.route));
    pass_on(hop, record, t);
  }
  switch (record_kind(record[0])) {
    case RecordKind::kPolygon:
      t = plus(t, times(cycle_, timing_.keep_test));
      if (keep(record, static_cast<std::uint32_t>(line_at_.size()))) {
        line_at_.push_back(static_cast<std::uint32_t>(at));
        next_free_ += n - std::min(n, kBoundsWords);  // the line stays; its bounds are not read
      }
      break;
    case RecordKind::kAttributes:
      read_attributes(record, local_);
      next_free_ += n;
      t = sort(t);
      if (ctx_.ready) ctx_.ready->raise(t);
      break;
    case RecordKind::kView:
      read_view(record, local_.camera);
      next_free_ += n;
      break;
    case RecordKind::kNone:
      break;  // a record it cannot read (a fault) is dropped
  }
  load_cpu_free_ = t;
  load_busy_ += t - began;
  buffer_free_ = std::max(t, memory_free_);  // the copies out of the buffer are done
  frame_ready_ = t;
}

void ArrayNode::pass_on(BroadcastHop& hop, std::span<const std::uint32_t> record,
                        const sc_core::sc_time& ready) {
  // The copy holds the link (or the ring's segment) and this memory: on a link, its
  // serialisation and latency; on the ring, the record's packets, headers and all, and a hop.
  sc_core::sc_time duration, serialisation;
  if (hop.link) {
    serialisation = hop.link->serialisation(32 * static_cast<std::uint64_t>(record.size()));
    duration = plus(serialisation, hop.link->latency());
  } else {
    const modules::TokenRing& ring = *ctx_.ring_medium;
    serialisation = ring.transmission(ring.wire_bytes(record.size() * 4));
    duration = plus(serialisation, ring.hop_latency());
  }
  const sc_core::sc_time offered = std::max({ready, memory_free_, hop.free});
  const sc_core::sc_time start = offer_record(*hop.socket, record, offered, duration);
  hop.free = plus(start, serialisation);
  memory_free_ = hop.free;
  load_link_busy_ += serialisation;
  load_memory_busy_ += serialisation;
}

bool ArrayNode::keep(std::span<const std::uint32_t> record, std::uint32_t line) {
  accel::CellIndex first, last;
  if (!ctx_.record_cells->touched(record, first, last)) return false;
  // The subvolumes the bounds touch that are its own: in each depth layer, the block of them
  // within its own block of that layer (SubvolumeMapping's inverse).
  const SubvolumeMapping& m = ctx_.mapping;
  // A processor's block along the rows is the same in every layer but on the torus, and along
  // the columns in the straight mapping only: a record whose bounds miss such a block misses it
  // in every layer (most of a large array's processors, for most records), and the layers need
  // not be visited.
  const auto misses = [](SubvolumeMapping::Range own, int lo, int hi) {
    return std::max(own.lo, lo) > std::min(own.hi - 1, hi);
  };
  if (m.mapping != Mapping::kTorus &&
      misses(m.owned_along_rows(position_.row, 0), first[m.row_axis], last[m.row_axis]))
    return false;
  if (m.mapping == Mapping::kStraight &&
      misses(m.owned_along_cols(position_.col, 0), first[m.col_axis], last[m.col_axis]))
    return false;
  bool kept = false;
  for (int d = first[m.depth_axis]; d <= last[m.depth_axis]; ++d) {
    const SubvolumeMapping::Range a = m.owned_along_cols(position_.col, d);
    const SubvolumeMapping::Range b = m.owned_along_rows(position_.row, d);
    const int a0 = std::max(a.lo, first[m.col_axis]), a1 = std::min(a.hi - 1, last[m.col_axis]);
    const int b0 = std::max(b.lo, first[m.row_axis]), b1 = std::min(b.hi - 1, last[m.row_axis]);
    for (int j = b0; j <= b1; ++j)
      for (int i = a0; i <= a1; ++i) {
        int at[3];
        at[m.depth_axis] = d;
        at[m.col_axis] = i;
        at[m.row_axis] = j;
        pending_[ctx_.grid->linear_index({at[0], at[1], at[2]})].push_back(line);
        kept = true;
      }
  }
  return kept;
}

sc_core::sc_time ArrayNode::sort(sc_core::sc_time t) {
  // Each list: its count, then its line numbers, ascending (the order they came), written
  // through the memory's port in subvolume order.
  std::vector<std::size_t> cells;
  cells.reserve(pending_.size());
  for (const auto& [c, lines] : pending_) cells.push_back(c);
  std::sort(cells.begin(), cells.end());
  std::vector<std::uint32_t> words;
  std::vector<std::pair<std::size_t, std::uint64_t>> lists;
  std::uint64_t entries = 0;
  for (const std::size_t c : cells) {
    const auto& lines = pending_[c];
    lists.emplace_back(c, next_free_ + words.size());
    words.push_back(static_cast<std::uint32_t>(lines.size()));
    words.insert(words.end(), lines.begin(), lines.end());
    entries += lines.size();
  }
  pending_.clear();
  // A second sort (only when a fault made another record read as the attributes) replaces the
  // lists of the subvolumes it has lists for and keeps the others'.
  std::vector<std::pair<std::size_t, std::uint64_t>> merged;
  merged.reserve(list_at_.size() + lists.size());
  auto old = list_at_.begin();
  for (const auto& entry : lists) {
    for (; old != list_at_.end() && old->first < entry.first; ++old) merged.push_back(*old);
    if (old != list_at_.end() && old->first == entry.first) ++old;
    merged.push_back(entry);
  }
  merged.insert(merged.end(), old, list_at_.end());
  list_at_ = std::move(merged);
  if (words.empty()) return t;
  if (next_free_ + words.size() > memory.size_words()) {
    // As for a record: no room (only under a fault); the subvolumes keep no lists.
    ++records_dropped_;
    list_at_.clear();
    return t;
  }
  sc_core::sc_time unused = sc_core::SC_ZERO_TIME;
  modules::write_words(memory_port_, next_free_, words.data(), words.size(), unused);
  next_free_ += words.size();
  t = plus(t, times(cycle_, timing_.sort * entries));
  const sc_core::sc_time start = std::max(t, memory_free_);
  const sc_core::sc_time write = times(timing_.memory_cycle, 2 * words.size());
  memory_free_ = plus(start, write);
  load_memory_busy_ += write;
  return memory_free_;
}

std::span<const std::uint32_t> ArrayNode::candidates(const accel::CellIndex& c) const {
  const std::size_t i = ctx_.grid->linear_index(c);
  const auto it =
      std::lower_bound(list_at_.begin(), list_at_.end(), i,
                       [](const auto& entry, std::size_t k) { return entry.first < k; });
  if (it == list_at_.end() || it->first != i) return {};
  const auto& words = memory.contents();
  const std::uint64_t at = it->second;
  const std::uint64_t count = std::min<std::uint64_t>(words[at], words.size() - at - 1);
  return {words.data() + at + 1, static_cast<std::size_t>(count)};
}

const std::vector<kernels::UllnerQuadParams<double>>& ArrayNode::held() {
  if (memory.words_written() == decoded_after_) return decoded_;
  const auto& words = memory.contents();
  decoded_.resize(line_at_.size());
  for (std::size_t k = 0; k < line_at_.size(); ++k)
    decoded_[k] = kernels::load_words(std::span<const std::uint32_t, kernels::kUllnerStoredWords>(
        words.data() + line_at_[k] + kLineParams, kernels::kUllnerStoredWords));
  decoded_after_ = memory.words_written();
  return decoded_;
}

ArrayNode::~ArrayNode() {
  // Made in the constructor's body, after the memories: destroyed before them.
  for (auto port = in.rbegin(); port != in.rend(); ++port) port->reset();
}

void ArrayNode::item_put(int port, const sc_core::sc_time& stamp) {
  std::uint64_t& front = front_[static_cast<std::size_t>(port)];
  if (front == kNoMessage) front = stamp.value();  // else an older message is first
  if (!idle_) return;  // it looks at its ports when it has done what it is doing
  const sc_core::sc_time now = modules::sim_now();
  if (ctx_.queue)
    ctx_.queue->wake_at(queue_slot_, std::max(stamp, now));  // the sooner one stands
  else
    wake_.notify(stamp > now ? stamp - now : sc_core::SC_ZERO_TIME);
}

void ArrayNode::prepare() const {
  // A hint to the cache, no more: the lines activate(), step() and next_message() read first.
  prepare_activation();
  modules::prefetch_object(position_);
  modules::prefetch_object(own_);
  modules::prefetch_object(front_);
  modules::prefetch_object(idle_);
  modules::prefetch_object(received_);
  const std::size_t first = first_port();
  if (front_[first] != kNoMessage) in[first]->fifo.prepare_get();
}

bool ArrayNode::next_message(RayMessage& msg) {
  const sc_core::sc_time now = clock_.now();
  // The port whose message arrived first, if one has by now.
  const std::size_t best = first_port();
  if (front_[best] != kNoMessage && front_[best] <= now.value()) {
    const sc_core::sc_time best_t = modules::from_ticks(front_[best]);
    sc_core::sc_time taken;
    modules::TimedFifo<RayMessage>& port = in[best]->fifo;
    msg = port.get(now, taken);
    const std::optional<sc_core::sc_time> next = port.next_item_time();
    front_[best] = next ? next->value() : kNoMessage;
    received_.add(type_index(msg.type));
    // --trace perfetto: the message's flow steps through the processor that takes it.
    if (msg.links > 0 && traced_)
      trace_.flow(name(), "message", msg.id, modules::PerfettoTrace::FlowPhase::kStep, now);
    // On a ring the journey ran from the copy out to the delivery into this port.
    probe_to(msg, ctx_.stages.ring, modules::LatencyPart::kTransfer, best_t);
    probe_to(msg, ctx_.stages.in, modules::LatencyPart::kQueueing, taken);
    receive_copy(best_t);
    return true;
  }
  if (!own_.empty()) {
    msg = std::move(own_.front());
    own_.pop_front();
    probe_to(msg, ctx_.stages.node, modules::LatencyPart::kQueueing, now);
    return true;
  }
  // A new ray for its next pixel (L801), when it has nothing else to do.
  while (!vision_ || vision_->done()) {
    if (block_.first_row + next_row_ >= block_.end_row || block_.first_col >= block_.end_col)
      return false;
    const auto y = static_cast<std::uint32_t>(block_.first_row + next_row_++);
    const int w = ctx_.frame->width();
    vision_ = std::make_unique<tasks::VisionRayTask>(
        *camera_, w, ctx_.frame->height(), ctx_.frame->spp(),
        y * static_cast<std::uint32_t>(w) + static_cast<std::uint32_t>(block_.first_col),
        y * static_cast<std::uint32_t>(w) + static_cast<std::uint32_t>(block_.end_col),
        ctx_.frame->detailed_rows());
  }
  int sample = 0;
  msg = RayMessage{};
  msg.type = MessageType::kNew;
  msg.ray = vision_->next(sample);
  msg.first_sample = sample == 0;
  msg.credit = ctx_.credit_per_ray;
  msg.created = now;
  msg.id = ++tally_.messages_made;
  msg.tree = ++tally_.rays_made;
  if (ctx_.probe) {
    msg.journey = ctx_.probe->begin(now);
    msg.cursor = now;
  }
  spend(timing_.new_ray, "new ray");
  return true;
}

void ArrayNode::start_frame() {
  camera_.emplace(local_.camera, ctx_.frame->width(), ctx_.frame->height());
  for (auto& q : in) {
    if (!q) continue;
    ports_ = true;
    if (waits_on_ports_) any_ |= q->fifo.put_event();
  }
  started_ = true;
  // The load ran in annotated time when the host broadcast; the frame starts once this
  // processor has handled the view.
  clock_.catch_up(frame_ready_);
}

ArrayNode::Step ArrayNode::step() {
  RayMessage msg;
  if (next_message(msg)) {
    process(std::move(msg));
    backlog_peak_.note(own_.size());
    quiet_since_.reset();
    return {};
  }
  if (!quiet_since_) quiet_since_ = clock_.now();
  const sc_core::sc_time send_at = plus(*quiet_since_, timing_.credit_quiet);
  // Out of work for the quiet time: what credit it holds goes one hop toward the detector,
  // where the next processor adds it to its own (a combining tree: a credit message crosses
  // one link, not the whole way, and messages meeting in a processor become one).
  if (credit_held_ > 0 && (position_ == GridNode{0, 0} || clock_.now() >= send_at)) {
    const std::uint64_t c = credit_held_;
    credit_held_ = 0;
    RayMessage back;
    back.type = MessageType::kCredit;
    back.credit = c;
    back.id = ++tally_.messages_made;
    if (position_ == GridNode{0, 0}) {
      process(std::move(back));
    } else {
      spend(timing_.message, "message");
      forward(std::move(back), GridNode{0, 0});
    }
    return {};
  }
  if (!ports_)
    return {.kind = Step::Kind::kFinished, .until = std::nullopt};  // a 1x1 array with no work left
  // Wait for a message: the first stamped ahead of its local time, or one put meanwhile on
  // another port that comes sooner; or for the quiet time to be over.
  std::optional<sc_core::sc_time> until;
  if (const std::uint64_t first = front_[first_port()]; first != kNoMessage)
    until = modules::from_ticks(first);
  if (credit_held_ > 0 && (!until || send_at < *until)) until = send_at;
  return {.kind = Step::Kind::kIdle, .until = until};
}

void ArrayNode::run() {
  modules::sim_wait(*ctx_.loaded);
  start_frame();
  for (;;) {
    const Step s = step();
    if (s.kind == Step::Kind::kFinished) return;
    if (s.kind == Step::Kind::kIdle) idle(s.until, any_, Wait::kWork);
  }
}

void ArrayNode::activate() {
  resume();
  idle_ = false;
  if (!started_) start_frame();
  // Handle what is due at this time; once it has computed ahead, look again then (a message
  // stamped by then may yet come: every message is put before its stamp).
  while (clock_.now() == modules::sim_now()) {
    const Step s = step();
    if (s.kind == Step::Kind::kFinished) return;  // never triggered again
    if (s.kind == Step::Kind::kIdle) {
      // Woken when the first message is due or the quiet time ends, or sooner by a put
      // (item_put), not by every put into its ports.
      idle_ = true;
      if (ctx_.queue) {
        begin_idle(Wait::kWork);
        if (s.until) ctx_.queue->wake_at(queue_slot_, *s.until);
        return;
      }
      if (s.until) wake_.notify(*s.until - modules::systemc_now());
      idle_trigger(std::nullopt, wake_, Wait::kWork);
      return;
    }
  }
  if (ctx_.queue)
    ctx_.queue->wake_at(queue_slot_, clock_.now());
  else
    resume_at_local_time();
}

void ArrayNode::process(RayMessage&& msg) {
  spend(timing_.message, "message");
  switch (msg.type) {
    case MessageType::kNew: {
      // Route it toward the processor owning the first subvolume it strikes (L803-L805).
      std::optional<accel::CellIndex> first;
      dda_.traverse(msg.ray.ray, shade_.t_min(msg.ray), msg.ray.t_max,
                    [&](const accel::CellIndex& c, std::span<const std::uint32_t>, double, double) {
                      first = c;
                      return true;
                    });
      if (!first) {
        // It misses the modelling space: it falls off the array (L807).
        answer(msg, false, Hit{});
        return;
      }
      const GridNode owner = ctx_.mapping.node_of(*first);
      if (!(owner == position_)) {
        forward(std::move(msg), owner);
        return;
      }
      msg.type = MessageType::kVision;
      ++entered_;
      search(msg);
      return;
    }
    case MessageType::kVision:
    case MessageType::kShadow:
      search(msg);
      return;
    case MessageType::kResult: {
      const GridNode owner = pixel_owner(msg.ray.pixel);
      if (!(owner == position_)) {
        forward(std::move(msg), owner);
        return;
      }
      add_result(msg);
      return;
    }
    case MessageType::kCredit:
      if (!(position_ == GridNode{0, 0})) {
        return_credit(msg.credit);  // it goes on with this processor's own, when it is idle
        return;
      }
      tally_.credit_returned += msg.credit;
      if (tally_.credit_returned == ctx_.total_credit) {
        tally_.done = clock_.now();
        // A delay for SystemC counts from its own time (the queue may run this ahead of it).
        tally_.frame_done.notify(clock_.now() - modules::systemc_now());
      }
      return;
  }
}

void ArrayNode::add_result(const RayMessage& msg) {
  spend(timing_.result, "result");
  ++tally_.results_added;
  if (tally_.results_added == ctx_.drop_result) {
    ++tally_.results_dropped;  // lost: its contribution never reaches the frame buffer
  } else {
    accumulate(msg.ray.pixel, msg.contribution);
  }
  tally_.latency.add(clock_.now() - msg.created);
  if (ctx_.probe && msg.journey != modules::LatencyProbe::kNoJourney) {
    ctx_.probe->add(msg.journey, ctx_.stages.node, modules::LatencyPart::kService,
                    clock_.now() - msg.cursor);
    ctx_.probe->end(msg.journey, clock_.now());
  }
  return_credit(msg.credit);
}

void ArrayNode::accumulate(std::uint32_t pixel, const Color& c) {
  // Added into its block of the frame buffer (L809): the pixel's sums read, added to, written
  // back through the port. The memory's time is a 24-bit colour's, read and written on the
  // 16-bit path (4 transfers; the model keeps wider sums so that the order results arrive in
  // cannot change a bit of the image).
  const int w = ctx_.frame->width();
  const int x = static_cast<int>(pixel % static_cast<std::uint32_t>(w));
  const int y = static_cast<int>(pixel / static_cast<std::uint32_t>(w));
  if (!block_.holds(x, y))
    SC_REPORT_ERROR("rtsim/ullner-array",
                    "a result reached a processor "
                    "whose block does not hold its pixel");
  std::array<std::uint32_t, kPixelWords> words{};
  const modules::PooledPayload gp;
  sc_core::sc_time unused = sc_core::SC_ZERO_TIME;
  const std::uint64_t at = block_.offset(x, y);
  modules::read_words(frame_buffer_port_, *gp, at, words.data(), kPixelWords, unused);
  const std::array<double, 3> add{c.r, c.g, c.b};
  for (int k = 0; k < 3; ++k) {
    auto sum = static_cast<std::int64_t>(words[2 * k] |
                                         (static_cast<std::uint64_t>(words[2 * k + 1]) << 32));
    sum += shading::PixelAccumulator::to_fixed(add[k]);
    words[2 * k] = static_cast<std::uint32_t>(static_cast<std::uint64_t>(sum));
    words[2 * k + 1] = static_cast<std::uint32_t>(static_cast<std::uint64_t>(sum) >> 32);
  }
  modules::write_words(frame_buffer_port_, *gp, at, words.data(), kPixelWords, unused);
  book_memory(times(timing_.memory_cycle, 4));
  // Sampled simulation times its windows by these (at this processor's time, which may be
  // ahead of the simulation's).
  ctx_.frame->fb().notify(pixel, clock_.now().value());
}

void ArrayNode::return_credit(std::uint64_t credit) { credit_held_ += credit; }

void ArrayNode::account(RayMessage& msg, int stage, modules::LatencyPart part,
                        const sc_core::sc_time& t) {
  if (stage < 0 || t <= msg.cursor) return;
  ctx_.probe->add(msg.journey, stage, part, t - msg.cursor);
  msg.cursor = t;
}

void ArrayNode::search(RayMessage& msg) {
  // Walk the ray's subvolumes from where it left off; search those this processor owns, each
  // for a hit within it (L807); stop at the first owned by another processor.
  const shading::TracedRay& r = msg.ray;
  const bool shadow = r.kind == RayKind::Shadow;
  const double t_min = shade_.t_min(r);
  const auto& params = held();
  const auto ray = kernels::UllnerRay<double>::make(r.ray.origin, r.ray.direction);
  std::uint32_t step = 0;
  std::optional<GridNode> next_owner;
  accel::GridHit hit;
  SurfaceHit details;
  std::uint64_t cells = 0, tests = 0;
  TraceCounters& counters = ctx_.frame->counters();
  // The intersection unit's test of one polygon (a line number from the subvolume's list) on
  // the words this memory holds. The answer is the search's, with the bound as it stands; what
  // the unit did is noted for its timing (intersection_pipeline.hpp): t against the subvolume's
  // own bound (`list_bound`), u and v, which do not depend on the bound.
  stream_.clear();
  double list_bound = r.t_max;
  bool first_of_list = false;
  std::uint32_t list = 0;
  auto test = [&](std::uint32_t line, double lo, double hi) {
    if (line >= params.size()) return kInfinity;  // an entry no line has (a fault)
    ++tests;
    ++counters.intersection_tests;
    const auto& P = params[line];
    const auto res = kernels::intersect(P, ray, lo, list_bound);
    stream_.push_back({.t = res.t,
                       .t_in_range = res.t_valid,
                       .u_valid = res.u_valid,
                       .v_valid = res.v_valid,
                       .bound = list_bound,
                       .immediate_bound = hi,
                       .list = list,
                       .first_of_list = first_of_list,
                       .any_hit = shadow});
    first_of_list = false;
    // In range of the bound as it stands (hi <= list_bound): intersect(P, ray, lo, hi)'s answer.
    if (!res.hit() || !(res.t < hi)) return kInfinity;
    details.t = res.t;
    details.u = res.u;
    details.v = res.v;
    details.geometric_normal = P.n_p();
    return res.t;
  };
  accel::GridTraversalStats st;
  bool occluded = false;
  // Where the last processor's walk stopped, if the message still says (ray_message.hpp): the
  // walk goes on from that subvolume rather than from the ray's origin.
  accel::DdaPlace from;
  if (msg.resume > 0 && msg.walk_at == msg.resume) {
    from = {.cell = msg.walk_cell, .t_enter = msg.walk_t_enter, .visited = msg.resume + 1u};
    step = msg.resume;
  }
  const auto walk = dda_.traverse_from(
      r.ray, t_min, r.t_max, from,
      [&](const accel::CellIndex& c, std::span<const std::uint32_t>, double t_enter,
          double t_exit) {
        if (step++ < msg.resume) return false;
        const GridNode owner = ctx_.mapping.node_of(c);
        if (!(owner == position_)) {
          next_owner = owner;
          msg.resume = step - 1;
          msg.walk_at = msg.resume;
          msg.walk_cell = c;
          msg.walk_t_enter = t_enter;
          return true;
        }
        ++cells;
        const std::span<const std::uint32_t> lines = candidates(c);
        first_of_list = true;  // stage 1 fetches the list's count with its first entry
        if (cells > 1) ++list;
        if (shadow) {
          list_bound = r.t_max;
          for (const std::uint32_t line : lines) {
            const double t = test(line, t_min, r.t_max);
            if (t > t_min && t < r.t_max) {
              occluded = true;
              return true;
            }
          }
          return false;
        }
        // subvolume_closest_hit's first bound: the end of the ray's part in this subvolume.
        list_bound = std::min(r.t_max, std::nextafter(t_exit, kInfinity));
        hit = accel::subvolume_closest_hit(lines, t_min, r.t_max, t_exit, test, st);
        return hit.valid();
      });
  counters.cells_visited += cells;
  counters.dda_steps += walk.steps;
  subvolumes_ += cells;
  tests_ += tests;

  // The time: the CPU steps through its subvolumes and starts the unit on each; the unit's
  // fetches share the memory with the ports (from when the memory is free), and the CPU waits
  // for its interrupt when the last polygon leaves the pipe.
  spend(timing_.subvolume * cells, "subvolumes");
  if (!stream_.empty()) {
    probe_to(msg, ctx_.stages.node, modules::LatencyPart::kService, clock_.now());
    const sc_core::sc_time start = std::max(clock_.now(), memory_free_);
    memory_waited_ += start - clock_.now();
    const PipelineRun run = run_pipeline(stream_, start, timing_.pipeline);
    memory_free_ = run.memory_end;
    memory_busy_ += run.memory_busy;
    pipeline_.words_fetched += run.words;
    pipeline_.words_wasted += run.wasted_words;
    pipeline_.busy.record(start, run.done - start);
    probe_to(msg, ctx_.stages.pipeline, modules::LatencyPart::kQueueing, start);
    probe_to(msg, ctx_.stages.pipeline, modules::LatencyPart::kService, run.done);
    idle_until(run.done, Wait::kData);
  }

  if (next_owner) {
    forward(std::move(msg), *next_owner);
    return;
  }
  if (shadow) {
    answer(msg, occluded, Hit{});
    return;
  }
  Hit h;
  if (hit.valid()) surface(static_cast<std::uint32_t>(hit.prim), details, h);
  answer(msg, hit.valid(), h);
}

void ArrayNode::surface(std::uint32_t line, const SurfaceHit& s, Hit& hit) const {
  // The rest of the hit from the polygon's line: its identity, its material, and the shading
  // normal of its corner normals when it has them (L452-L456).
  const auto& words = memory.contents();
  const std::uint64_t at = line_at_[line];
  hit.surface = s;
  hit.surface.shading_normal = s.geometric_normal;
  hit.prim_id = static_cast<std::int32_t>(words[at + kLineIdentity] & 0x7fffffffu);
  hit.material = std::min<std::uint32_t>(words[at + kLineMaterial],
                                         static_cast<std::uint32_t>(local_.materials.size() - 1));
  if ((words[at] & kRecordHasNormals) && at + kLineNormals + kNormalWords <= words.size()) {
    const std::span<const std::uint32_t> n(words.data() + at + kLineNormals, kNormalWords);
    auto vec = [&](std::size_t k) {
      return Vec3(get_real(n, 6 * k), get_real(n, 6 * k + 2), get_real(n, 6 * k + 4));
    };
    hit.surface.shading_normal = kernels::ullner_shading_normal(vec(0), vec(1), vec(2), vec(3), s.u,
                                                                s.v, s.geometric_normal);
  }
}

void ArrayNode::answer(const RayMessage& msg, bool found, const Hit& hit) {
  // The ray is answered here: shade a hit (ambient into a result, a shadow ray per light, the
  // reflected and refracted rays, L809-L817); a miss adds the background (a shadow ray that
  // left unobstructed, its light: L815).
  TraceCounters& counters = ctx_.frame->counters();
  counters.count_ray(msg.ray.kind);
  if (found && msg.ray.kind != RayKind::Shadow) ++counters.hits;
  if (msg.first_sample) ctx_.frame->record_primary(msg.ray.pixel, found, hit);
  Color contribution{0.0};
  const auto a = shade_.answer(msg.ray, found, hit, contribution, spawned_);
  counters.cost += a.cost;
  if (found && msg.ray.kind != RayKind::Shadow) spend(timing_.shade, "shade");
  // The message's credit is shared by what it sends (the first takes the remainder); with
  // nothing to send it is returned.
  const std::uint64_t outputs = (a.contributes ? 1 : 0) + spawned_.size();
  if (outputs == 0) {
    if (ctx_.probe) ctx_.probe->drop(msg.journey);  // nothing of it reaches a pixel
    return_credit(msg.credit);
    return;
  }
  // Too little to share (only a corrupted credit: the host gives 2^40 a ray): some get none,
  // and the detector may see the end before they are done.
  if (msg.credit < outputs) ++tally_.credit_exhausted;
  const std::uint64_t share = msg.credit / outputs;
  std::uint64_t extra = msg.credit - share * outputs;
  std::vector<RayMessage> out;
  out.reserve(outputs);
  if (a.contributes) {
    RayMessage res;
    res.type = MessageType::kResult;
    res.ray = msg.ray;
    res.contribution = contribution;
    res.created = msg.created;
    out.push_back(std::move(res));
  }
  for (const auto& s : spawned_) {
    RayMessage m;
    m.type = s.kind == RayKind::Shadow ? MessageType::kShadow : MessageType::kVision;
    m.ray = s;
    m.created = msg.created;
    out.push_back(std::move(m));
  }
  // Each output's latency counts from the same ray's creation: the first continues its journey,
  // the others continue copies of it, all copied before the first is sent on (it may end, and
  // free, its journey at once).
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].journey = k == 0 || !ctx_.probe ? msg.journey : ctx_.probe->fork(msg.journey);
    out[k].cursor = msg.cursor;
    out[k].hops = msg.hops;  // the watchdog counts along the ray tree
    out[k].id = ++tally_.messages_made;
    out[k].tree = msg.tree;
  }
  for (auto& m : out) {
    m.credit = share + extra;
    extra = 0;
    spend(timing_.spawn, "spawn");
    probe_to(m, ctx_.stages.node, modules::LatencyPart::kService, clock_.now());
    if (m.type == MessageType::kResult) {
      const GridNode owner = pixel_owner(m.ray.pixel);
      if (owner == position_)
        add_result(m);
      else
        forward(std::move(m), owner);
    } else {
      own_.push_back(std::move(m));
    }
  }
}

void ArrayNode::forward(RayMessage&& msg, const GridNode& to) {
  if (++msg.hops > ctx_.hop_limit) {
    ++tally_.looping;
    if (ctx_.probe) ctx_.probe->drop(msg.journey);
    return_credit(msg.credit);
    return;
  }
  // On the mesh: the link and the neighbour's port and state, on their way into the cache while
  // the route, the copy and the link are timed.
  std::optional<Direction> d;
  if (!ctx_.ring) {
    d = ctx_.topology->next_hop(position_, to);
    const auto k = static_cast<std::size_t>(*d);
    if (links_[k]) links_[k]->prepare_transfer();
    if (const ArrayNode* n = neighbour_[k]) n->prepare_receive(modules::opposite(*d));
  }
  spend(timing_.route, "route");
  probe_to(msg, ctx_.stages.node, modules::LatencyPart::kService, clock_.now());
  if (ctx_.ring) {
    // On a ring the message goes straight to its destination's port: the copy out waits for
    // the memory, then the ring carries it (accounted where it is taken).
    const sc_core::sc_time start = copy_out();
    probe_to(msg, ctx_.stages.ring, modules::LatencyPart::kQueueing, start);
    sent_.add(type_index(msg.type));
    const auto cls = static_cast<std::size_t>(type_index(msg.type));
    const auto me = static_cast<std::size_t>(ctx_.topology->index(position_));
    const auto dest = static_cast<std::size_t>(ctx_.topology->index(to));
    ctx_.ring->send(me, dest, std::move(msg), RayMessage::kWireBits / 8, start, cls);
    return;
  }
  send(std::move(msg), *d);
}

void ArrayNode::receive_copy(const sc_core::sc_time& arrived) {
  // The port copied the message into this memory as it came over the link, 16 bits a memory
  // cycle (L854: a copy costs memory time at both ends). Where this processor's own fetches and
  // copies held the memory during that time, the copy waited for them: the message is all there
  // that much later, and the CPU reads it then. (Booked when the message is taken, in this
  // processor's order of time; its own bookings come first.)
  const sc_core::sc_time copy = times(timing_.memory_cycle, 2 * RayMessage::kWords);
  const sc_core::sc_time from = arrived > copy ? arrived - copy : sc_core::SC_ZERO_TIME;
  const sc_core::sc_time overlap =
      memory_free_ > from ? std::min(copy, memory_free_ - from) : sc_core::SC_ZERO_TIME;
  const sc_core::sc_time landed = plus(arrived, overlap);
  memory_waited_ += overlap;
  memory_busy_ += copy;
  memory_free_ = std::max(memory_free_, landed);
  if (landed > clock_.now()) idle_until(landed, Wait::kData);
}

sc_core::sc_time ArrayNode::book_memory(const sc_core::sc_time& d) {
  const sc_core::sc_time start = std::max(clock_.now(), memory_free_);
  memory_waited_ += start - clock_.now();
  memory_free_ = plus(start, d);
  memory_busy_ += d;
  return start;
}

sc_core::sc_time ArrayNode::copy_out() {
  // The port copies the message out of this memory (L854), 16 bits a memory cycle.
  return book_memory(times(timing_.memory_cycle, 2 * RayMessage::kWords));
}

void ArrayNode::send(RayMessage&& msg, Direction d) {
  // The port copies the message out of this memory into the neighbour's (L854).
  const int k = static_cast<int>(d);
  if (!out_[k]) SC_REPORT_ERROR("rtsim/ullner-array", "a message was routed off the array");
  modules::Link& link = *links_[k];
  const sc_core::sc_time start = copy_out();
  const sc_core::sc_time arrived = link.transfer(RayMessage::kWireBits, start);
  probe_to(msg, ctx_.stages.link, modules::LatencyPart::kQueueing, start);
  probe_to(msg, ctx_.stages.link, modules::LatencyPart::kTransfer, arrived);
  sent_.add(type_index(msg.type));
  sent_by_link_[k]->add(type_index(msg.type));
  if (traced_) {
    // --trace perfetto: the message on the link, and its flow from link to processor to link.
    const int to = ctx_.topology->index(*ctx_.topology->neighbour(position_, d));
    trace_.slice(link.name(), message_type_names()[type_index(msg.type)], start, arrived - start,
                 {{"ray", msg.tree},
                  {"message", msg.id},
                  {"from", ctx_.topology->index(position_)},
                  {"to", to}});
    trace_.flow(link.name(), "message", msg.id,
                msg.links == 0 ? modules::PerfettoTrace::FlowPhase::kStart
                               : modules::PerfettoTrace::FlowPhase::kStep,
                start);
  }
  ++msg.links;
  if (timing_.credit_carried && credit_held_ > 0 && !(position_ == GridNode{0, 0}) &&
      d == ctx_.topology->next_hop(position_, GridNode{0, 0})) {
    // The held credit rides on a message going the detector's way anyway (its credit word); the
    // next processor keeps it, or passes it on with the message.
    msg.credit += credit_held_;
    credit_held_ = 0;
    ++tally_.credit_carried;
  }
  for (MessageFault* f : link_faults_[k]) f->apply(msg, ctx_.frame->width(), ctx_.frame->height());
  modules::send_message(*out_[k], msg, arrived, RayMessage::kWireBits);
}

}  // namespace rtsim::platform::ullner_array
