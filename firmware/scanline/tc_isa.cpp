#include "firmware/scanline/tc_isa.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::scanline {

namespace {
/// A word read as a whole number (an index or a count), bounded so nothing wraps.
int whole(float v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int>(std::lround(std::clamp(v, -1024.0f, 1024.0f)));
}
}  // namespace

float quantize(float v, QuantKind kind) {
  if (!std::isfinite(v)) v = 0.0f;
  // 12 bits: x and y signed over [-1, 1] (2048 steps a unit), depth and colour over [0, 1].
  switch (kind) {
    case QuantKind::ScreenXY:
      return std::clamp(std::round(v * 2048.0f), -2048.0f, 2047.0f) / 2048.0f;
    case QuantKind::Depth:
    case QuantKind::Colour:
      return std::clamp(std::round(v * 4095.0f), 0.0f, 4095.0f) / 4095.0f;
  }
  return v;
}

int TcProcessor::address(const Instruction& in) const {
  const int base = in.addr;
  const int offset = in.index == kNoIndex ? 0 : ix[in.index % kIndexRegisters];
  // The address arithmetic of an 8-bit address: it wraps.
  return ((base + offset) % kTcWords + kTcWords) % kTcWords;
}

void TcProcessor::execute(const Instruction& in) {
  if (in.op == Op::Reset) {
    off = false;
    return;
  }
  if (off) return;
  ++executed;
  const auto m = [&]() -> float& { return memory[static_cast<std::size_t>(address(in))]; };
  int& r = ix[in.reg % kIndexRegisters];
  switch (in.op) {
    case Op::Load:
      acc = m();
      break;
    case Op::Store:
      m() = acc;
      break;
    case Op::Add:
      acc += m();
      break;
    case Op::Sub:
      acc -= m();
      break;
    case Op::Mul:
      acc *= m();
      break;
    case Op::Div: {
      const float d = m();
      acc = d != 0.0f ? acc / d : 0.0f;  // the programs never divide by zero; a fault might
      break;
    }
    case Op::Literal:
      acc = in.literal;
      break;
    case Op::StoreLiteral:
      m() = in.literal;
      break;
    case Op::Quantize:
      acc = quantize(acc, static_cast<QuantKind>(in.reg));
      break;
    case Op::Send:
      sent.push_back(acc);
      break;
    case Op::IndexLiteral:
      r = whole(in.literal);
      break;
    case Op::IndexLoad:
      r = whole(m());
      break;
    case Op::IndexStore:
      m() = static_cast<float>(r);
      break;
    case Op::IndexCopy:
      r = ix[in.other % kIndexRegisters];
      break;
    case Op::IndexInc:
      ++r;
      break;
    case Op::IndexAddMod: {
      const int n = whole(m());
      r = n > 0 ? ((r + ix[in.other % kIndexRegisters]) % n + n) % n : 0;
      break;
    }
    case Op::OffIfLess:
      off = acc < m();
      break;
    case Op::OffIfLessEqual:
      off = acc <= m();
      break;
    case Op::OffIfGreater:
      off = acc > m();
      break;
    case Op::OffIfGreaterEqual:
      off = acc >= m();
      break;
    case Op::OffIfEqual:
      off = acc == m();
      break;
    case Op::OffIfNotEqual:
      off = acc != m();
      break;
    case Op::OffIfIndexAtLeast:
      off = static_cast<float>(r) >= m();
      break;
    case Op::Reset:
      break;
  }
  if (!std::isfinite(acc)) acc = 0.0f;
}

}  // namespace rtsim::scanline
