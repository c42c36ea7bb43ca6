#include "modules/resumable.hpp"

#include <new>

namespace rtsim::modules {

std::vector<void*>& FramePool::free_list(std::size_t size_class) {
  static std::vector<void*> lists[kClasses];
  return lists[size_class];
}

void* FramePool::get(std::size_t n) {
  const std::size_t c = (n + kGrain - 1) / kGrain;
  if (c >= kClasses) return ::operator new(n);
  std::vector<void*>& list = free_list(c);
  if (list.empty()) return ::operator new(c* kGrain);
  void* p = list.back();
  list.pop_back();
  return p;
}

void FramePool::put(void* p, std::size_t n) noexcept {
  const std::size_t c = (n + kGrain - 1) / kGrain;
  if (c >= kClasses) {
    ::operator delete(p);
    return;
  }
  try {
    free_list(c).push_back(p);
  } catch (...) {
    ::operator delete(p);
  }
}

}  // namespace rtsim::modules
