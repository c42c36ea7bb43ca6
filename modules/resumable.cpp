#include "modules/resumable.hpp"

namespace rtsim::modules {

void* FramePool::fresh(std::size_t c, std::size_t n) {
  // Pooled frames are made whole size classes, so any frame of the class can reuse them.
  return ::operator new(c < kClasses ? c * kGrain : n);
}

}  // namespace rtsim::modules
