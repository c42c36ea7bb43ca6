#pragma once
// The Newell teapot as 32 bicubic Bezier patches (with Frank Crow's bottom), as Eric Haines'
// Standard Procedural Databases list it (public domain): builtin:teapot, the benchmark on which
// Wang, Lewis & Hung checked their pipeline (seed 002 L266). Built in so that `rtsim validate` and
// the sweeps in configs/sweeps/ measure a real patch scene without a path to
// shared/scenes/teapot.bpt, which holds the same patches.
#include "firmware/scene.hpp"

namespace rtsim::scenes {

/// builtin:teapot: no camera (the renderer frames it, as for any .bpt file), no lights, one
/// material (kDefaultBptMaterial).
Scene make_newell_teapot();

}  // namespace rtsim::scenes
