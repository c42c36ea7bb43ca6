#pragma once
// PixelFlow's SIMD instruction stream (seed 004 L3-L13, L61, L69-L71): a shading node's RISC GP
// runs the shader's C++ and issues SIMD instructions that every pixel processor executes at once
// ("IGCStream", L69: C++ inline functions that emit SIMD code). One instruction takes Fig. 6's
// time (L5-L11) whatever the number of pixels enabled, so what a shading part costs is the
// instructions it issues, by operation and by how the operands are held: 2-byte short, 4-byte
// long or 4-byte float, plus the conversions between float and long (L13).
//
// A Stream records those instructions. A Lane<R> is a varying value (one per pixel processor,
// held as R); arithmetic on lanes issues one instruction for all pixels. A Uniform is a value
// the GP holds (L61: uniform expressions run on the GP), free to compute; combining it with a
// lane costs the lane's instruction. Lanes carry no data: the image's arithmetic is the shading
// code's own (deferred_shader.cpp); the stream times it.
//
// What Fig. 6 does not price is free here (an assumption, docs/assumptions.md): moves and
// stores under the enable mask (SIMD's if/else, L31), comparisons beyond their subtraction,
// widening a short to a long and narrowing back (fixed-point shifts), and table reads (priced
// per lookup by the node, L148).
#include <array>
#include <cstdint>
#include <string_view>

namespace rtsim::deferred::simd {

/// Fig. 6's columns: how a value is held in a pixel processor's memory.
enum class Repr : std::uint8_t { Short, Long, Float };
inline constexpr int kReprs = 3;
inline constexpr std::array<std::string_view, kReprs> kReprNames = {"short", "long", "float"};

/// Fig. 6's rows.
enum class Arith : std::uint8_t { Add, Mul, Div, Sqrt };
inline constexpr int kAriths = 4;
inline constexpr std::array<std::string_view, kAriths> kArithNames = {"add", "mul", "div", "sqrt"};

/// Instructions issued, by operation and operand width.
struct InstructionMix {
  std::array<std::array<std::uint32_t, kReprs>, kAriths> ops{};
  std::uint32_t float_to_long = 0;
  std::uint32_t long_to_float = 0;

  std::uint32_t& at(Arith a, Repr r) {
    return ops[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)];
  }
  std::uint32_t at(Arith a, Repr r) const {
    return ops[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)];
  }
  std::uint32_t total() const;
  InstructionMix& operator+=(const InstructionMix& o);
  bool operator==(const InstructionMix& o) const = default;
};

/// Seconds one SIMD instruction takes (all pixel processors at once, L3).
struct InstructionTimes {
  std::array<std::array<double, kReprs>, kAriths> seconds{};
  double float_to_long = 0.0;
  double long_to_float = 0.0;

  double& at(Arith a, Repr r) {
    return seconds[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)];
  }
  double at(Arith a, Repr r) const {
    return seconds[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)];
  }
  /// Seconds the instructions of `mix` take, one after another.
  double time_of(const InstructionMix& mix) const;
};

class Stream;

/// A varying value held as R in every pixel processor.
template <Repr R>
class Lane {
 public:
  explicit Lane(Stream& s) : stream_(&s) {}
  Stream& stream() const { return *stream_; }

 private:
  Stream* stream_;
};

/// A value the GP holds: the same for every pixel.
struct Uniform {};

/// A vector of three lanes (a normal, a direction, a colour, a position).
template <Repr R>
struct Vec {
  Lane<R> x, y, z;
};

class Stream {
 public:
  /// A value already in the pixel processors' memory: an appearance parameter (Fig. 8) or what
  /// an earlier part left there.
  template <Repr R>
  Lane<R> in() {
    return Lane<R>(*this);
  }
  template <Repr R>
  Vec<R> in_vec() {
    return {in<R>(), in<R>(), in<R>()};
  }
  void issue(Arith a, Repr r, std::uint32_t n = 1) { mix_.at(a, r) += n; }
  void issue_float_to_long() { ++mix_.float_to_long; }
  void issue_long_to_float() { ++mix_.long_to_float; }
  const InstructionMix& mix() const { return mix_; }

 private:
  InstructionMix mix_;
};

// --- Arithmetic: one instruction each ------------------------------------------------------
template <Repr R>
Lane<R> operator+(Lane<R> a, Lane<R>) {
  a.stream().issue(Arith::Add, R);
  return a;
}
template <Repr R>
Lane<R> operator-(Lane<R> a, Lane<R>) {
  a.stream().issue(Arith::Add, R);
  return a;
}
template <Repr R>
Lane<R> operator*(Lane<R> a, Lane<R>) {
  a.stream().issue(Arith::Mul, R);
  return a;
}
template <Repr R>
Lane<R> operator/(Lane<R> a, Lane<R>) {
  a.stream().issue(Arith::Div, R);
  return a;
}
template <Repr R>
Lane<R> operator+(Lane<R> a, Uniform) {
  a.stream().issue(Arith::Add, R);
  return a;
}
template <Repr R>
Lane<R> operator-(Uniform, Lane<R> a) {
  a.stream().issue(Arith::Add, R);
  return a;
}
template <Repr R>
Lane<R> operator-(Lane<R> a, Uniform) {
  a.stream().issue(Arith::Add, R);
  return a;
}
template <Repr R>
Lane<R> operator*(Lane<R> a, Uniform) {
  a.stream().issue(Arith::Mul, R);
  return a;
}
template <Repr R>
Lane<R> operator*(Uniform, Lane<R> a) {
  return a * Uniform{};
}
/// A uniform over a lane (a reciprocal).
template <Repr R>
Lane<R> operator/(Uniform, Lane<R> a) {
  a.stream().issue(Arith::Div, R);
  return a;
}
template <Repr R>
Lane<R> sqrt(Lane<R> a) {
  a.stream().issue(Arith::Sqrt, R);
  return a;
}
/// A comparison: its subtraction; the result sets the enable mask (free).
template <Repr R>
Lane<R> less(Lane<R> a, Lane<R>) {
  a.stream().issue(Arith::Add, R);
  return a;
}
template <Repr R>
Lane<R> less(Lane<R> a, Uniform) {
  a.stream().issue(Arith::Add, R);
  return a;
}
/// A value kept where the mask is set, another elsewhere: stores under the mask (free).
template <Repr R>
Lane<R> select(Lane<R>, Lane<R> a, Lane<R>) {
  return a;
}

// --- Changes of representation (L13) --------------------------------------------------------
inline Lane<Repr::Long> to_long(Lane<Repr::Float> a) {
  a.stream().issue_float_to_long();
  return Lane<Repr::Long>(a.stream());
}
inline Lane<Repr::Float> to_float(Lane<Repr::Long> a) {
  a.stream().issue_long_to_float();
  return Lane<Repr::Float>(a.stream());
}
/// A fixed-point shift between a short and a long (free).
inline Lane<Repr::Long> widen(Lane<Repr::Short> a) { return Lane<Repr::Long>(a.stream()); }
inline Lane<Repr::Short> narrow(Lane<Repr::Long> a) { return Lane<Repr::Short>(a.stream()); }
inline Vec<Repr::Short> narrow(const Vec<Repr::Long>& v) {
  return {narrow(v.x), narrow(v.y), narrow(v.z)};
}

// --- Vectors -------------------------------------------------------------------------------
template <Repr R>
Vec<R> operator+(const Vec<R>& a, const Vec<R>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <Repr R>
Vec<R> operator-(const Vec<R>& a, const Vec<R>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
/// A vector less (or plus) a uniform one (a light's position, an eye's).
template <Repr R>
Vec<R> operator-(Uniform, const Vec<R>& a) {
  return {Uniform{} - a.x, Uniform{} - a.y, Uniform{} - a.z};
}
template <Repr R>
Vec<R> operator*(const Vec<R>& a, Lane<R> s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <Repr R>
Vec<R> operator*(const Vec<R>& a, Uniform) {
  return {a.x * Uniform{}, a.y * Uniform{}, a.z * Uniform{}};
}
template <Repr R>
Vec<R> operator*(const Vec<R>& a, const Vec<R>& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <Repr R>
Lane<R> dot(const Vec<R>& a, const Vec<R>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
/// A dot product with a uniform vector (a row of a matrix the GP holds).
template <Repr R>
Lane<R> dot(const Vec<R>& a, Uniform) {
  return a.x * Uniform{} + a.y * Uniform{} + a.z * Uniform{};
}
template <Repr R>
Vec<R> cross(const Vec<R>& a, const Vec<R>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <Repr R>
Lane<R> length(const Vec<R>& a) {
  return sqrt(dot(a, a));
}
/// a / |a|: one division for the reciprocal, a multiplication a component.
template <Repr R>
Vec<R> normalize(const Vec<R>& a) {
  const Lane<R> inv = Uniform{} / length(a);
  return a * inv;
}
/// x^n for a uniform exponent n >= 1, by repeated squaring.
template <Repr R>
Lane<R> pow(Lane<R> x, double n) {
  auto e = static_cast<std::uint32_t>(n < 1.0 ? 1.0 : n + 0.5);
  Lane<R> result = x;
  bool first = true;
  while (e > 0) {
    if (e & 1u) {
      if (!first) result = result * x;
      first = false;
    }
    e >>= 1u;
    if (e > 0) x = x * x;
  }
  return result;
}
/// a + t (b - a), a component.
template <Repr R>
Lane<R> lerp(Lane<R> a, Lane<R> b, Lane<R> t) {
  return a + (b - a) * t;
}

}  // namespace rtsim::deferred::simd
