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
  link.declare({.name = "bit_rate",
                .kind = params::ParamKind::kBitRate,
                .default_value = d.bit_rate,
                .min = "1 bit/s",
                .description = "Link " + who + ": bits per second on each lane",
                .source = d.source});
}

Link::Link(const ModuleParams& params)
    : name_(params.path()),
      latency_(params.get_time("latency")),
      lanes_(std::max<std::size_t>(1, params.get_count("lanes"))),
      // One bit time in whole picoseconds (the time resolution).
      bit_time_(from_ps(static_cast<std::int64_t>(
          std::max(1.0, std::round(1e12 / params.get_bitrate_bps("bit_rate")))))) {}

sc_core::sc_time Link::serialisation(std::uint64_t bits) const {
  return times(bit_time_, (bits + lanes_ - 1) / lanes_);
}

sc_core::sc_time Link::transfer(std::uint64_t bits, const sc_core::sc_time& start,
                                const sc_core::sc_time& written) {
  const sc_core::sc_time begin = std::max(start, free_);
  waited_ += begin - start;
  const sc_core::sc_time done = std::max(plus(begin, serialisation(bits)), written);
  if (done > begin) {
    timeline_.add(begin, done - begin);
    busy_ += done - begin;
  }
  free_ = done;
  ++messages_;
  bits_ += bits;
  return plus(done, latency_);
}

}  // namespace rtsim::modules
