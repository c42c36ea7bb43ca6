#pragma once
// Gaudet's Broadcast Processor and its bus (seed 001 §5.1-5.3, L814-L895): a processor with its
// own memory module holding one data set — first the ID list ({ID, address, size} per packet),
// then the packets in successive locations (Fig. 5-5, L877-L879) — cycling for ever through the
// ID list and broadcasting on a 32-bit bus with a sync strobe and a wired-OR hit line.
//
// The Fig. 5-6 loop (L893), with the simulator's timings (L957-L962):
//   loop0: point at the start of the ID list
//   loop1: broadcast the next ID (sync strobe), wait for the comparators, fetch the packet's
//          address and size                                       -> id_slot (1000 ns)
//          if the hit line is low, skip the packet (adaptive broadcasting, §5.1.2)
//          start the streamed read                                 -> packet_overhead (800 ns)
//   loop2: broadcast the packet word by word                       -> word_time (400 ns) a word
//   check: at the end of the ID list reset the loop                -> loop_reset (400 ns)
// Non-adaptive broadcasting sends every packet every cycle, hit or not (L837, L1047).
//
// The broadcast order is the order of the ID list in memory, which the control processor lays
// out (breadth-first, depth-first or random, Fig. 6-11).
//
// Events only where order matters (DESIGN.md): the loop runs arithmetically through IDs that no
// Bus Interface Controller holds, and the loop wakes only at the strobe of an ID some BIC
// asked for. It plans that strobe as it strobes the one before (from the end of the packet it
// sends), and a request whose slot comes sooner moves its alarm instead of waking it to plan
// again; a freed buffer wakes it only while every strobe misses for want of one. The bus is
// cycling all the time all the same: its statistics count every ID and packet the loop went
// through, to the frame's end (run_to). tests/gaudet_sync_test.cpp holds the plans to a loop
// that woke at every request and every packet's end.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <systemc>
#include <unordered_map>
#include <vector>

#include "modules/memory.hpp"
#include "modules/module_params.hpp"
#include "modules/resumable.hpp"
#include "modules/resumable_process.hpp"
#include "modules/statistics.hpp"
#include "modules/wake_queue.hpp"
#include "platform/machines/gaudet_pert/bus_interface.hpp"

namespace rtsim::platform::gaudet {

/// The loop's timings, read from the bus's parameters (declare_params).
struct BroadcastTiming {
  sc_core::sc_time id_slot, packet_overhead, word_time, loop_reset;
};

/// The statistics group of its name: busy while the bus carries packet words (its utilisation),
/// ids, cycles, packets, packet_words, hit_packets, captures.
class BroadcastProcessor : public sc_core::sc_module,
                           public modules::StatGroup,
                           private modules::WakeQueue::Client {
 public:
  /// The data set's memory module; the control processor loads it through memory.socket.
  modules::Memory memory;

  /// Its parameters, under `bus` ("broadcast": every bus; "shell_bus": one): the timings of
  /// the loop (L957-L962), and when its loop wakes (a simulator setting).
  static void declare_params(const modules::ParamDecls& bus);

  SC_HAS_PROCESS(BroadcastProcessor);
  /// `params`: its own (ModuleParams under its name); `load_word_time` the control processor's
  /// download rate into its memory. Its loop is a program (modules/resumable.hpp) that an
  /// SC_METHOD of its own runs, or, `on_queue`, the machine's event queue (join), with the PERT
  /// processors' programs.
  BroadcastProcessor(sc_core::sc_module_name name, const modules::ModuleParams& params,
                     std::size_t memory_words, sc_core::sc_time load_word_time, bool adaptive,
                     bool on_queue);
  /// Elaboration (made `on_queue`): its loop runs on `queue`, which starts it at the frame's
  /// start.
  void join(modules::WakeQueue& queue);

  /// Elaboration: a BIC listening on this bus.
  void attach(BusInterface& bic);

  /// Starts the loop at `t` (absolute) on the ID list the control processor loaded: `ids`
  /// entries of `entry_words` words from address 0.
  void start(const sc_core::sc_time& t, std::size_t ids, std::uint32_t entry_words);

  /// At the frame's end (`end`, now): the loop's counts (IDs, cycles, a sleeping BIC's missed
  /// strobes) run on to it from wherever the loop last woke. The bus cycles all the time;
  /// without this its counts would stop at its last wake, a time that depends on how it plans,
  /// not on the machine.
  void run_to(const sc_core::sc_time& end);

  /// Minimum cycle time (nothing sent): mct of L1068-L1079.
  sc_core::sc_time minimum_cycle() const;

  struct Stats {
    std::uint64_t ids = 0;             ///< IDs broadcast
    std::uint64_t cycles = 0;          ///< completed passes through the ID list
    std::uint64_t packets = 0;         ///< packets broadcast
    std::uint64_t packet_words = 0;    ///< their words
    std::uint64_t hit_packets = 0;     ///< packets some BIC captured
    std::uint64_t captures = 0;        ///< packets captured, summed over BICs
    sc_core::sc_time packet_time;      ///< time spent sending packets (overhead + words)
    sc_core::sc_time hit_packet_time;  ///< of which packets some BIC captured
  };
  Stats stats() const {
    return {ids_.value(),         cycles_.value(),   packets_.value(), packet_words_.value(),
            hit_packets_.value(), captures_.value(), busy_.total(),    hit_packet_time_.value()};
  }
  /// Called for every packet some BIC captures (traces): id, start, duration, captures.
  std::function<void(std::uint32_t, sc_core::sc_time, sc_core::sc_time, std::size_t)> on_packet;

  /// Called by the BICs.
  void demand(std::uint32_t id, int delta);
  /// A BIC's request for `id` was withdrawn at `t`: a strobe up to then still matches it
  /// (bus_interface.hpp), so the loop plans for it until then, though it left the demand.
  void withdrawn(std::uint32_t id, const sc_core::sc_time& t);
  /// A BIC's register holds `id` from `t`: if its slot's strobe comes before the one the loop
  /// sleeps for, the loop's alarm moves to it (at once while every strobe misses).
  void requested(std::uint32_t id, const sc_core::sc_time& t);
  /// The BIC at `place` (in the order attached) put `id` in a register (holders_).
  void held(std::uint32_t id, std::uint32_t place);
  /// A BIC freed a buffer: the loop wakes only from a sleep through missed strobes, the one
  /// plan a free buffer can change (which slots are wanted depends on the registers alone).
  void buffer_freed() {
    if (sleep_ == Sleep::kAnyChange || (wake_at_every_change_ && sleep_ != Sleep::kBusy))
      ring_at(modules::sim_now());
  }

 private:
  struct Slot {
    std::uint32_t id = 0;
    std::uint32_t words = 0;
    std::uint32_t address = 0;  ///< of the packet's first word in memory
  };
  struct Cursor {
    std::size_t pos = 0;
    sc_core::sc_time t = sc_core::SC_ZERO_TIME;  ///< when slot `pos` starts
  };
  /// Its SC_METHOD (not on the queue): resumes the loop where it waits.
  void run();
  /// The queue's activation (on the queue).
  void woken() override;
  /// The loop (what its thread did).
  modules::Resumable program();
  /// What the loop sleeps for, so that a BIC's change wakes it only when it could change the
  /// plan (each wake is a thread switch and a new plan; most requests are for slots after the
  /// one it sleeps for, and most freed buffers change nothing it planned).
  enum class Sleep {
    kBusy,       ///< not on alarm_: a slot no BIC caught, or not started (it plans after)
    kUntil,      ///< until planned_ (a strobe, or a look again): a sooner strobe moves it
    kAnyChange,  ///< through missed strobes: a request or a freed buffer may turn one to a hit
  };
  /// Sleeps until `until` (none: for ever) or until the alarm is moved sooner, as `why`; then
  /// sleep_ is kBusy again.
  modules::Resumable sleep(std::optional<sc_core::sc_time> until, Sleep why);
  /// Sets the alarm the sleeping loop wakes at to `t` (now or later).
  void ring_at(const sc_core::sc_time& t);
  /// The first strobe of `key`'s slots after `t` (its register valid from t), the loop going on
  /// from the cursor without sending (the slots' starts repeat every idle cycle).
  sc_core::sc_time first_strobe_after(std::uint32_t key, const sc_core::sc_time& t) const;
  sc_core::sc_time packet_time(const Slot& s) const;
  /// The slot at `c` passes with its packet sent (`sent`) or skipped; `account`: count it.
  void pass(Cursor& c, bool sent, bool account);
  /// Moves the cursor to the first slot starting at or after `t`; no ID there is wanted.
  void skip_to(const sc_core::sc_time& t);
  /// The cursor `d` slots after `c` (d < the slots in the list), no packet sent but those the
  /// mode sends anyway: the slots' starts repeat cycle after cycle (offset_).
  Cursor after(const Cursor& c, std::size_t d) const;
  /// The distance from the cursor to the first slot of the next cycle's worth whose ID some BIC
  /// holds in a register valid by then; the number of slots if there is none.
  std::size_t next_wanted();
  /// Some BIC holds the ID of `key` in a register valid at `t`: its slot at `t` is worth a
  /// strobe.
  bool wanted(std::uint32_t key, const sc_core::sc_time& t) const;
  /// The earliest time from which a register of some BIC holding a listed ID is valid.
  std::optional<sc_core::sc_time> first_request_time() const;
  /// Every BIC holding a demanded ID in a register valid before `t` has no buffer free before
  /// `t`: a strobe at `t` of any wanted slot misses (no hit line, L920).
  bool every_strobe_misses(const sc_core::sc_time& t) const;
  /// The earliest time at or after `t` from which a strobe could see the BICs otherwise without
  /// a wake: a buffer freed, or a register valid, from a later time (a processor's local time).
  std::optional<sc_core::sc_time> next_change(const sc_core::sc_time& t) const;
  /// While every strobe misses: the demanded IDs some BIC requests at the cursor, with the BICs
  /// that request each (miss_plan_), as they are before the loop sleeps.
  void plan_missed_strobes();
  /// `place` joins holders_[key] (kept ascending, once).
  void add_holder(std::uint32_t key, std::uint32_t place);
  /// Counts, as misses in the BICs of miss_plan_, the strobes the loop would have made of their
  /// slots from the cursor until `end` (not at it).
  void count_missed_strobes(const sc_core::sc_time& end);

  BroadcastTiming timing_;
  bool adaptive_;
  /// broadcast.wakes = every_change (the reference the plans ahead are tested against), or a
  /// bus that sends every packet.
  bool wake_at_every_change_;
  std::vector<BusInterface*> bics_;
  std::vector<Slot> slots_;
  // The IDs the ID list holds, each under a key 0, 1, ... (its first slot's order): an ID is a
  // 32-bit word of the BP's memory, and a corrupted one may be any value, so nothing is sized
  // by the IDs' values.
  static constexpr std::uint32_t kUnlisted = 0xFFFFFFFFu;
  /// The key of `id`, or kUnlisted when the ID list does not hold it.
  std::uint32_t key_of(std::uint32_t id) const {
    if (id < key_by_id_.size()) return key_by_id_[id];
    const auto it = key_by_large_id_.find(id);
    return it == key_by_large_id_.end() ? kUnlisted : it->second;
  }
  /// By ID, for the IDs below kDenseIdsPerSlot x slots (the IDs the control processor gives).
  std::vector<std::uint32_t> key_by_id_;
  std::unordered_map<std::uint32_t, std::uint32_t> key_by_large_id_;  ///< the others
  std::vector<std::uint32_t> id_of_key_;
  std::vector<int> demand_;  ///< by key: valid registers holding its ID, over all BICs
  /// By key: its slots in the ID list (one, unless a corrupted memory lists an ID twice).
  std::vector<std::vector<std::uint32_t>> positions_;
  /// By key: the BICs (their places in bics_, ascending) that have put its ID in a register
  /// since its last strobe, so a superset of those that hold it (valid or withdrawn): a strobe,
  /// wanted() and the miss plan ask these alone, in bics_' order, and find what asking every BIC
  /// finds, since a BIC that does not hold an ID neither requests nor hits it. Trimmed at a
  /// strobe of the ID, to the BICs that still hold it.
  std::vector<std::vector<std::uint32_t>> holders_;
  std::vector<std::uint32_t> demanded_;  ///< the keys whose demand_ is positive, in no order
  /// Requests withdrawn (key, when), kept until the loop is past them: at quantum 0 a strobe at
  /// the very time of the withdrawal is all they can still meet.
  std::vector<std::pair<std::uint32_t, sc_core::sc_time>> withdrawn_;
  /// Forgets the withdrawals before now; true if any is left.
  bool withdrawals_pending();
  std::vector<std::pair<std::size_t, std::uint32_t>>
      candidates_;  ///< next_wanted's (distance, key)
  std::vector<std::pair<std::uint32_t, std::vector<BusInterface*>>> miss_plan_;  ///< key, BICs
  /// By slot: when it starts after the cycle's start, no packet sent but those the mode sends
  /// anyway (adaptive: none; direct: every one); offset_[slots] ends the last slot.
  std::vector<sc_core::sc_time> offset_;
  long total_demand_ = 0;
  sc_core::sc_time idle_cycle_ = sc_core::SC_ZERO_TIME;  ///< one cycle with nothing wanted
  std::uint64_t idle_cycle_packets_ = 0, idle_cycle_words_ = 0;
  Cursor cursor_;
  sc_core::sc_event start_;
  sc_core::sc_event alarm_;  ///< what the loop sleeps on (sleep, ring_at; not on the queue)
  modules::ResumableProcess process_;  ///< its loop, and what runs it
  Sleep sleep_ = Sleep::kBusy;
  /// The end of the frame once the loop has run on to it (run_to): busy time is recorded up to
  /// it (a direct-mode packet that starts before it ends after it).
  sc_core::sc_time record_until_ = sc_core::sc_max_time();
  sc_core::sc_time planned_ = sc_core::SC_ZERO_TIME;     ///< while sleeping: when it wakes
  sc_core::sc_time packet_end_ = sc_core::SC_ZERO_TIME;  ///< of the last packet some BIC caught
  modules::Busy busy_{*this,
                      "time the bus carried packet words (its utilisation; IDs go by "
                      "whether or not anyone listens)"};
  modules::Counter ids_{*this, "ids", "IDs broadcast"};
  modules::Counter cycles_{*this, "cycles", "completed passes through the ID list"};
  modules::Counter packets_{*this, "packets", "packets broadcast"};
  modules::Counter packet_words_{*this, "packet_words", "their words", modules::StatUnit::words};
  modules::Counter hit_packets_{*this, "hit_packets", "packets some BIC captured"};
  modules::Counter captures_{*this, "captures", "packets captured, summed over BICs"};
  modules::Duration hit_packet_time_{*this, "hit_packet_time_s",
                                     "time spent sending packets some BIC captured"};
  std::vector<BusInterface*> hitters_;
};

}  // namespace rtsim::platform::gaudet
