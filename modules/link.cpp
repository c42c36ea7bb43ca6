#include "modules/link.hpp"

#include <algorithm>
#include <cmath>

#include "modules/sim_time.hpp"

namespace rtsim::modules {

namespace {
// Its parameters' names, each written once: declared with the preset's defaults, read below.
constexpr const char* kLatency = "latency";
constexpr const char* kLanes = "lanes";
constexpr const char* kBitTime = "bit_time";
constexpr const char* kBitRate = "bit_rate";
}  // namespace

void Link::declare_params(const ParamDecls& link, const Defaults& d) {
  const std::string& who = link.path();
  link.time(kLatency, d.latency,
            "Link " + who + ": time from a message's last bit leaving to its arrival", d.source);
  link.count(kLanes, d.lanes, "1", "65536", "lanes",
             "Link " + who + ": bits carried side by side (1: bit-serial, 32: word-parallel)",
             d.source);
  if (d.bit_rate.empty()) {
    link.declare({.name = kBitTime,
                  .kind = params::ParamKind::kTime,
                  .default_value = d.bit_time,
                  .min = "1 ps",
                  .max = "1 s",
                  .description = "Link " + who + ": time to send one bit on each lane",
                  .source = d.source});
    return;
  }
  link.declare({.name = kBitRate,
                .kind = params::ParamKind::kBitRate,
                .default_value = d.bit_rate,
                .min = "1 bit/s",
                .description = "Link " + who + ": bits per second on each lane",
                .source = d.source});
}

namespace {
/// One bit time in whole picoseconds (the time resolution), from whichever the link declares.
sc_core::sc_time read_bit_time(const ModuleParams& params) {
  if (params.registry().contains(params.registry().class_path(params.path_of(kBitTime))))
    return std::max(from_ps(1), params.get_time(kBitTime));
  return from_ps(static_cast<std::int64_t>(
      std::max(1.0, std::round(1e12 / params.get_bitrate_bps(kBitRate)))));
}
}  // namespace

void Link::check_params(const ModuleParams& params) {
  (void)params.get_time(kLatency);
  (void)params.get_count(kLanes);
  (void)read_bit_time(params);
}

Link::Link(std::string name, const ModuleParams& params)
    : StatGroup(std::move(name)),
      latency_(params.get_time(kLatency)),
      lanes_(std::max<std::size_t>(1, params.get_count(kLanes))),
      bit_time_(read_bit_time(params)) {}

sc_core::sc_time Link::serialisation(std::uint64_t bits) const {
  return times(bit_time_, (bits + lanes_ - 1) / lanes_);
}

sc_core::sc_time Link::transfer(std::uint64_t bits, const sc_core::sc_time& start,
                                const sc_core::sc_time& written) {
  const sc_core::sc_time begin = std::max(start, free_);
  last_begin_ = begin;
  waited_ += begin - start;
  const sc_core::sc_time done = std::max(plus(begin, serialisation(bits)), written);
  if (done > begin) busy_.record(begin, done - begin);
  free_ = done;
  ++messages_;
  bits_ += bits;
  return plus(done, latency_);
}

sc_core::sc_time Link::transfer(std::uint64_t bits, const sc_core::sc_time& start,
                                const sc_core::sc_time& written, const Carried& c) {
  const sc_core::sc_time arrives = transfer(bits, start, written);
  if (trace_ && trace_->records()) {
    trace_->slice(name(), c.what, last_begin_, arrives - last_begin_,
                  {{c.key, static_cast<double>(c.id)}, {"bits", static_cast<double>(bits)}});
    trace_->hop(name(), c.key, c.flow != 0 ? c.flow : c.id, last_begin_);
  }
  return arrives;
}

}  // namespace rtsim::modules
