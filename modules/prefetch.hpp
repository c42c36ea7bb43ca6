#pragma once
// Asks the CPU to bring an object's cache lines in ahead of its use (a hint: no effect on what
// the program computes). A large machine's processors each keep their state in its own few
// kilobytes, so every activation starts by waiting for its state to come from memory; a queue
// that knows who runs next can have that state on its way while the current one runs
// (modules/wake_queue.hpp, Client::prepare), and a sender its receiver's port (ullner-array).
#include <cstddef>

namespace rtsim::modules {

inline constexpr std::size_t kCacheLine = 64;

/// What the lines are wanted for.
enum class PrefetchFor { kRead = 0, kWrite = 1 };

/// Prefetches the lines of the `bytes` bytes at `p`.
template <PrefetchFor kFor = PrefetchFor::kRead>
void prefetch_bytes(const void* p, std::size_t bytes) {
  const char* c = static_cast<const char*>(p);
  constexpr int kRw = static_cast<int>(kFor);
  for (std::size_t at = 0; at < bytes; at += kCacheLine) __builtin_prefetch(c + at, kRw);
  if (bytes > 0) __builtin_prefetch(c + bytes - 1, kRw);
}

/// Prefetches the lines `x` lies on.
template <PrefetchFor kFor = PrefetchFor::kRead, class T>
void prefetch_object(const T& x) {
  prefetch_bytes<kFor>(&x, sizeof(T));
}

}  // namespace rtsim::modules
