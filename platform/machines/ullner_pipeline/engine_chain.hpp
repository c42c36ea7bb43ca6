#pragma once
// The ray-tracing pipeline proper (seed 000 §2.4, Fig. 2-23): N polygon processors in a chain,
// each holding one polygon, joined by bit-serial links (13 wires each way plus handshake,
// L729-L731); the host drives the unused input at one end and reads the unused output at the
// other.
//
// Two ways to simulate the processors (pipeline.model), with the same times for every ray:
//  * chain: the processors are identical, so the chain steps each description through every
//    processor's test in order (each intersects the description it received with the polygon in
//    its registers and passes on the one it wrote, L702-L713) and when it enters and leaves is
//    arithmetic (ChainTiming, stalls included). Memory grows by a register line and two counters
//    a processor. The load writes each description where it comes to rest.
//  * engines: every processor is a PolygonEngine module; the description travels from one to the
//    next as a transaction and each times itself (polygon_engine.hpp); the load is a wave of
//    transactions through them.
// Both time descriptions lazily, as far as the one ahead allows, and a description leaves when
// the host has freed a slot of its result queue (host.result_slots): a slow host's end holds the
// chain up.
// Wall time grows by one intersection a processor a ray either way (which the hardware does).
//
// What the host reads is the description that came out of the last processor: its identity
// field names the polygon (dummies' identities are ignored, L719) and its t and (u, v) the point;
// the host shades with its own copy of that polygon (its normal and corner normals, L452-L456).
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <systemc>
#include <vector>

#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/tasks/polygon_processor_task.hpp"
#include "firmware/trace_counters.hpp"
#include "modules/latency_probe.hpp"
#include "modules/link.hpp"
#include "modules/local_clock.hpp"
#include "modules/memory.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/ullner_peripheral/messages.hpp"
#include "platform/machines/ullner_pipeline/chain_timing.hpp"
#include "platform/machines/ullner_pipeline/polygon_engine.hpp"
#include "platform/machines/ullner_pipeline/polygon_load.hpp"

namespace rtsim::platform::ullner_pipeline {

class EngineChain : public sc_core::sc_module, private RegisterFile {
 public:
  /// The first processor's input register: one description (the host is held until it is free).
  modules::MessageQueue<ullner::RayRequest> input;
  /// Polygon descriptions presented by the host (a PolygonLoad on each write).
  tlm_utils::simple_target_socket<EngineChain> load;
  /// The processors' polygon registers: processor k's description at line k
  /// (PolygonDescription::kWords words). A --fault on a word corrupts that processor's polygon
  /// as it is shifted in.
  modules::Memory registers;
  tlm_utils::simple_initiator_socket<EngineChain> result_out;  ///< to the host's result queue

  /// Its parameters under `pipeline`: the number of processors, a processor's timing
  /// (`engine.*`) and the links' (`link.*`).
  static void declare_params(const modules::ParamDecls& pipeline);

  SC_HAS_PROCESS(EngineChain);
  /// Processors in a chain with parameters `pipeline`, and that parameter's full name.
  static std::size_t engines(const modules::ModuleParams& pipeline);
  static std::string engines_name(const modules::ModuleParams& pipeline);

  /// The twin's geometry in `run` is the host's copy of the scene (all of it is loaded; the
  /// host reads hits on them with it).
  EngineChain(sc_core::sc_module_name name, MachineRun& run);

  std::uint64_t engines() const { return timing_.engines(); }
  /// Faults in flight (description_fault.hpp), before the simulation: applied by either model
  /// where the description enters their processor.
  void set_faults(std::vector<DescriptionFault> faults);
  const std::vector<DescriptionFault>& faults() const { return faults_; }
  /// pipeline.model = engines: processor k's module (fill and drain along the chain); empty in
  /// chain mode.
  const std::vector<std::unique_ptr<PolygonEngine>>& engine_modules() const {
    return engine_modules_;
  }
  /// pipeline.model = engines: processors sampled evenly along the chain (the first and the
  /// last among them), and when each was busy; empty in chain mode.
  const std::vector<std::uint64_t>& watched() const { return watched_; }
  const std::vector<modules::BusyTimeline>& watched_busy() const { return watched_busy_; }
  const ChainTiming& timing() const { return timing_; }
  /// The host's result queue, whose slots are the far end's registers (before simulating).
  void set_result_queue(const modules::TimedFifo<ullner::RayResult>& results) {
    far_end_.results = &results;
  }
  /// Whether the host kept the pipe full (L743): descriptions the first processor accepted as
  /// soon as it could (the next one was waiting in its register), the time it stood ready with
  /// its register empty, the time one waited there while the chain ahead was full, and the time
  /// the last processor held answers ready for want of a result slot.
  std::uint64_t kept_full() const { return kept_full_; }
  sc_core::sc_time host_starved() const { return host_starved_; }
  sc_core::sc_time chain_held() const { return chain_held_; }
  sc_core::sc_time far_end_held() const;
  /// Busy time of each processor: one issue interval a description.
  sc_core::sc_time engine_busy() const { return engine_busy_.total(); }
  /// Per processor: descriptions it overwrote, and answers it gave (the description left the
  /// chain naming it).
  const std::vector<std::uint64_t>& overwrites() const { return overwrites_; }
  const std::vector<std::uint64_t>& answers() const { return answers_; }
  /// The time a polygon description takes over a link (the load).
  sc_core::sc_time polygon_time() const { return polygon_time_; }
  /// Sum over descriptions of the time from the first processor accepting it to its answer
  /// leaving the last one.
  sc_core::sc_time transit_total() const { return transit_total_; }

 private:
  /// A description in the chain: accepted by the first processor, not yet left the last.
  struct InChain {
    ullner::RayRequest request;
    DescriptionInFlight msg;
    sc_core::sc_time accepted;
    // pipeline.model = engines: the processor that accepted it last and whether it has started
    // passing it on; the transaction that carries it.
    std::uint64_t at = 0;
    bool started = false;
    modules::MessageExtension<DescriptionInFlight> ext{nullptr, tasks::RayDescription::kWireBits};
    tlm::tlm_generic_payload gp;
    InChain() = default;
    InChain(const InChain&) = delete;
    InChain& operator=(const InChain&) = delete;
    /// The payload would free an extension still set on it: ext is a member, not its own.
    ~InChain() {
      if (gp.get_extension<modules::MessageExtension<DescriptionInFlight>>())
        gp.clear_extension(&ext);
    }
  };
  /// The far end's registers: a slot of the host's result queue for description j once the
  /// host has taken the answer a queue's length before it.
  struct ResultSlots final : FarEnd {
    const modules::TimedFifo<ullner::RayResult>* results = nullptr;
    std::optional<sc_core::sc_time> slot_free(std::uint64_t j) const override;
  };

  void run();
  /// pipeline.model = engines: the processors as modules, bound in a chain.
  void build_engines();
  /// The first processor can take the next description (it knows when it passed on the last).
  bool can_accept() const;
  /// The first processor takes the description waiting in its input register.
  void accept_next();
  /// Moves every description on as far as the ones ahead and the far end allow, and delivers
  /// the answers of those that leave, in order.
  void advance();
  /// pipeline.model = engines: moves in_chain_[i] on; false when it cannot move.
  bool move(std::size_t i);
  /// The oldest description leaves the last processor, its link starting at `start`.
  void leave(const sc_core::sc_time& start);
  /// pipeline.model = chain: the description through every processor's data, in order.
  void through_processors(DescriptionInFlight& msg);
  /// What the last processor passes on (a description, or during the load its previous polygon)
  /// reaches the host's end; the chain reads it from the payload's extension.
  void at_host_end(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  void load_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);
  /// A processor's registers, line `line` of `registers`: written through the load port (its
  /// faults apply), what they held given back.
  void exchange(std::uint64_t line, PolygonDescription& words) override;
  /// The processors' polygons as their registers hold them (decoded again after any write).
  const std::vector<kernels::UllnerQuadParams<double>>& polygons();
  ullner::RayResult read_answer(const ullner::RayRequest& req, const tasks::RayDescription& d);

  tlm_utils::simple_initiator_socket<EngineChain> registers_port_;  ///< the load's writes
  tlm::tlm_generic_payload register_write_;  ///< reused: a load writes N^2 lines
  const functional::SceneGeometry& geometry_;
  std::uint64_t polygons_;
  TraceCounters& counters_;
  modules::LatencyProbe& probe_;
  int probe_input_ = -1, probe_engines_ = -1, probe_link_out_ = -1;
  modules::Link inner_link_;
  modules::Link link_out_;
  ChainTiming timing_;
  sc_core::sc_time polygon_time_;
  modules::LocalClock clock_;  ///< the first processor's time
  std::vector<kernels::UllnerQuadParams<double>> decoded_;
  std::vector<std::uint32_t> identities_;  ///< each processor's identity word, as decoded_
  std::uint64_t decoded_after_ = ~std::uint64_t{0};  ///< registers' words_written() then
  std::vector<std::uint64_t> overwrites_, answers_;
  std::vector<DescriptionFault> faults_;  ///< by processor
  /// pipeline.fault.dead_engine: the processor that passes every description unchanged (-1: none).
  std::int64_t dead_engine_ = -1;
  sc_core::sc_time transit_total_ = sc_core::SC_ZERO_TIME;
  std::deque<InChain> in_chain_;
  std::uint64_t entered_ = 0;  ///< descriptions accepted by the first processor
  ResultSlots far_end_;
  std::uint64_t kept_full_ = 0;
  sc_core::sc_time last_entered_ =
      sc_core::SC_ZERO_TIME;  ///< the first processor's last acceptance
  sc_core::sc_time host_starved_ = sc_core::SC_ZERO_TIME, chain_held_ = sc_core::SC_ZERO_TIME;

  // "pipeline.engine": the class of processors. Every processor is busy one issue interval per
  // description, so the class's figures are each processor's; the busy signal is the first
  // processor's issue slots (every processor's, shifted along the chain).
  modules::StatGroup engine_class_;
  modules::Busy engine_busy_{engine_class_, "each processor's issue slots (its utilisation)"};
  modules::Counter descriptions_{engine_class_, "descriptions",
                                 "descriptions every processor passed"};
  modules::Counter loaded_{engine_class_, "load_descriptions",
                           "polygon descriptions shifted in before the frame"};
  modules::Computed engine_count_{engine_class_, "engines", modules::StatUnit::count,
                                  "processors in the chain", [this] { return engines(); }};
  modules::Computed overwrites_sum_{engine_class_, "overwrites", modules::StatUnit::count,
                                    "descriptions a processor overwrote, over all processors",
                                    [this] { return sum(overwrites_, engines()); }};
  modules::Computed answers_sum_{engine_class_, "answers", modules::StatUnit::count,
                                 "answers a processor holding a polygon gave, over all of them",
                                 [this] { return sum(answers_, polygons_); }};
  modules::Computed dummies_{engine_class_, "dummies", modules::StatUnit::count,
                             "processors holding no polygon",
                             [this] { return engines() - polygons_; }};
  // The first inner link's group also counts the N-1 links that carry what it carries, each one
  // hop later.
  modules::Computed links_{inner_link_, "links", modules::StatUnit::count,
                           "inner links in the chain", [this] { return engines() - 1; }};
  modules::Computed bits_all_links_{inner_link_, "bits_all_links", modules::StatUnit::bits,
                                    "bits over all inner links",
                                    [this] { return inner_link_.bits() * (engines() - 1); }};
  static std::uint64_t sum(const std::vector<std::uint64_t>& v, std::uint64_t first_n);

  // pipeline.model = engines: the processors, and the chain's sockets at the host's end (into
  // the first one's register) and at the far end (what leaves the last one, and when).
  std::vector<std::unique_ptr<PolygonEngine>> engine_modules_;
  std::unique_ptr<tlm_utils::simple_initiator_socket<EngineChain>> to_first_;
  std::unique_ptr<tlm_utils::simple_target_socket<EngineChain>> far_end_socket_;
  // The load's wave: into the first processor's registers, and back to the host from the last.
  std::unique_ptr<tlm_utils::simple_initiator_socket<EngineChain>> to_first_load_;
  std::unique_ptr<tlm_utils::simple_target_socket<EngineChain>> load_back_;
  std::vector<std::uint64_t> watched_;
  std::vector<modules::BusyTimeline> watched_busy_;
};

}  // namespace rtsim::platform::ullner_pipeline
