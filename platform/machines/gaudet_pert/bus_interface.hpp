#pragma once
// Gaudet's Bus Interface Controller (seed 001 §5.4, L897-L924; Fig. 5-7 is lost, the prose
// survives): the processor's only connection to a broadcast bus.
//  * ID registers (§5.4.1, L910-L912): the processor writes the ID of a packet it wants into a
//    free register; the register is flagged free again when its packet has been received.
//  * Comparator and hit line (§5.4.2, L920): on the Broadcast Processor's sync strobe the ID on
//    the bus is latched and compared with all valid registers in parallel; if one matches *and*
//    a buffer is free, the BIC drives the (wired-OR) hit line and arms the free buffer. A match
//    with no free buffer is not a hit: the packet is missed until a later cycle.
//  * Buffers (§5.4.3, L924): two FIFO buffers; the processor works on a packet in one while the
//    BIC fills the other, and reads a word per cycle. The hit line "sets the available buffer to
//    start copying" (L920) and the buffers are FIFOs (L924): with `stream` set, a packet is
//    taken as soon as its first record is in and its words are read as they arrive
//    (ReceivedPacket::words_in); the register is still freed at full arrival (L912).
// The number of registers and of buffers are parameters (the thesis says "multiple" and 2).
// Every register and buffer carries the time from which its state holds, so a processor that
// runs ahead of simulated time cannot make the bus see a request before its time.
//
// A strobe sees the registers and buffers as they were just before it: a request or a freed
// buffer at the strobe's very time counts from the next strobe (the comparator latches the
// registers as the strobe comes, L920), and a request withdrawn at its very time (cancel) is
// still matched: its packet streams in and is dropped, as when the withdrawal came after. Which of
// two threads SystemC runs first at one time is the order of its event queue, which any other event
// can change: with `<=`, a request and a strobe at the same picosecond met or missed by that order,
// and an unrelated timed event in the simulation moved 8-PERT frame times by up to 0.3%
// (tests/gaudet_tie_order_test.cpp).
#include <cstdint>
#include <span>
#include <string>
#include <systemc>
#include <vector>

#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/machines/gaudet_pert/packet_port.hpp"

namespace rtsim::platform::gaudet {

class BroadcastProcessor;

class BusInterface final : public PacketPort, public modules::StatGroup {
 public:
  /// How many ID registers a processor's BIC has by default, and why (the thesis says
  /// "multiple", L910: each processor's preset chooses).
  struct IdRegisters {
    std::string value, description, source;
  };
  /// Its parameters under `bic` ("pert.shell.bic"): `id_registers` and `buffers`.
  static void declare_params(const modules::ParamDecls& bic, const IdRegisters& id_registers);
  /// Its parameters' names (each processor class gives its own defaults, so a name is the
  /// constant here and the rest of its declaration is declare_params').
  static constexpr const char* kBuffers = "buffers";
  static constexpr const char* kIdRegisters = "id_registers";
  static constexpr const char* kStream = "stream";
  /// `stream` under `bic`, for a processor that reads its packets record by record (the
  /// ShellProcessor): `value` "true" or "false", and why.
  static void declare_stream_param(const modules::ParamDecls& bic, std::string value,
                                   std::string source);
  /// `params`: its own, under its name ("pert0.shell.bic"). `stream_unit_words`: with `stream`
  /// declared and set, a packet is taken once this many words are in; 0: never streams.
  explicit BusInterface(const modules::ModuleParams& params, std::uint32_t stream_unit_words = 0);

  const std::string& name() const { return stat_path(); }

  // Processor side (PacketPort).
  bool request(std::uint32_t id, const sc_core::sc_time& t) override;
  void cancel(std::uint32_t id, const sc_core::sc_time& t) override;
  bool pending(std::uint32_t id) const override;
  bool register_free(const sc_core::sc_time& t) const override;
  std::optional<sc_core::sc_time> next_arrival(
      std::optional<std::uint32_t> id = std::nullopt) const override;
  std::optional<ReceivedPacket> take(const sc_core::sc_time& t,
                                     std::optional<std::uint32_t> id = std::nullopt) override;
  void release(const ReceivedPacket& p, const sc_core::sc_time& t) override;
  const sc_core::sc_event& changed_event() const override { return changed_; }

  // Bus side (the Broadcast Processor's sync strobe at `t`).
  /// Some valid register holds `id` (valid at `t`) but no buffer is free: counted as a miss.
  bool hit(std::uint32_t id, const sc_core::sc_time& t);
  /// The packet `id` streams into a free buffer from `start` (the bus starts sending it); its
  /// words follow from `first_word`, one every `word_time`; its last word is in at `arrival`.
  /// The register that asked for it is freed on receipt (L912). `words`: the packet as the bus
  /// carried it, copied into the buffer.
  void capture(std::uint32_t id, const sc_core::sc_time& start, const sc_core::sc_time& arrival,
               const sc_core::sc_time& first_word, const sc_core::sc_time& word_time,
               std::span<const std::uint32_t> words);

  /// Some register holds `id`, valid at `t` (the comparator would match it then): valid
  /// before `t`, and not withdrawn before it.
  bool requested(std::uint32_t id, const sc_core::sc_time& t) const;
  /// Some register holds `id`, valid or withdrawn: a strobe of it may still match here.
  bool holds(std::uint32_t id) const;
  std::uint64_t missed_no_buffer() const { return missed_.value(); }

 private:
  friend class BroadcastProcessor;
  struct Register {
    std::uint32_t id = 0;
    bool valid = false;
    sc_core::sc_time from = sc_core::SC_ZERO_TIME;  ///< valid from / free from
    /// The request its processor withdrew last (cancel): its ID, valid from `withdrawn_from`,
    /// withdrawn at `withdrawn_at`. Strobes up to then match it (until one captures it).
    bool withdrawn = false;
    std::uint32_t withdrawn_id = 0;
    sc_core::sc_time withdrawn_from = sc_core::SC_ZERO_TIME;
    sc_core::sc_time withdrawn_at = sc_core::SC_ZERO_TIME;
    bool withdrawn_match(std::uint32_t i, const sc_core::sc_time& t) const {
      return withdrawn && withdrawn_id == i && withdrawn_from < t && t <= withdrawn_at;
    }
  };
  enum class BufferState { kFree, kFilled, kInUse };
  struct Buffer {
    BufferState state = BufferState::kFree;
    std::uint32_t id = 0;
    sc_core::sc_time at = sc_core::SC_ZERO_TIME;     ///< free from / arrival
    sc_core::sc_time start = sc_core::SC_ZERO_TIME;  ///< its transfer began (filled)
    sc_core::sc_time ready = sc_core::SC_ZERO_TIME;  ///< can be taken from (filled)
    sc_core::sc_time first_word = sc_core::SC_ZERO_TIME, word_time = sc_core::SC_ZERO_TIME;
    std::vector<std::uint32_t> words;  ///< the FIFO's contents (filled)
  };
  int free_buffer(const sc_core::sc_time& t) const;

  std::vector<Register> registers_;
  std::vector<Buffer> buffers_;
  std::uint32_t stream_unit_words_ = 0;  ///< 0: packets are taken at full arrival
  BroadcastProcessor* bus_ = nullptr;
  std::uint32_t bus_place_ = 0;  ///< its place among the bus's BICs
  sc_core::sc_event changed_;
  modules::Counter requests_{*this, "requests", "packet IDs its processor asked for"};
  modules::Counter received_{*this, "packets_received", "packets captured into a buffer"};
  modules::Counter missed_{*this, "missed_no_buffer",
                           "broadcasts of a wanted packet that found no free buffer"};
  modules::Counter register_full_{*this, "register_full",
                                  "requests refused: every ID register in use"};
  modules::Peak peak_registers_{*this, "registers_in_use_peak", "ID registers in use at once"};
};

}  // namespace rtsim::platform::gaudet
