#pragma once
// The messages of the Pixel-Planes 5 ray tracer on its token ring (seed 004 L292-L315, L352-L360;
// note 004 "Traffic classes"): every node's traffic is one of these, carried by the kit's
// RingChannel into the destination's queue. What crosses the ring is what the receiver works
// with: a caster's samples are the image's values, not a pointer to the functional twin's.
#include <array>
#include <cstdint>
#include <string>
#include <systemc>
#include <vector>

#include "firmware/tasks/region_sampling.hpp"
#include "firmware/tasks/sample_lattice.hpp"

namespace rtsim::platform::pxpl5 {

/// A screen region a ray caster is given: pixels [x0, x0 + w) x [y0, y0 + h), and the sample
/// lattice positions it casts (Layout::regions).
struct Region {
  int x0 = 0, y0 = 0, w = 0, h = 0;
  int id = -1;  ///< its number in the frame's list (-1: none left)
  tasks::LatticeRange lattice;
};

/// One sample: its lattice position and its value, the radiance summed over the position's
/// rays in the frame buffer's fixed point (shading::PixelAccumulator), so that resampling at full
/// density changes no bit. In a pixels message, a display pixel and its value.
using Sample = tasks::LatticeSample;

enum class Kind : std::uint8_t {
  kStartFrame,  ///< host -> master GP: frame f begins
  kRequest,     ///< caster -> master GP: give me a region (and what my last one cost)
  kAssign,      ///< master GP -> caster: a region, or none (id -1) when the frame's are given out
  kSamples,     ///< caster -> compositor: the samples of a region in the compositor's band
  kBand,        ///< compositor -> renderer: the band's samples in the renderer's tile
  kPixels,      ///< renderer -> frame buffer: display pixels
  kFrameDone,   ///< frame buffer -> host: every pixel of frame f is in
  kFrameBegin,  ///< master GP -> compositor: frame f's regions are being handed out
};

/// Traffic classes of the ring's statistics, in Kind order.
inline const std::vector<std::string> kTrafficClasses = {
    "start", "request", "assign", "samples", "band", "pixels", "frame_done", "frame_begin"};

struct Message {
  Kind kind = Kind::kStartFrame;
  int frame = 0;
  int from = 0;  ///< the sender's node index
  Region region;
  double last_cost_s = 0;  ///< kRequest: time the sender spent on its previous region
  int last_region = -1;    ///< kRequest: that region's id
  std::vector<Sample> samples;
  /// kSamples, --latency-probe (not on the wire): when its caster began the region and when it
  /// handed the message to the ring.
  sc_core::sc_time began, sent;
};

/// A samples, band or pixels message of frame `frame` carrying the samples gathered in `from`,
/// which is left empty for the next ones.
inline Message take_samples(Kind kind, int frame, std::vector<Sample>& from) {
  Message m;
  m.kind = kind;
  m.frame = frame;
  m.samples = std::move(from);
  from.clear();
  return m;
}

}  // namespace rtsim::platform::pxpl5
