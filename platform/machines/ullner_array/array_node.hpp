#pragma once
// One processor of Ullner's ray-tracing array (seed 000 §2.5.2, L829-L858): an MC68000-class CPU
// (its costs per message handled are parameters: the thesis gives none), its memory shared with
// the intersection unit and the link ports, the 9-stage intersection pipeline of Fig. 2-28, and
// four link ports, each copying a ray message from this memory into a neighbour's (L854; routing
// in software). It owns a column of subvolumes (subvolume_mapping.hpp) and the block of the frame
// buffer at its position in the array (L781).
//
// Its work (L799-L819): a new ray is routed to the processor owning the first subvolume it
// strikes; a vision or shadow ray is searched through this processor's subvolumes along it, one
// subvolume at a time (the closest hit within the subvolume, accel::subvolume_closest_hit), then
// passed to the neighbour owning the next one; a hit is shaded (ShadeTask::answer): its
// contribution goes to the pixel's processor in a result message and the rays it spawns start
// here.
//
// The load (L785-L797, L858): the host's records (broadcast_record.hpp) reach it on its
// broadcast port from its parent in a spanning tree of the array (row 0 from the west, every
// other processor from the north), each copied into a buffer of its memory; it passes each on
// to its children (broadcast_copy.hpp), keeps a polygon whose bounding box touches one of its
// subvolumes (the keep test, L787), and once the scene's attributes have come sorts what it kept
// into a list for each of its subvolumes (L858) and raises its ready flag. The polygons it
// tests, their materials and corner normals, the lights, the background and the view are read
// from its memory: it knows nothing else of the scene.
//
// Termination (the thesis gives no mechanism, L827): credit recovery. The host hands each
// processor a credit for each vision ray of its pixels; a message carries credit, a processor
// that spawns splits it among what it sends, and one that consumes a message (a result added,
// a ray destroyed) keeps the credit and, once it has been out of work for node.credit_quiet_time,
// sends what it holds one hop toward the detector (processor 0) in a credit message that crosses
// the link like any other. A processor that receives credit on its way adds it to its own, so
// credit flows to the detector along a combining tree, not as one message per return across the
// whole array (which made half the message hops and a hot column at 32x32). The frame is complete
// when the detector holds all the credit.
//
// How it is simulated (node.process): by default event-driven, run by the array's own event
// queue (modules/wake_queue.hpp: one SystemC process for all the processors, node.process =
// queue) or by SystemC as an SC_METHOD each (method); no stack of its own either way. An
// activation at simulated time t takes what is due by t and handles it all, its local time
// running ahead; it is activated again at its local time, or, idle, when its first message is due
// or its quiet time ends (a put of a message due sooner brings that forward, item_put). This is
// exact, not an approximation: every message is put before its stamp (a link takes time), so what
// is due by t is there at t, whichever processor due at t runs first. The thread (node.process =
// thread) waits wherever it spends time, the plain reading of the same steps;
// tests/ullner_array_test.cpp shows every statistic identical on all three.
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "firmware/accel/dda.hpp"
#include "firmware/accel/uniform_grid.hpp"
#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/kernels/ullner_quad_words.hpp"
#include "firmware/shading/camera.hpp"
#include "firmware/tasks/shade_task.hpp"
#include "firmware/tasks/vision_ray_task.hpp"
#include "modules/link.hpp"
#include "modules/memory.hpp"
#include "modules/mesh_topology.hpp"
#include "modules/message_channel.hpp"
#include "modules/processor.hpp"
#include "modules/ring_buffer.hpp"
#include "modules/ring_channel.hpp"
#include "modules/statistics.hpp"
#include "modules/wake_queue.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/machines/machine_trace.hpp"
#include "platform/machines/ullner_array/broadcast_copy.hpp"
#include "platform/machines/ullner_array/intersection_pipeline.hpp"
#include "platform/machines/ullner_array/message_fault.hpp"
#include "platform/machines/ullner_array/ray_message.hpp"
#include "platform/machines/ullner_array/record_cells.hpp"
#include "platform/machines/ullner_array/subvolume_mapping.hpp"

namespace rtsim::platform::ullner_array {

/// Words of memory each processor (by topology index) needs for the load: the lines it keeps
/// (the polygons listed in its subvolumes), the attributes, its subvolume lists, the view, and a
/// buffer for the record being received (`geometry`: the host's polygons; `attribute_words`,
/// `view_words`: those records' sizes). One pass over the subvolumes for the whole array.
std::vector<std::size_t> load_words_needed(const accel::UniformGrid& grid,
                                           const SubvolumeMapping& mapping,
                                           const modules::MeshTopology& topology,
                                           const functional::SceneGeometry& geometry,
                                           std::size_t attribute_words, std::size_t view_words);

/// The processor whose frame-buffer block holds pixel (x, y) of a width x height image (L781:
/// the block's place in the image is the processor's in the array).
modules::GridNode pixel_processor(int x, int y, int width, int height,
                                  const modules::MeshTopology& topology);

/// What every processor shares (read-only but for the frame buffer and the detector's count).
struct ArrayContext {
  const modules::MeshTopology* topology = nullptr;
  SubvolumeMapping mapping;
  /// The subdivision of the modelling space (its planes and divisions: what the DDA walks and
  /// the keep test compares with; the lists in it are the functional twin's, never read here).
  const accel::UniformGrid* grid = nullptr;
  /// The cells each broadcast record touches, worked out once a record for every processor.
  RecordCells* record_cells = nullptr;
  shading::ShadeParams shade;
  functional::FrameState* frame = nullptr;
  std::uint64_t credit_per_ray = 0;  ///< credit the host gives for each vision ray
  std::uint64_t total_credit = 0;
  /// The host has broadcast the view: every processor's load is timed by then.
  const sc_core::sc_event* loaded = nullptr;
  ReadyLine* ready = nullptr;
  /// On a ring, the medium the broadcast passes from processor to processor in ring order.
  const modules::TokenRing* ring_medium = nullptr;
  /// --fault nodeK.link_D:WORD:XOR: the messages its links corrupt (message_fault.hpp).
  std::vector<MessageFault>* message_faults = nullptr;
  /// The model's watchdog: a message that has crossed more links, with the messages of its ray
  /// tree before it, than any tree can need (a corrupted type or resume position can send one
  /// back and forth, or have a ray shaded again and again, for ever) is destroyed, its credit
  /// kept where it ends.
  std::uint32_t hop_limit = 0;
  /// A fault for tests: the result message with this sequence number (counted where results
  /// are added) is lost; 0 loses none.
  std::uint64_t drop_result = 0;
  /// array.interconnect = ring: one token ring instead of the mesh links; a message goes from
  /// its sender straight to its destination (no processor on the way copies it). Null: mesh.
  modules::RingChannel<RayMessage>* ring = nullptr;
  /// --latency-probe: a ray's journey from its creation to its contribution being added, by
  /// class of stage (every node alike): the processor, its intersection unit, the links (or
  /// the ring) and the input queues.
  modules::LatencyProbe* probe = nullptr;
  /// node.process = queue: the array's own event queue, which runs every processor.
  modules::WakeQueue* queue = nullptr;
  struct ProbeStages {
    int node = -1, pipeline = -1, link = -1, ring = -1, in = -1;
  } stages;
};

/// The input port of the ring (in[kRingPort]), after the four mesh ports.
inline constexpr int kRingPort = 4;

/// What the whole array counts (the detector's view and the dropped result).
struct ArrayTally {
  std::uint64_t credit_returned = 0;
  std::optional<sc_core::sc_time> done;        ///< when the detector held all the credit
  sc_core::sc_event frame_done{"frame_done"};  ///< notified then (the readout starts)
  std::uint64_t results_added = 0;
  std::uint64_t results_dropped = 0;
  std::uint64_t credit_exhausted = 0;  ///< messages whose credit could not be shared out
  std::uint64_t credit_carried = 0;    ///< times held credit rode on another message
  std::uint64_t looping = 0;           ///< messages the watchdog destroyed (hop_limit)
  std::uint64_t messages_made = 0;     ///< the last message's id (RayMessage::id)
  std::uint64_t rays_made = 0;         ///< the last vision ray's number (RayMessage::ray)
  modules::LatencyRecorder latency;    ///< a ray's creation to its contribution being added
};

class ArrayNode : public modules::Processor,
                  private modules::PutListener,
                  private modules::WakeQueue::Client {
 private:
  // What a step of the frame and a record of the load read of the processor itself, declared
  // first so that they share a few cache lines: a 32 x 32 array's 1024 processors take turns,
  // and each turn finds its processor's state out of the cache (the rest of the object is
  // kilobytes of sockets, modules and the scene's copy).
  struct Timing {
    std::uint64_t message, route, subvolume, shade, spawn, result, new_ray, keep_test, sort;
    sc_core::sc_time memory_cycle;  ///< one 16-bit transfer (L835, L891)
    double cpu_memory_share;        ///< of its computing time, its bus cycles' hold on the memory
    PipelineTiming pipeline;        ///< its intersection unit's (Fig. 2-28)
    sc_core::sc_time credit_quiet;  ///< idle this long before credit goes on (node.*)
    bool credit_carried;            ///< held credit also rides on messages toward the detector
  };
  /// The stamp (ticks) of the oldest message in each port, kNoMessage if none: which port's
  /// message came first is read here, not from five queues each step (in[] order).
  static constexpr std::uint64_t kNoMessage = ~std::uint64_t{0};
  std::array<std::uint64_t, 5> front_{kNoMessage, kNoMessage, kNoMessage, kNoMessage, kNoMessage};
  /// node.process = queue: its number in ctx_.queue.
  std::size_t queue_slot_ = 0;
  sc_core::sc_time memory_free_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time cycle_;
  std::uint64_t credit_held_ = 0;
  std::optional<sc_core::sc_time> quiet_since_;  ///< out of work since, if it is
  bool idle_ = false;
  bool ports_ = false;           ///< whether it has any port
  bool waits_on_ports_ = false;  ///< node.process = thread: it waits on any_ (else it is woken)
  bool started_ = false;
  int next_row_ = 0;  ///< of its block, the next to make vision rays for
  const ArrayContext& ctx_;
  ArrayTally& tally_;
  modules::GridNode position_;
  std::array<const ArrayNode*, 4> neighbour_{};  ///< the processor each link leads to (mesh)
  /// The load's state: where the next record goes, when its buffer is free, the CPU's time.
  std::uint64_t next_free_ = 0;
  sc_core::sc_time buffer_free_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time load_cpu_free_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time frame_ready_ = sc_core::SC_ZERO_TIME;
  Timing timing_;

 public:
  /// The input port from the neighbour in each direction (absent at an unconnected edge, and
  /// all four on a ring), and the ring's (in[kRingPort], on a ring only).
  std::array<std::unique_ptr<modules::MessageQueue<RayMessage>>, 5> in;
  /// Its memory (L835: 128 KB): the polygon lines it kept, the scene's attributes, its
  /// subvolume lists and the view, in the order they came.
  modules::Memory memory;
  /// The host's broadcast, from its parent (or the host).
  tlm_utils::simple_target_socket<ArrayNode> broadcast_in;
  /// Its block of the frame buffer (L781): kPixelWords words a pixel, its rows in order. A region
  /// of its memory in the thesis; apart here so that a large image does not count against the
  /// polygons' 128 KB (its accesses are charged to the memory's time all the same).
  modules::Memory frame_buffer;
  /// Words of a pixel: the three channels' fixed-point sums (PixelAccumulator), two words each.
  static constexpr unsigned kPixelWords = 6;
  /// The pixels of its block: image rows [first_row, end_row) x columns [first_col, end_col).
  struct Block {
    int first_row = 0, end_row = 0, first_col = 0, end_col = 0;
    bool holds(int x, int y) const {
      return y >= first_row && y < end_row && x >= first_col && x < end_col;
    }
    std::size_t offset(int x, int y) const {
      return (static_cast<std::size_t>(y - first_row) *
                  static_cast<std::size_t>(end_col - first_col) +
              static_cast<std::size_t>(x - first_col)) *
             kPixelWords;
    }
  };
  const Block& block() const { return block_; }

  /// node.process: how the simulator runs it ("queue", "method", "thread").
  static std::string process_kind(const params::ParamRegistry& registry);
  /// The class name its parameters are declared and read under: all processors alike.
  static constexpr const char* kClass = "node";
  /// Parameters of every processor, under kClass.
  static void declare_params(const modules::ParamDecls& node);
  /// Words of a processor's memory, and the parameter's full name (for a message).
  static std::size_t memory_words(const params::ParamRegistry& registry);
  static std::string memory_words_name(const params::ParamRegistry& registry);

  SC_HAS_PROCESS(ArrayNode);
  ArrayNode(sc_core::sc_module_name name, const params::ParamRegistry& registry,
            const ArrayContext& context, ArrayTally& tally, modules::GridNode position,
            MachineTrace& trace);
  /// Its ports go first, newest first, then its memories: the reverse of the order they were
  /// made in, so that SystemC finds each where modules/removal_order.hpp leaves it, at the front.
  ~ArrayNode() override;

  /// Wires this processor's output in direction `d` to `neighbour`'s input from the opposite
  /// side (elaboration).
  void connect(modules::Direction d, ArrayNode& neighbour);
  /// Prefetches what a message put into its port from `from` touches (send()'s hint).
  void prepare_receive(modules::Direction from) const;
  /// Its children in the broadcast's spanning tree (the host feeds processor (0, 0)): on the
  /// mesh, row 0 passes east and every processor south; on a ring, each to its successor.
  std::vector<modules::GridNode> broadcast_children() const;
  /// Binds its port to child k of broadcast_children() (elaboration).
  void connect_broadcast(std::size_t k, ArrayNode& child);

  modules::GridNode position() const { return position_; }
  std::size_t polygons() const { return line_at_.size(); }
  /// When it had handled the last record of the load (the view): its frame starts then.
  const sc_core::sc_time& frame_ready() const { return frame_ready_; }

 private:
  /// Its intersection unit's statistics ("node0.pipeline"): busy while it fetches or issues.
  struct PipelineStats : modules::StatGroup {
    using modules::StatGroup::StatGroup;
    modules::Busy busy{*this, "time fetching polygons or issuing tests (its utilisation)"};
    modules::Counter words_fetched{*this, "words_fetched", "polygon words fetched from memory",
                                   modules::StatUnit::words};
    modules::Counter words_wasted{*this, "words_wasted",
                                  "u and v words fetched for polygons that passed stage 3 on a "
                                  "bound a closer hit still in the pipe was about to tighten "
                                  "(L847)",
                                  modules::StatUnit::words};
  };
  /// A child in the broadcast's tree: the socket to its broadcast port and the link to it (none
  /// on a ring: the segment to the successor), and when that is free. The load's use of a link
  /// is counted here (load_link_busy_s), not in the link's own statistics, which are the
  /// frame's.
  struct BroadcastHop {
    modules::GridNode child;
    std::unique_ptr<tlm_utils::simple_initiator_socket<ArrayNode>> socket;
    const modules::Link* link = nullptr;
    sc_core::sc_time free = sc_core::SC_ZERO_TIME;
  };
  /// What a processor does after one step of its loop (step()).
  struct Step {
    enum class Kind {
      kAgain,     ///< it handled something: on at its local time
      kIdle,      ///< nothing to do until `until` (if any) or a message arrives
      kFinished,  ///< it has no ports and no work: nothing will ever come
    } kind = Kind::kAgain;
    std::optional<sc_core::sc_time> until;
  };
  /// node.process = thread: a SystemC thread that waits wherever it spends time (the reference).
  void run();
  /// node.process = method: the same steps as an SC_METHOD, each activation handling what is
  /// due at its time and computing ahead, triggered again at its local time or by what it
  /// idles for.
  void activate();
  /// node.process = queue: the array's queue runs it (an activation).
  void woken() override { activate(); }
  /// node.process = queue: prefetches what its next activation reads first (its state, the
  /// port whose message came first and that message), while the processor before it runs.
  void prepare() const override;
  /// The frame starts (the host has broadcast the view): its camera, its ports' events.
  void start_frame();
  /// One step of its loop at its local time, which is simulated time: takes and handles the
  /// next message, or sends its credit on, or says what it waits for. Never waits itself.
  Step step();
  /// broadcast_in: a record offered by the parent (broadcast_copy.hpp).
  void receive_record(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  /// The CPU's work on the record at word `at` of its memory, there since `arrived`.
  void handle_record(std::uint64_t at, std::size_t words, const sc_core::sc_time& arrived);
  /// Copies `record` to a child, the CPU having started it at `ready`.
  void pass_on(BroadcastHop& hop, std::span<const std::uint32_t> record,
               const sc_core::sc_time& ready);
  /// The keep test (L787): whether the polygon record's bounds touch one of its subvolumes;
  /// those it touches get its line number (`line`) in their pending lists.
  bool keep(std::span<const std::uint32_t> record, std::uint32_t line);
  /// The sort (L858): its subvolume lists written to its memory from `t`; returns when done.
  sc_core::sc_time sort(sc_core::sc_time t);
  /// The candidates its memory lists for subvolume `c` (line numbers; empty if none).
  std::span<const std::uint32_t> candidates(const accel::CellIndex& c) const;
  /// A message was put into one of its ports, to be there at `stamp`: noted as its port's first if
  /// the port was empty, and an idle event-driven processor wakes then if that is sooner than it
  /// would have.
  void item_put(int port, const sc_core::sc_time& stamp) override;
  /// Takes the next message: an arrived one, then this processor's own, then a new vision ray.
  bool next_message(RayMessage& msg);
  void process(RayMessage&& msg);
  void search(RayMessage& msg);
  /// Sends `msg` one hop toward `to` on the mesh, or on the ring straight to `to`.
  void forward(RayMessage&& msg, const modules::GridNode& to);
  void send(RayMessage&& msg, modules::Direction d);
  /// Books its memory for `d` from when it is free (its unit's fetches, a port's copy out, a
  /// frame-buffer update: first come, first served in its own order of time); returns the start.
  sc_core::sc_time book_memory(const sc_core::sc_time& d);
  /// The port copies the message out of this memory: when it may start, and the memory's time.
  sc_core::sc_time copy_out();
  /// The port copied a message that `arrived` into this memory: its memory time, and the CPU's
  /// wait if the memory was busy.
  void receive_copy(const sc_core::sc_time& arrived);
  /// The hit on line `line` with its surface details `s`, completed from its memory.
  void surface(std::uint32_t line, const SurfaceHit& s, Hit& hit) const;
  void answer(const RayMessage& msg, bool found, const Hit& hit);
  void add_result(const RayMessage& msg);
  /// Adds `c` into its block of the frame buffer at `pixel`.
  void accumulate(std::uint32_t pixel, const Color& c);
  static Block block_of(const ArrayContext& ctx, const modules::GridNode& at);
  static std::size_t block_words(const ArrayContext& ctx, const modules::GridNode& at);
  void return_credit(std::uint64_t credit);
  /// --latency-probe: the time of `msg`'s journey since its cursor, up to `t`, was `part` at
  /// `stage` (a message followed by no journey costs a comparison).
  void probe_to(RayMessage& msg, int stage, modules::LatencyPart part, const sc_core::sc_time& t) {
    if (msg.journey != modules::LatencyProbe::kNoJourney) account(msg, stage, part, t);
  }
  void account(RayMessage& msg, int stage, modules::LatencyPart part, const sc_core::sc_time& t);
  void spend(std::uint64_t cycles, std::string_view what);
  modules::GridNode pixel_owner(std::uint32_t pixel) const;
  const std::vector<kernels::UllnerQuadParams<double>>& held();

  /// What its memory says of the scene: lights, materials, background, view.
  scenes::Scene local_;
  std::optional<shading::PinholeCamera> camera_;
  tasks::ShadeTask shade_;
  accel::Dda dda_;
  std::array<std::unique_ptr<tlm_utils::simple_initiator_socket<ArrayNode>>, 4> out_;
  std::array<std::unique_ptr<modules::Link>, 4> links_;
  std::array<std::vector<MessageFault*>, 4> link_faults_;  ///< what each link corrupts
  tlm_utils::simple_initiator_socket<ArrayNode> memory_port_;
  std::vector<BroadcastHop> broadcast_out_;
  std::vector<std::uint32_t> line_at_;  ///< line number -> word address of its header
  /// Line numbers kept for each of its subvolumes (by the grid's linear index), until the sort.
  std::unordered_map<std::size_t, std::vector<std::uint32_t>> pending_;
  /// Word address of each subvolume's list (its count, then line numbers), by the grid's
  /// linear index, ascending (a processor has a few dozen: a binary search is the fastest way).
  std::vector<std::pair<std::size_t, std::uint64_t>> list_at_;
  std::vector<kernels::UllnerQuadParams<double>> decoded_;
  std::uint64_t decoded_after_ = ~std::uint64_t{0};
  modules::RingBuffer<RayMessage> own_;  ///< rays spawned here, not yet searched
  Block block_;  ///< its pixels: the vision rays it makes, the results it adds
  tlm_utils::simple_initiator_socket<ArrayNode> frame_buffer_port_;
  std::unique_ptr<tasks::VisionRayTask> vision_;
  /// Its ports' arrivals, the events it idles on: one list for the whole frame (a list made for
  /// each wait allocates); ports_ says whether it has any.
  sc_core::sc_event_or_list any_;
  /// The port whose oldest message came first (the lowest in in[] order on a tie); its front_
  /// is kNoMessage if no port holds one.
  std::size_t first_port() const {
    return static_cast<std::size_t>(std::min_element(front_.begin(), front_.end()) -
                                    front_.begin());
  }
  /// node.process = method: it idles on this alone, notified for when it must look again (the
  /// first message due, the end of its quiet time); a put notifies it only if sooner.
  sc_core::sc_event wake_{"wake"};
  std::vector<shading::TracedRay> spawned_;
  std::vector<PipelineTest> stream_;  ///< a search's tests, for its unit's timing

  PipelineStats pipeline_;
  /// Messages through the output link in each direction, by type: in the link's group.
  std::array<std::unique_ptr<modules::CounterArray>, 4> sent_by_link_;
  modules::CounterArray received_{*this, "received_", message_type_names(),
                                  "messages taken, by type"};
  modules::CounterArray sent_{*this, "sent_", message_type_names(), "messages sent, by type"};
  modules::Computed polygons_{*this, "polygons", modules::StatUnit::count,
                              "polygons its memory holds", [this] { return line_at_.size(); }};
  modules::Counter records_{*this, "load_records", "broadcast records received"};
  modules::Counter records_dropped_{*this, "load_records_dropped",
                                    "broadcast records (or its lists) its memory had no room for "
                                    "(only under a fault)"};
  modules::Duration load_busy_{*this, "load_busy_s",
                               "CPU time handling the broadcast: passing records on, keep tests, "
                               "the sort"};
  modules::Duration load_link_busy_{*this, "load_link_busy_s",
                                    "time its links (or its ring segment) carried broadcast "
                                    "records to its children"};
  modules::Duration load_memory_busy_{*this, "load_memory_busy_s",
                                      "time its memory took broadcast records in, copied them "
                                      "out, or took the subvolume lists"};
  modules::Computed ready_{*this, "frame_ready_s", modules::StatUnit::seconds,
                           "when it had handled the view (its load's end, its frame's start)",
                           [this] { return frame_ready_.to_seconds(); }};
  modules::Counter subvolumes_{*this, "subvolumes_searched", "subvolumes searched"};
  modules::Counter entered_{*this, "vision_rays_entered",
                            "new rays that reached the subvolume they first strike here and "
                            "became vision rays (where the eye's rays enter the array, Figs. "
                            "2-29, 2-30)"};
  modules::Counter tests_{*this, "intersections", "ray/polygon tests of its unit"};
  modules::Duration memory_busy_{*this, "memory_busy_s",
                                 "time its memory was fetching polygons, copying messages or "
                                 "serving its CPU"};
  modules::Duration cpu_memory_busy_{
      *this, "cpu_memory_busy_s", "time its CPU's bus cycles held the memory (in memory_busy_s)"};
  modules::Duration memory_waited_{*this, "memory_waited_s",
                                   "time its CPU, its intersection unit or a port copy waited "
                                   "for the memory, busy with another of them"};
  modules::Peak backlog_peak_{*this, "backlog_peak", "rays spawned here waiting to be searched"};
};

}  // namespace rtsim::platform::ullner_array
