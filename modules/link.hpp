#pragma once
// A point-to-point link of the kit (DESIGN.md "The three layers"): a message of b bits handed to
// it at time t starts when the link is free, occupies it for the serialisation time
//     ceil(b / lanes) bit times,   bit time = 1 / bit_rate   (one bit per lane per bit time)
// and arrives `latency` after its last bit left. A bit-serial wire (lanes 1), a word-parallel
// bus (lanes 32) and a network hop are the same class with other parameters. A message that
// finds the link busy waits (back-pressure on its sender: the time is counted); a sender that
// produces the words more slowly than the link carries them holds the link until its last word
// is written (the message cannot arrive before it exists). It is the statistics group of its
// name: busy while it carries bits, messages, bits, waited_s.
//
// Used by gaudet-pert (the queues of a PERT's ring) and ullner-peripheral (host <-> peripheral);
// the ray-tracing pipeline's 13 bit-serial wires (seed 000 L727-L733) and the array's node links
// are links too.
#include <cstdint>
#include <string>
#include <systemc>

#include "modules/module_params.hpp"
#include "modules/prefetch.hpp"
#include "modules/slice_sink.hpp"
#include "modules/statistics.hpp"

namespace rtsim::modules {

class Link : public StatGroup {
 public:
  /// A machine preset's defaults for one link, with where they come from.
  struct Defaults {
    std::string latency{};   ///< "0 s"
    std::string lanes{};     ///< "32"
    std::string bit_rate{};  ///< "5 Mbit/s" (per lane); or, when empty:
    std::string bit_time{};  ///< "150 ns": the link is set by its bit time (a bit-serial wire)
    std::string source{};
  };
  /// Declares `latency`, `lanes` and `bit_rate` (or `bit_time`) under the link's path.
  static void declare_params(const ParamDecls& link, const Defaults& d);

  /// Reads its parameters under `params` without building it: a machine that may not build the
  /// link reads them anyway, so a bad value is an error whichever layout is chosen.
  static void check_params(const ModuleParams& params);

  /// Reads its parameters under `params` (its name: "pert0.link.shade_to_shell").
  explicit Link(const ModuleParams& params) : Link(params.path(), params) {}
  /// A link named `name` whose parameters are its class's, under `params` (the pipeline's
  /// links all read "pipeline.link").
  Link(std::string name, const ModuleParams& params);

  const std::string& name() const { return stat_path(); }
  const sc_core::sc_time& latency() const { return latency_; }
  /// Serialisation time of `bits`.
  sc_core::sc_time serialisation(std::uint64_t bits) const;
  const sc_core::sc_time& bit_time() const { return bit_time_; }
  std::uint64_t lanes() const { return lanes_; }

  /// A message of `bits` whose first word is ready at `start` and whose last word is written
  /// by `written` (its sender's own pace; = start if it was ready at once): returns when its
  /// last bit arrives at the far end. Messages are carried in the order they are handed over.
  sc_core::sc_time transfer(std::uint64_t bits, const sc_core::sc_time& start,
                            const sc_core::sc_time& written);
  sc_core::sc_time transfer(std::uint64_t bits, const sc_core::sc_time& start) {
    return transfer(bits, start, start);
  }

  /// What a message carries, for the traces: a slice `what` on the link's track with `key` = id
  /// (the ray or job) and its bits, and a step of that item's flow (SliceSink::hop).
  struct Carried {
    std::string_view what;  ///< "ray", "result", "description", ...
    std::string_view key;   ///< "ray" or "job": the flow it steps
    std::uint64_t id = 0;
    /// The flow's id when the item's id is not unique in the machine (0: the id).
    std::uint64_t flow = 0;
  };
  /// Traces the messages handed over with what they carry into `sink` (the run's traces).
  void trace_to(SliceSink& sink) { trace_ = &sink; }
  /// transfer(), traced as carrying `c`.
  sc_core::sc_time transfer(std::uint64_t bits, const sc_core::sc_time& start,
                            const sc_core::sc_time& written, const Carried& c);

  /// A hint to the cache, no more: brings in what transfer() reads and writes (a sender that
  /// knows its link early calls it while it does other work; modules/prefetch.hpp).
  void prepare_transfer() const {
    const auto* from = reinterpret_cast<const char*>(&free_);
    const auto* to = reinterpret_cast<const char*>(&waited_ + 1);
    prefetch_bytes<PrefetchFor::kWrite>(from, static_cast<std::size_t>(to - from));
  }
  std::uint64_t messages() const { return messages_.value(); }
  std::uint64_t bits() const { return bits_.value(); }
  /// Time it carried bits (its utilisation) and when.
  sc_core::sc_time busy() const { return busy_.total(); }
  const BusyTimeline& timeline() const { return busy_.timeline(); }
  /// Time messages waited for the link to be free (back-pressure).
  sc_core::sc_time waited() const { return waited_.value(); }

 private:
  sc_core::sc_time latency_;
  std::uint64_t lanes_;
  sc_core::sc_time bit_time_;
  sc_core::sc_time free_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time last_begin_ = sc_core::SC_ZERO_TIME;  ///< when the last message took the link
  SliceSink* trace_ = nullptr;
  Busy busy_{*this, "time carrying bits (its utilisation)"};
  Counter messages_{*this, "messages", "messages carried"};
  Counter bits_{*this, "bits", "bits carried", StatUnit::bits};
  Duration waited_{*this, "waited_s", "time messages waited for the link to be free"};
};

}  // namespace rtsim::modules
