#include "firmware/scanline/tc_program.hpp"

namespace rtsim::scanline {

namespace {

// --- Memory (L1272: the polygon's 27 words, 16 vertices of 7 words, a few dozen others) -------
namespace mem {
constexpr std::uint8_t kVx = 0, kVy = 4, kVz = 8;     // the 4 points (world)
constexpr std::uint8_t kNx = 12, kNy = 16, kNz = 20;  // the 4 normals (world)
constexpr std::uint8_t kCr = 24, kCg = 25, kCb = 26;  // the polygon's colour
// The 16 vertices after transformation (4, then 2 a clipping stage), a component an array.
constexpr std::uint8_t kX = 32, kY = 48, kZ = 64, kW = 80, kR = 96, kG = 112, kB = 128;
constexpr std::uint8_t kMatrix = 144;  // m[row][column] at kMatrix + 4 row + column
constexpr std::uint8_t kAmbient = 160, kPoint = 163, kDirection = 166;
constexpr std::uint8_t kList[2] = {170, 180};  // vertex lists of indices, 10 each
constexpr std::uint8_t kNu = 190;              // vertices in the input list
constexpr std::uint8_t kNc = 191;              // vertices in the output list
constexpr std::uint8_t kNv = 192;              // vertices stored (the next new one's index)
constexpr std::uint8_t kNs = 193;              // crossings noted
constexpr std::uint8_t kSi = 194, kSj = 196, kSn = 198;  // a crossing's ends and new vertex
constexpr std::uint8_t kT0 = 200, kT1 = 201, kT2 = 202, kT3 = 203, kT4 = 204;
constexpr std::uint8_t kZero = 210, kOne = 211, kTwo = 212, kThree = 213;
constexpr std::uint8_t kD = 214;                              // max(0, n.p)
constexpr std::uint8_t kT = 215;                              // the intersection's parameter
constexpr std::uint8_t kYTop = 216, kXTop = 217, kTop = 218;  // the top vertex so far
constexpr std::uint8_t kStepLeft = 219, kStepRight = 220;     // list steps down each chain
constexpr std::uint8_t kQ = 221;                              // 1 / quant(dy)
constexpr std::uint8_t kDone = 222, kChain = 223;
}  // namespace mem

// Index registers.
constexpr std::uint8_t kI = 0, kJ = 1, kK = 2, kL = 3, kR = 4, kN = 5;

/// Hand-compiling: one call an instruction, counted against the task being built.
class Assembler {
 public:
  explicit Assembler(BroadcastProgram& p) : p_(p) {}
  void task(TcTask t) { task_ = t; }

  void load(std::uint8_t a, std::uint8_t ix = kNoIndex) { emit(Op::Load, a, ix); }
  void store(std::uint8_t a, std::uint8_t ix = kNoIndex) { emit(Op::Store, a, ix); }
  void add(std::uint8_t a, std::uint8_t ix = kNoIndex) { emit(Op::Add, a, ix); }
  void sub(std::uint8_t a, std::uint8_t ix = kNoIndex) { emit(Op::Sub, a, ix); }
  void mul(std::uint8_t a, std::uint8_t ix = kNoIndex) { emit(Op::Mul, a, ix); }
  void div(std::uint8_t a, std::uint8_t ix = kNoIndex) { emit(Op::Div, a, ix); }
  void literal(float v) { emit(Op::Literal, 0, kNoIndex, 0, 0, v); }
  void store_literal(std::uint8_t a, float v) { emit(Op::StoreLiteral, a, kNoIndex, 0, 0, v); }
  void quantize(QuantKind k) { emit(Op::Quantize, 0, kNoIndex, static_cast<std::uint8_t>(k)); }
  void send() { emit(Op::Send, 0); }
  void index_literal(std::uint8_t r, int v) {
    emit(Op::IndexLiteral, 0, kNoIndex, r, 0, static_cast<float>(v));
  }
  void index_load(std::uint8_t r, std::uint8_t a, std::uint8_t ix = kNoIndex) {
    emit(Op::IndexLoad, a, ix, r);
  }
  void index_store(std::uint8_t r, std::uint8_t a, std::uint8_t ix = kNoIndex) {
    emit(Op::IndexStore, a, ix, r);
  }
  void index_copy(std::uint8_t r, std::uint8_t from) { emit(Op::IndexCopy, 0, kNoIndex, r, from); }
  void index_inc(std::uint8_t r) { emit(Op::IndexInc, 0, kNoIndex, r); }
  /// ix[r] := (ix[r] + ix[step]) mod m[count]
  void index_add_mod(std::uint8_t r, std::uint8_t step, std::uint8_t count) {
    emit(Op::IndexAddMod, count, kNoIndex, r, step);
  }
  void off_if(Op test, std::uint8_t a, std::uint8_t ix = kNoIndex) { emit(test, a, ix); }
  void off_if_index_at_least(std::uint8_t r, std::uint8_t a) {
    emit(Op::OffIfIndexAtLeast, a, kNoIndex, r);
  }
  void reset() { emit(Op::Reset, 0); }

 private:
  void emit(Op op, std::uint8_t a, std::uint8_t ix = kNoIndex, std::uint8_t reg = 0,
            std::uint8_t other = 0, float lit = 0.0f) {
    p_.code.push_back(Instruction{op, a, ix, reg, other, lit});
    ++p_.count[static_cast<std::size_t>(task_)];
  }
  BroadcastProgram& p_;
  TcTask task_ = TcTask::Transform;
};

const std::uint8_t kComponents[7] = {mem::kX, mem::kY, mem::kZ, mem::kW, mem::kR, mem::kG, mem::kB};

// Fig. 3-10, for the four vertices: a column of the matrix stored, then used four times.
void vertex_transformation(Assembler& a, const TcLiterals& lit) {
  const std::uint8_t out[4] = {mem::kX, mem::kY, mem::kZ, mem::kW};
  for (std::uint8_t c = 0; c < 4; ++c) {
    for (std::uint8_t r = 0; r < 4; ++r)
      a.store_literal(static_cast<std::uint8_t>(mem::kMatrix + 4 * r + c), lit.matrix[r][c]);
    const auto m = [&](int r) { return static_cast<std::uint8_t>(mem::kMatrix + 4 * r + c); };
    for (std::uint8_t v = 0; v < 4; ++v) {
      // x := x1 m11 + y1 m21 + z1 m31 + m41
      a.load(mem::kVx + v);
      a.mul(m(0));
      a.store(mem::kT0);
      a.load(mem::kVy + v);
      a.mul(m(1));
      a.add(mem::kT0);
      a.store(mem::kT0);
      a.load(mem::kVz + v);
      a.mul(m(2));
      a.add(mem::kT0);
      a.add(m(3));
      a.store(static_cast<std::uint8_t>(out[c] + v));
    }
  }
}

// Fig. 3-11 for the four vertices.
void colour_computation(Assembler& a, const TcLiterals& lit) {
  a.store_literal(mem::kZero, 0.0f);
  a.store_literal(mem::kOne, 1.0f);
  for (std::uint8_t k = 0; k < 3; ++k) {
    a.store_literal(mem::kAmbient + k, lit.ambient[k]);
    if (!lit.point_light) continue;
    a.store_literal(mem::kPoint + k, lit.point[k]);
    a.store_literal(mem::kDirection + k, lit.direction[k]);
  }
  const std::uint8_t colour[3] = {mem::kCr, mem::kCg, mem::kCb};
  const std::uint8_t out[3] = {mem::kR, mem::kG, mem::kB};
  for (std::uint8_t v = 0; v < 4; ++v) {
    if (!lit.point_light) {
      // No point source: r := a_r c_r, and g, b.
      for (std::uint8_t k = 0; k < 3; ++k) {
        a.load(mem::kAmbient + k);
        a.mul(colour[k]);
        a.store(static_cast<std::uint8_t>(out[k] + v));
      }
      continue;
    }
    // d := max(0, n.p): the sum, then 0 where it is negative (a shutdown block).
    a.load(mem::kNx + v);
    a.mul(mem::kDirection);
    a.store(mem::kT0);
    a.load(mem::kNy + v);
    a.mul(mem::kDirection + 1);
    a.add(mem::kT0);
    a.store(mem::kT0);
    a.load(mem::kNz + v);
    a.mul(mem::kDirection + 2);
    a.add(mem::kT0);
    a.store(mem::kD);
    a.off_if(Op::OffIfGreaterEqual, mem::kZero);
    a.store_literal(mem::kD, 0.0f);
    a.reset();
    // r := (a_r + p_r d) c_r, and g, b.
    for (std::uint8_t k = 0; k < 3; ++k) {
      a.load(mem::kPoint + k);
      a.mul(mem::kD);
      a.add(mem::kAmbient + k);
      a.mul(colour[k]);
      a.store(static_cast<std::uint8_t>(out[k] + v));
    }
  }
}

// The accumulator := the signed distance of vertex ix[reg] inside plane p (>= 0: visible):
/// w - x, w + x, w - y, w + y, z, w - z (L1005: -w <= x, y <= w, 0 <= z <= w).
void distance(Assembler& a, int plane, std::uint8_t reg) {
  switch (plane) {
    case 4:
      a.load(mem::kZ, reg);
      return;
    default: {
      static const std::uint8_t kAxis[6] = {mem::kX, mem::kX, mem::kY, mem::kY, 0, mem::kZ};
      a.load(mem::kW, reg);
      if (plane == 1 || plane == 3)
        a.add(kAxis[plane], reg);
      else
        a.sub(kAxis[plane], reg);
    }
  }
}

// Fig. 3-13 for one plane: note the crossings while copying indices, then intersect twice.
void clip_plane(Assembler& a, int plane) {
  const std::uint8_t in = mem::kList[plane % 2], out = mem::kList[(plane + 1) % 2];
  a.store_literal(mem::kNc, 0.0f);
  a.store_literal(mem::kNs, 0.0f);
  a.index_literal(kI, 0);  // the current vertex's place in the list
  a.index_load(kJ, mem::kNu);
  a.index_literal(kR, -1);
  a.index_add_mod(kJ, kR, mem::kNu);  // the previous one's: the last
  // Each stage may add a vertex (L1165): 4, 5, ... 9 to examine.
  for (int pass = 0; pass < 4 + plane; ++pass) {
    // The edge from j to i crosses the plane: note it, and its new vertex's place.
    a.off_if_index_at_least(kI, mem::kNu);
    a.index_load(kK, in, kJ);
    distance(a, plane, kK);
    a.store(mem::kT0);
    a.index_load(kL, in, kI);
    distance(a, plane, kL);
    a.mul(mem::kT0);
    a.off_if(Op::OffIfGreaterEqual, mem::kZero);
    a.index_load(kR, mem::kNs);
    a.index_store(kL, mem::kSi, kR);
    a.index_store(kK, mem::kSj, kR);
    a.load(mem::kNv);
    a.store(mem::kSn, kR);
    a.index_load(kR, mem::kNc);
    a.store(out, kR);
    a.add(mem::kOne);
    a.store(mem::kNv);
    a.load(mem::kNc);
    a.add(mem::kOne);
    a.store(mem::kNc);
    a.load(mem::kNs);
    a.add(mem::kOne);
    a.store(mem::kNs);
    a.reset();
    // The current vertex is visible: its index to the output list.
    a.off_if_index_at_least(kI, mem::kNu);
    a.index_load(kL, in, kI);
    distance(a, plane, kL);
    a.off_if(Op::OffIfLess, mem::kZero);
    a.index_load(kR, mem::kNc);
    a.index_store(kL, out, kR);
    a.load(mem::kNc);
    a.add(mem::kOne);
    a.store(mem::kNc);
    a.reset();
    a.index_copy(kJ, kI);
    a.index_inc(kI);
  }
  // A convex polygon crosses a plane at most twice (L1210).
  for (int pass = 0; pass < 2; ++pass) {
    a.load(mem::kNs);
    a.off_if(Op::OffIfLessEqual, mem::kZero);
    a.sub(mem::kOne);
    a.store(mem::kNs);
    a.index_load(kR, mem::kNs);
    a.index_load(kL, mem::kSi, kR);
    a.index_load(kK, mem::kSj, kR);
    a.index_load(kN, mem::kSn, kR);
    // t := d_j / (d_j - d_i); the new vertex := v_j + t (v_i - v_j), colour too.
    distance(a, plane, kK);
    a.store(mem::kT0);
    distance(a, plane, kL);
    a.store(mem::kT1);
    a.load(mem::kT0);
    a.sub(mem::kT1);
    a.store(mem::kT2);
    a.load(mem::kT0);
    a.div(mem::kT2);
    a.store(mem::kT);
    for (const std::uint8_t c : kComponents) {
      a.load(c, kL);
      a.sub(c, kK);
      a.mul(mem::kT);
      a.add(c, kK);
      a.store(c, kN);
    }
    a.reset();
  }
  a.load(mem::kNc);
  a.store(mem::kNu);
}

void clipping(Assembler& a) {
  a.store_literal(mem::kNu, 4.0f);
  a.store_literal(mem::kNv, 4.0f);
  for (std::uint8_t k = 0; k < 4; ++k) a.store_literal(mem::kList[0] + k, k);
  for (int plane = 0; plane < 6; ++plane) clip_plane(a, plane);
  // Fewer than 3 vertices left (a polygon touching the volume at a point or an edge): none.
  a.store_literal(mem::kThree, 3.0f);
  a.load(mem::kNu);
  a.off_if(Op::OffIfGreaterEqual, mem::kThree);
  a.store_literal(mem::kNu, 0.0f);
  a.reset();
}

// Fig. 3-14. After six planes the list is the first again.
void perspective_division(Assembler& a) {
  const std::uint8_t list = mem::kList[0];
  a.index_literal(kI, 0);
  for (int pass = 0; pass < 10; ++pass) {
    a.off_if_index_at_least(kI, mem::kNu);
    a.index_load(kK, list, kI);
    for (const std::uint8_t c : {mem::kX, mem::kY, mem::kZ}) {
      a.load(c, kK);
      a.div(mem::kW, kK);
      a.store(c, kK);
    }
    a.index_inc(kI);
  }
  a.reset();
}

// Fig. 3-15.
void scan_conversion_preprocessing(Assembler& a) {
  const std::uint8_t list = mem::kList[0];
  // The leftmost top vertex: the first the raster scan meets (y up the screen).
  a.index_literal(kI, 0);
  a.index_load(kK, list, kI);
  a.load(mem::kY, kK);
  a.store(mem::kYTop);
  a.load(mem::kX, kK);
  a.store(mem::kXTop);
  a.store_literal(mem::kTop, 0.0f);
  a.index_literal(kI, 1);
  for (int pass = 0; pass < 9; ++pass) {
    // As high, further left.
    a.off_if_index_at_least(kI, mem::kNu);
    a.index_load(kK, list, kI);
    a.load(mem::kY, kK);
    a.off_if(Op::OffIfNotEqual, mem::kYTop);
    a.load(mem::kX, kK);
    a.off_if(Op::OffIfGreaterEqual, mem::kXTop);
    a.store(mem::kXTop);
    a.index_store(kI, mem::kTop);
    a.reset();
    // Higher.
    a.off_if_index_at_least(kI, mem::kNu);
    a.index_load(kK, list, kI);
    a.load(mem::kY, kK);
    a.off_if(Op::OffIfLessEqual, mem::kYTop);
    a.store(mem::kYTop);
    a.load(mem::kX, kK);
    a.store(mem::kXTop);
    a.index_store(kI, mem::kTop);
    a.reset();
    a.index_inc(kI);
  }
  // The winding: the left chain leaves the top towards the next vertex in the list if
  // (v[t+1] - v[t]) x (v[t-1] - v[t]) > 0 (counter-clockwise on the screen), else the previous.
  a.index_load(kR, mem::kTop);
  a.index_copy(kJ, kR);
  a.index_literal(kN, -1);
  a.index_add_mod(kJ, kN, mem::kNu);  // t-
  a.index_copy(kL, kR);
  a.index_literal(kN, 1);
  a.index_add_mod(kL, kN, mem::kNu);  // t+
  a.index_load(kK, list, kR);
  a.index_load(kI, list, kL);
  a.index_load(kN, list, kJ);
  a.load(mem::kX, kI);
  a.sub(mem::kX, kK);
  a.store(mem::kT0);
  a.load(mem::kY, kI);
  a.sub(mem::kY, kK);
  a.store(mem::kT1);
  a.load(mem::kX, kN);
  a.sub(mem::kX, kK);
  a.store(mem::kT2);
  a.load(mem::kY, kN);
  a.sub(mem::kY, kK);
  a.mul(mem::kT0);
  a.store(mem::kT3);
  a.load(mem::kT1);
  a.mul(mem::kT2);
  a.store(mem::kT4);
  a.load(mem::kT3);
  a.sub(mem::kT4);
  a.store_literal(mem::kStepLeft, -1.0f);
  a.store_literal(mem::kStepRight, 1.0f);
  a.off_if(Op::OffIfLessEqual, mem::kZero);
  a.store_literal(mem::kStepLeft, 1.0f);
  a.store_literal(mem::kStepRight, -1.0f);
  a.reset();
  // Both chains, top to bottom, in one loop: at most 10 vertices, the top and the bottom twice.
  a.store_literal(mem::kTwo, 2.0f);
  a.store_literal(mem::kDone, 0.0f);
  a.store_literal(mem::kChain, 0.0f);
  a.index_load(kI, mem::kTop);
  a.index_load(kN, mem::kStepLeft);
  a.load(mem::kNu);  // nothing to send for no polygon
  a.off_if(Op::OffIfGreater, mem::kZero);
  a.store_literal(mem::kDone, 1.0f);
  a.reset();
  for (int pass = 0; pass < 12; ++pass) {
    // The vertex (k) and the next down the chain (l); dy between them, quantized.
    a.load(mem::kDone);
    a.off_if(Op::OffIfNotEqual, mem::kZero);
    a.index_load(kK, list, kI);
    a.index_copy(kJ, kI);
    a.index_add_mod(kJ, kN, mem::kNu);
    a.index_load(kL, list, kJ);
    a.load(mem::kY, kK);
    a.quantize(QuantKind::ScreenXY);
    a.store(mem::kT0);
    a.load(mem::kY, kL);
    a.quantize(QuantKind::ScreenXY);
    a.store(mem::kT1);
    a.load(mem::kT0);
    a.sub(mem::kT1);
    a.store(mem::kT2);
    a.store_literal(mem::kQ, 0.0f);
    a.reset();
    // q := 1 / quant(dy) where the next is lower.
    a.load(mem::kDone);
    a.off_if(Op::OffIfNotEqual, mem::kZero);
    a.load(mem::kT2);
    a.off_if(Op::OffIfLessEqual, mem::kZero);
    a.literal(1.0f);
    a.div(mem::kT2);
    a.store(mem::kQ);
    a.reset();
    // send y; x, dx; z, dz; r, dr; g, dg; b, db.
    a.load(mem::kDone);
    a.off_if(Op::OffIfNotEqual, mem::kZero);
    a.load(mem::kT0);
    a.send();
    const std::pair<std::uint8_t, QuantKind> fields[5] = {{mem::kX, QuantKind::ScreenXY},
                                                          {mem::kZ, QuantKind::Depth},
                                                          {mem::kR, QuantKind::Colour},
                                                          {mem::kG, QuantKind::Colour},
                                                          {mem::kB, QuantKind::Colour}};
    for (const auto& [field, kind] : fields) {
      a.load(field, kK);
      a.quantize(kind);
      a.store(mem::kT3);
      a.send();
      a.load(field, kL);
      a.quantize(kind);
      a.sub(mem::kT3);
      a.mul(mem::kQ);
      a.send();
    }
    a.reset();
    // The next is higher: this was the chain's bottom (a level edge is followed: at the top it
    // starts the right chain, at the bottom both chains take it, and a repeated vertex is a
    // level edge of no length). The right chain starts from the top again; after it, done.
    a.load(mem::kDone);
    a.off_if(Op::OffIfNotEqual, mem::kZero);
    a.load(mem::kT2);
    a.off_if(Op::OffIfGreaterEqual, mem::kZero);
    a.load(mem::kChain);
    a.add(mem::kOne);
    a.store(mem::kChain);
    a.index_load(kI, mem::kTop);
    a.index_load(kN, mem::kStepRight);
    a.off_if(Op::OffIfLess, mem::kTwo);
    a.store_literal(mem::kDone, 1.0f);
    a.reset();
    // Otherwise down the chain.
    a.load(mem::kDone);
    a.off_if(Op::OffIfNotEqual, mem::kZero);
    a.load(mem::kT2);
    a.off_if(Op::OffIfLess, mem::kZero);
    a.index_copy(kI, kJ);
    a.reset();
  }
}

}  // namespace

std::uint32_t BroadcastProgram::total() const {
  std::uint32_t n = 0;
  for (const auto c : count) n += c;
  return n;
}

BroadcastProgram build_tc_program(const TcLiterals& literals) {
  BroadcastProgram p;
  Assembler a(p);
  a.task(TcTask::Transform);
  vertex_transformation(a, literals);
  a.task(TcTask::Colour);
  colour_computation(a, literals);
  a.task(TcTask::Clipping);
  clipping(a);
  a.task(TcTask::Division);
  perspective_division(a);
  a.task(TcTask::Preprocessing);
  scan_conversion_preprocessing(a);
  return p;
}

void load_polygon(TcProcessor& p, const TcPolygon& polygon) {
  for (std::size_t v = 0; v < 4; ++v) {
    p.memory[mem::kVx + v] = static_cast<float>(polygon.vertex[v].x);
    p.memory[mem::kVy + v] = static_cast<float>(polygon.vertex[v].y);
    p.memory[mem::kVz + v] = static_cast<float>(polygon.vertex[v].z);
    p.memory[mem::kNx + v] = static_cast<float>(polygon.normal[v].x);
    p.memory[mem::kNy + v] = static_cast<float>(polygon.normal[v].y);
    p.memory[mem::kNz + v] = static_cast<float>(polygon.normal[v].z);
  }
  p.memory[mem::kCr] = static_cast<float>(polygon.colour.r);
  p.memory[mem::kCg] = static_cast<float>(polygon.colour.g);
  p.memory[mem::kCb] = static_cast<float>(polygon.colour.b);
}

void broadcast(const BroadcastProgram& program, std::vector<TcProcessor>& processors) {
  for (const Instruction& in : program.code)
    for (TcProcessor& p : processors) p.execute(in);
}

EdgeChains edge_chains(const std::vector<float>& sent) {
  EdgeChains out;
  std::vector<EdgeEntry>* chain = &out.left;
  for (std::size_t k = 0; k + kEdgeEntryWords <= sent.size(); k += kEdgeEntryWords) {
    const float* w = &sent[k];
    const EdgeEntry e{w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], w[8], w[9], w[10]};
    if (chain == &out.left && !out.left.empty() && e.y > out.left.back().y) chain = &out.right;
    chain->push_back(e);
  }
  return out;
}

}  // namespace rtsim::scanline
