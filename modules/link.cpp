#include "modules/link.hpp"

#include <algorithm>
#include <cmath>

#include "modules/sim_time.hpp"

namespace rtsim::modules {

void Link::declare_params(const ParamDecls& link, const Defaults& d) {
  const std::string& who = link.path();
  link.time("latency", d.latency,
            "Link " + who + ": time from a message's last bit leaving to its arrival", d.source);
  link.count("lanes", d.lanes, "1", "65536", "lanes",
             "Link " + who + ": bits carried side by side (1: bit-serial, 32: word-parallel)",
             d.source);
  if (d.bit_rate.empty()) {
    link.declare({.name = "bit_time",
                  .kind = params::ParamKind::kTime,
                  .default_value = d.bit_time,
                  .min = "1 ps",
                  .max = "1 s",
                  .description = "Link " + who + ": time to send one bit on each lane",
                  .source = d.source});
    return;
  }
  link.declare({.name = "bit_rate",
                .kind = params::ParamKind::kBitRate,
                .default_value = d.bit_rate,
                .min = "1 bit/s",
                .description = "Link " + who + ": bits per second on each lane",
                .source = d.source});
}

namespace {
/// One bit time in whole picoseconds (the time resolution), from whichever the link declares.
sc_core::sc_time read_bit_time(const ModuleParams& params) {
  const std::string bit_time = params.path() + ".bit_time";
  if (params.registry().contains(params.registry().class_path(bit_time)))
    return std::max(from_ps(1), params.get_time("bit_time"));
  return from_ps(static_cast<std::int64_t>(
      std::max(1.0, std::round(1e12 / params.get_bitrate_bps("bit_rate")))));
}
}  // namespace

Link::Link(std::string name, const ModuleParams& params)
    : StatGroup(std::move(name)),
      latency_(params.get_time("latency")),
      lanes_(std::max<std::size_t>(1, params.get_count("lanes"))),
      bit_time_(read_bit_time(params)) {}

sc_core::sc_time Link::serialisation(std::uint64_t bits) const {
  return times(bit_time_, (bits + lanes_ - 1) / lanes_);
}

sc_core::sc_time Link::transfer(std::uint64_t bits, const sc_core::sc_time& start,
                                const sc_core::sc_time& written) {
  const sc_core::sc_time begin = std::max(start, free_);
  waited_ += begin - start;
  const sc_core::sc_time done = std::max(plus(begin, serialisation(bits)), written);
  if (done > begin) busy_.record(begin, done - begin);
  free_ = done;
  ++messages_;
  bits_ += bits;
  return plus(done, latency_);
}

}  // namespace rtsim::modules
