#pragma once
// The figures of Ullner's ray-tracing pipeline (seed 000 §2.4.4, L741-L753; note 000 §3.4 and
// §7.4 V12-V16): throughput one ray per ~5 us whatever the number of processors, latency N x 5 us,
// a 512 x 512 frame in about 1.3 s, about eight seconds with shadows and anti-aliasing, and a
// host that cannot keep up setting the pace while the processors idle.
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

/// Machine name of the pipeline in `rtsim run`.
inline constexpr const char* kPipelineMachine = "ullner-pipeline";

}  // namespace rtsim::validation
