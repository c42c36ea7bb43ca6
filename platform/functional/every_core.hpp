#pragma once
// Functional work shared out over threads: the functional renderer's rows, and a sampled run's
// count of its windows' work (window_work.hpp), once the simulation is over.
#include <functional>

namespace rtsim::functional {

/// The cores of this machine (1 to 256): what a functional pass uses when nothing else runs.
int every_core();

/// Runs `worker(t)` on `threads` threads (t = 0 on the calling one) and waits for them all;
/// returns how many ran: fewer when the system would not create more, so a worker must share
/// its work dynamically rather than by its index.
int run_on_threads(int threads, const std::function<void(int)>& worker);

}  // namespace rtsim::functional
