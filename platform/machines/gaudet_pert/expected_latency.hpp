#pragma once
// Gaudet's worst-case analysis of adaptive broadcasting (seed 001 §6.3.1, L1064-L1099): the
// expected average latency of a PrimProcessor's first packet when n PrimProcessors post their
// requests at once, with no two asking for the same packet, and the PrimBroadcaster sends in
// one cycle every ID and as many packets as are asked for (n to 2n).
//   eal    = sum_{i=0}^{n} P(n+i) L(n+i)                      (L1083-L1087)
//   L(n+i) = [mct + (n+i-1) apt] / 2 + apt                     (L1091)
//   P(n+i) = C(n,i) P1^(n-i) P2^i                              (L1092)
//   P1 = (2r - p) / r,  P2 = (p - r) / r                       (L1096-L1097)
// p: packets broadcast, r: rays processed, mct: minimum cycle time (every ID, no packet),
// apt: average time to broadcast a packet.
#include <algorithm>
#include <cmath>

namespace rtsim::platform::gaudet {

struct EalInputs {
  int n = 1;       ///< PrimProcessors (PERTs)
  double p = 0.0;  ///< packets broadcast
  double r = 0.0;  ///< rays processed
  double mct_s = 0.0;
  double apt_s = 0.0;
};

/// P2 = (p - r) / r, clamped to [0, 1] (the model allows 1 or 2 packets a ray).
inline double eal_two_packet_probability(const EalInputs& in) {
  if (!(in.r > 0)) return 0.0;
  return std::clamp((in.p - in.r) / in.r, 0.0, 1.0);
}

inline double expected_average_latency_s(const EalInputs& in) {
  const double p2 = eal_two_packet_probability(in);
  const double p1 = 1.0 - p2;
  double eal = 0.0;
  for (int i = 0; i <= in.n; ++i) {
    // C(n, i) P1^(n-i) P2^i through logs: n may be large.
    const double log_c =
        std::lgamma(in.n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(in.n - i + 1.0);
    double prob = 0.0;
    if ((p1 > 0 || i == in.n) && (p2 > 0 || i == 0))
      prob = std::exp(log_c + (in.n - i > 0 ? (in.n - i) * std::log(p1) : 0.0) +
                      (i > 0 ? i * std::log(p2) : 0.0));
    const double latency = (in.mct_s + (in.n + i - 1) * in.apt_s) / 2.0 + in.apt_s;
    eal += prob * latency;
  }
  return eal;
}

}  // namespace rtsim::platform::gaudet
