#pragma once
// The transformation and clipping (T&C) processor of Ullner's scan-line tree (seed 000 §3.3.1,
// L1096-L1336): one processor a polygon, all on one bus, the program held at the bus's end and
// broadcast (SIMD, L1100-L1102). The processor, as L1274 postulates it: a floating-point unit
// with one accumulator, several index registers that increment and decrement, 256 words of 32-bit
// floating-point memory (L1272), instructions with one 8-bit address optionally modified by an
// index register, and no jumps or calls: control stays at the bus's end.
//
// Conditional work is the shutdown flag (L1161): a test instruction that finds its condition
// true makes the processor ignore every later instruction until the bus's reset line, which
// wakes every processor at once. Loops are broadcast their bound's number of times (L1161,
// L1165). Literals travel with the instruction that uses them ("m11 := literal", Fig. 3-10).
//
// Every instruction below is one broadcast: the program's length is its instruction count
// (Fig. 3-16 counts the same way, L1334).
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace rtsim::scanline {

/// Words of a T&C processor's memory (L1272: 256 words of 32-bit floating point).
inline constexpr int kTcWords = 256;
/// Index registers ("several", L1274).
inline constexpr int kIndexRegisters = 6;

enum class Op : std::uint8_t {
  // The accumulator, with an operand at addr (+ the index register, if any).
  Load,          ///< acc := m
  Store,         ///< m := acc
  Add,           ///< acc := acc + m
  Sub,           ///< acc := acc - m
  Mul,           ///< acc := acc m
  Div,           ///< acc := acc / m
  Literal,       ///< acc := literal
  StoreLiteral,  ///< m := literal
  Quantize,      ///< acc := quant(acc): 12-bit fixed point of the kind `reg` names (L1266)
  Send,          ///< acc to the scan conversion processor (Fig. 3-15's `send`)
  // Index registers.
  IndexLiteral,  ///< ix[reg] := literal
  IndexLoad,     ///< ix[reg] := m (a whole number)
  IndexStore,    ///< m := ix[reg]
  IndexCopy,     ///< ix[reg] := ix[other]
  IndexInc,      ///< ix[reg] := ix[reg] + 1
  IndexAddMod,   ///< ix[reg] := (ix[reg] + ix[other]) mod m (m: a count in memory)
  // Shutdown tests: the processor stops listening if the condition holds (L1161).
  OffIfLess,          ///< acc <  m
  OffIfLessEqual,     ///< acc <= m
  OffIfGreater,       ///< acc >  m
  OffIfGreaterEqual,  ///< acc >= m
  OffIfEqual,         ///< acc == m
  OffIfNotEqual,      ///< acc != m
  OffIfIndexAtLeast,  ///< ix[reg] >= m
  Reset,              ///< the bus's reset line: every processor listens again
};
inline constexpr int kOps = 24;

/// Quantize's kinds: screen x and y in [-1, 1], depth in [0, 1], a colour in [0, 1].
enum class QuantKind : std::uint8_t { ScreenXY, Depth, Colour };

/// No index register.
inline constexpr std::uint8_t kNoIndex = 0xff;

struct Instruction {
  Op op = Op::Reset;
  std::uint8_t addr = 0;          ///< the 8-bit address
  std::uint8_t index = kNoIndex;  ///< the index register that modifies addr
  std::uint8_t reg = 0;           ///< the index register an index op names; Quantize's kind
  std::uint8_t other = 0;         ///< IndexCopy's and IndexAddMod's second register
  float literal = 0.0f;
};

/// 12-bit fixed point (L1340, L1348): the value a quantized word stands for.
float quantize(float v, QuantKind kind);

/// One T&C processor: its memory, accumulator, index registers and shutdown flag, and the words
/// it has sent its scan conversion processor.
class TcProcessor {
 public:
  std::array<float, kTcWords> memory{};
  float acc = 0.0f;
  std::array<int, kIndexRegisters> ix{};
  bool off = false;
  std::vector<float> sent;
  /// Instructions it executed (not ignored).
  std::uint64_t executed = 0;

  /// Hears one broadcast instruction.
  void execute(const Instruction& in);

 private:
  int address(const Instruction& in) const;
};

}  // namespace rtsim::scanline
