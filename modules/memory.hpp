#pragma once
// A word-addressed memory behind a TLM-2.0 target socket. b_transport reads or writes
// data_length / 4 32-bit words at the payload's byte address and annotates the access time:
// writes come through a load port at `write_word_time` per word; reads fetch whole lines of
// `line_words` words in parallel at `read_line_time` a line (Ullner's 20 parameter memories:
// "one cycle reads a whole polygon", seed 000 L544). Streams the model only needs to time (a
// pipeline fetching every polygon for every ray) are charged with account_line_reads(), which
// advances the same counters without moving data. It is the statistics group of its name: busy
// while its read port reads lines, words_written, lines_read and the load port's write_busy_s.
// Used by ullner-peripheral (the parameter memories) and gaudet-pert (the Broadcast Processors'
// memories); the array's node memories next.
#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <span>
#include <string>
#include <systemc>
#include <tlm>
#include <vector>

#include "common/input_error.hpp"
#include "modules/blocking_target.hpp"
#include "modules/payload_pool.hpp"
#include "modules/sim_time.hpp"
#include "modules/statistics.hpp"

namespace rtsim::modules {

/// The most host memory the modelled memories of one run may take together: their sizes are
/// parameters whose bounds are the machines' (a node's memory up to 10^9 words), but 64 nodes
/// of 4 GB are more than this computer holds. A run that would pass it is refused while it is
/// built, before it runs (docs/bad-input.md, "Resources").
inline constexpr std::uint64_t kMaxModelledMemoryBytes = std::uint64_t{1} << 30;

/// Bytes the Memory modules that exist now hold.
inline std::uint64_t& modelled_memory_bytes() {
  static std::uint64_t bytes = 0;
  return bytes;
}

/// How a Memory's host words are given back. Host memory: a large block is mapped pages the
/// system zeroes when first touched, so a thousand node memories cost only the words they are
/// given (a vector, or calloc from the heap, would write every one); a small one comes from
/// calloc.
struct HostWordsFree {
  static constexpr std::size_t kMapFromBytes = 64 * 1024;
  std::size_t mapped_bytes = 0;  ///< 0: from calloc
  void operator()(std::uint32_t* p) const {
    if (mapped_bytes)
      munmap(p, mapped_bytes);
    else
      std::free(p);
  }
};

class Memory : public sc_core::sc_module, public StatGroup, public BlockingTarget {
 public:
  tlm::tlm_target_socket<> socket;

  Memory(sc_core::sc_module_name name, std::size_t words, unsigned line_words,
         sc_core::sc_time write_word_time, sc_core::sc_time read_line_time)
      : sc_core::sc_module(name),
        StatGroup(sc_core::sc_module::name()),
        socket("socket"),
        data_(reserve_host_memory(words)),
        words_(words),
        line_words_(line_words ? line_words : 1),
        write_word_time_(write_word_time),
        read_line_time_(read_line_time) {
    socket.bind(*this);
  }

  ~Memory() override { modelled_memory_bytes() -= words_ * sizeof(std::uint32_t); }
  Memory(const Memory&) = delete;
  Memory& operator=(const Memory&) = delete;

  std::span<const std::uint32_t> contents() const { return {data_.get(), words_}; }
  std::size_t size_words() const { return words_; }

  /// A fault in the load path (`rtsim run --fault`): whenever word `word` is written, it is
  /// stored XORed with `xor_mask`, as if the transfer had been corrupted in flight. The model's
  /// answers come from what the memory holds, so the fault shows wherever the word is used.
  struct Fault {
    std::uint64_t word = 0;
    std::uint32_t xor_mask = 0;
    std::uint64_t applied = 0;  ///< writes it corrupted
  };
  void inject_fault(std::uint64_t word, std::uint32_t xor_mask) {
    faults_.push_back({word, xor_mask, 0});
  }
  const std::vector<Fault>& faults() const { return faults_; }
  std::uint64_t words_written() const { return words_written_.value(); }
  std::uint64_t lines_read() const { return lines_read_.value(); }
  sc_core::sc_time write_busy() const { return write_busy_.value(); }
  sc_core::sc_time read_busy() const { return read_busy_.total(); }

  /// `lines` line reads from `start` whose data the model does not need; returns their time.
  sc_core::sc_time account_line_reads(std::uint64_t lines, const sc_core::sc_time& start) {
    lines_read_ += lines;
    const sc_core::sc_time t = times(read_line_time_, lines);
    read_busy_.record(start, t);
    return t;
  }
  /// `times` more writes of the `words` words from word `first` whose data the model does not
  /// need to move (a machine that computes where shifted data comes to rest): the counters and
  /// the faults' application counts advance as if they had been written.
  void account_writes(std::uint64_t first, std::uint64_t words, std::uint64_t times) {
    words_written_ += words * times;
    for (auto& f : faults_)
      if (f.word >= first && f.word < first + words) f.applied += times;
  }
  /// When the read port was busy (reads charged by account_line_reads, and b_transport reads).
  const BusyTimeline& read_timeline() const { return read_busy_.timeline(); }

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) override {
    const std::uint64_t addr = gp.get_address();
    const unsigned len = gp.get_data_length();
    if (addr % 4 != 0 || len % 4 != 0 || gp.get_byte_enable_ptr() != nullptr ||
        gp.get_streaming_width() < len) {
      gp.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
      return;
    }
    const std::uint64_t first = addr / 4, words = len / 4;
    if (first + words > words_) {
      gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
      return;
    }
    if (gp.is_write()) {
      std::memcpy(&data_[first], gp.get_data_ptr(), len);
      for (auto& f : faults_) {
        if (f.word < first || f.word >= first + words) continue;
        data_[f.word] ^= f.xor_mask;
        ++f.applied;
      }
      words_written_ += words;
      const sc_core::sc_time t = times(write_word_time_, words);
      write_busy_ += t;
      delay += t;
    } else if (gp.is_read()) {
      std::memcpy(gp.get_data_ptr(), &data_[first], len);
      delay +=
          account_line_reads((words + line_words_ - 1) / line_words_, modules::sim_now() + delay);
    }
    gp.set_response_status(tlm::TLM_OK_RESPONSE);
  }

  using Words = std::unique_ptr<std::uint32_t[], HostWordsFree>;

  /// `words` zero words, counted against kMaxModelledMemoryBytes; an InputError naming this
  /// memory if they would pass it.
  Words reserve_host_memory(std::size_t words) {
    const std::uint64_t bytes = static_cast<std::uint64_t>(words) * sizeof(std::uint32_t);
    std::uint64_t& total = modelled_memory_bytes();
    if (words > kMaxModelledMemoryBytes || total + bytes > kMaxModelledMemoryBytes)
      throw InputError(name(), 0,
                       "this memory of " + std::to_string(words) + " words, with the " +
                           std::to_string(total >> 20) +
                           " MiB of the memories built before it, would take more than the " +
                           std::to_string(kMaxModelledMemoryBytes >> 20) +
                           " MiB rtsim gives a run's modelled memories "
                           "(kMaxModelledMemoryBytes); lower the parameter that sizes it "
                           "(`rtsim list params --machine M '*memory*'`)");
    Words data;
    if (bytes >= HostWordsFree::kMapFromBytes) {
      void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (p == MAP_FAILED) throw std::bad_alloc();
      data = Words(static_cast<std::uint32_t*>(p), HostWordsFree{static_cast<std::size_t>(bytes)});
    } else {
      data = Words(static_cast<std::uint32_t*>(std::calloc(std::max<std::size_t>(words, 1), 4)));
      if (!data) throw std::bad_alloc();
    }
    total += bytes;
    return data;
  }

  Words data_;
  std::size_t words_;
  unsigned line_words_;
  sc_core::sc_time write_word_time_;
  sc_core::sc_time read_line_time_;
  Busy read_busy_{*this, "time its read port read lines (its utilisation)"};
  Counter words_written_{*this, "words_written", "words written through its load port",
                         StatUnit::words};
  Counter lines_read_{*this, "lines_read", "lines read"};
  Duration write_busy_{*this, "write_busy_s", "time its load port wrote words"};
  std::vector<Fault> faults_;
};

/// One TLM transaction of `n` words at word address `word` of the memory behind `port`
/// (`command` read or write, `words` the data), adding the access time to `delay` (loosely
/// timed: the caller synchronises when it likes). False if the memory refused it (out of range).
/// It uses `gp`, which the caller keeps: a loop of many accesses makes no payload each.
template <class Socket>
bool transfer_words(Socket& port, tlm::tlm_generic_payload& gp, tlm::tlm_command command,
                    std::uint64_t word, std::uint32_t* words, std::size_t n,
                    sc_core::sc_time& delay) {
  gp.set_command(command);
  gp.set_address(word * 4);
  gp.set_data_ptr(reinterpret_cast<unsigned char*>(words));
  gp.set_data_length(static_cast<unsigned>(n * 4));
  gp.set_streaming_width(static_cast<unsigned>(n * 4));
  gp.set_byte_enable_ptr(nullptr);
  gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  port->b_transport(gp, delay);
  return !gp.is_response_error();
}

/// Writes `n` words from `words` at word address `word` of the memory behind `port` (its load
/// path) in one TLM write transaction (transfer_words).
template <class Socket>
bool write_words(Socket& port, tlm::tlm_generic_payload& gp, std::uint64_t word,
                 const std::uint32_t* words, std::size_t n, sc_core::sc_time& delay) {
  return transfer_words(port, gp, tlm::TLM_WRITE_COMMAND, word, const_cast<std::uint32_t*>(words),
                        n, delay);
}

/// Reads `n` words at word address `word` of the memory behind `port` into `words`, in one TLM
/// read transaction (transfer_words).
template <class Socket>
bool read_words(Socket& port, tlm::tlm_generic_payload& gp, std::uint64_t word,
                std::uint32_t* words, std::size_t n, sc_core::sc_time& delay) {
  return transfer_words(port, gp, tlm::TLM_READ_COMMAND, word, words, n, delay);
}

template <class Socket>
bool write_words(Socket& port, std::uint64_t word, const std::uint32_t* words, std::size_t n,
                 sc_core::sc_time& delay) {
  const PooledPayload gp;  // a payload made for each call costs more than the write
  return write_words(port, *gp, word, words, n, delay);
}

}  // namespace rtsim::modules
