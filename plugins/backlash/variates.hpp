#pragma once
// Random variates for Monte Carlo of tolerance stacks, fast and the same on every platform.
//
// The engine is xoshiro256++ (Blackman and Vigna, 2018): 256 bits of state, period 2^256 - 1, a
// few additions, shifts and rotations per 64-bit output; seeded through splitmix64 so that
// neighbouring seeds give unrelated streams. Its update is linear over GF(2), so advancing it by
// 2^128 steps (jump) or 2^192 steps (long_jump) is a fixed polynomial in the update applied to the
// state: that cuts one seed's sequence into streams that never overlap (lanes, chunks of samples).
// Normal variates come from a ziggurat (Marsaglia and Tsang, "The ziggurat method for generating
// random variables", 2000, in the double-precision form Doornik describes, 2005): 1024 strips of
// equal area under the density, one 64-bit draw and one comparison in 99.6 % of the calls.
// Uniform variates take the top 52 bits of a draw as the mantissa of a double in [2, 4) (an exact
// conversion without an integer-to-float instruction, so that it vectorises), less 3; a
// triangular Tri(-1, 0, 1) variate is half the difference of two uniforms (the convolution of two
// boxes). Everything is fixed here, so a seed gives the same samples on every platform (the
// standard library's distributions are implementation-defined). docs/methods/backlash.md,
// "Monte Carlo sampler".
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace mechgraph::backlash {

class Xoshiro256 {
 public:
  using result_type = std::uint64_t;
  explicit Xoshiro256(std::uint64_t seed) {
    for (std::uint64_t& s : state_) {  // splitmix64 fills the state
      seed += 0x9E3779B97F4A7C15ull;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      s = z ^ (z >> 31);
    }
  }
  /// The engine in a given state (not all zero).
  static Xoshiro256 from_state(const std::array<std::uint64_t, 4>& state) {
    Xoshiro256 e(0);
    for (int i = 0; i < 4; ++i) e.state_[i] = state[i];
    return e;
  }
  std::array<std::uint64_t, 4> state() const { return {state_[0], state_[1], state_[2], state_[3]}; }
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }
  result_type operator()() {
    const std::uint64_t result = rotl(state_[0] + state_[3], 23) + state_[0];
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }
  /// Uniform on [-1, 1).
  double symmetric_uniform() { return symmetric_uniform_of((*this)()); }
  /// The top 52 bits of a draw as a uniform on [-1, 1) in steps of 2^-51: they are the mantissa of
  /// a double in [2, 4) (exponent 0x400), from which 3 is subtracted exactly.
  static double symmetric_uniform_of(std::uint64_t bits) {
    return std::bit_cast<double>((bits >> 12) | 0x4000000000000000ull) - 3.0;
  }
  /// The top 53 bits as a double (through a signed integer: the unsigned conversion branches).
  static double top53(std::uint64_t bits) { return static_cast<double>(static_cast<std::int64_t>(bits >> 11)); }

  /// Advances the engine by 2^128 steps: the state becomes J(T) s, J the jump polynomial of the
  /// update T (its coefficients, lowest first, in `jump_polynomial`), evaluated by Horner's rule
  /// as a sum of the states met while stepping 256 times.
  void jump() { advance_by(jump_polynomial); }
  /// Advances the engine by 2^192 steps.
  void long_jump() { advance_by(long_jump_polynomial); }
  static constexpr std::array<std::uint64_t, 4> jump_polynomial{0x180EC6D33CFD0ABAull, 0xD5A61266F0C9392Cull,
                                                               0xA9582618E03FC9AAull, 0x39ABDC4529B1661Cull};
  static constexpr std::array<std::uint64_t, 4> long_jump_polynomial{0x76E15D3EFEFDCBBFull, 0xC5004E441C522FB3ull,
                                                                    0x77710069854EE241ull, 0x39109BB02ACBE635ull};

 private:
  void advance_by(const std::array<std::uint64_t, 4>& polynomial) {
    std::uint64_t sum[4] = {0, 0, 0, 0};
    for (const std::uint64_t word : polynomial)
      for (int bit = 0; bit < 64; ++bit) {
        const std::uint64_t take = 0 - ((word >> bit) & 1u);  // all ones when the coefficient is 1
        for (int i = 0; i < 4; ++i) sum[i] ^= state_[i] & take;
        (*this)();
      }
    for (int i = 0; i < 4; ++i) state_[i] = sum[i];
  }
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

/// The ziggurat's strips for the standard normal density f(x) = exp(-x^2/2) (unnormalised):
/// x[1] = r is where the tail starts, each strip [x[i+1], x[i]] x [f(x[i]), f(x[i+1])] plus the
/// base (the rectangle below f(r) out to x[0] = v / f(r), with the tail beyond r) has area v,
/// v = r f(r) + integral_r^inf f = r f(r) + sqrt(pi/2) erfc(r/sqrt(2)). With 1024 strips (8 %
/// of them left to the slow path at 256 strips: 1.5 % of the draws; here 0.43 %) r is the root,
/// found by bisection, that makes the top strip [0, x[1023]] close with area v (to 2e-15).
struct ZigguratTable {
  static constexpr int strips = 1024;
  static constexpr std::uint64_t strip_mask = strips - 1;  // the strip from the low 10 bits of a draw
  static constexpr double r = 4.038849846109504;
  static constexpr double v = 0.0012263246463530893;
  std::array<double, strips + 1> x{};
  std::array<double, strips> ratio{};    // x[i+1] / x[i]: the strip's core
  std::array<double, strips + 1> f{};    // f(x[i])
  ZigguratTable() {
    const double f_r = std::exp(-0.5 * r * r);
    x[0] = v / f_r;
    x[1] = r;
    for (int i = 2; i < strips; ++i) x[i] = std::sqrt(-2.0 * std::log(v / x[i - 1] + std::exp(-0.5 * x[i - 1] * x[i - 1])));
    x[strips] = 0.0;
    for (int i = 0; i < strips; ++i) ratio[i] = x[i + 1] / x[i];
    for (int i = 0; i <= strips; ++i) f[i] = std::exp(-0.5 * x[i] * x[i]);
  }
};

inline const ZigguratTable ziggurat_table;

/// The ziggurat's fast path on one draw: the strip i (low 10 bits) and u in [-1, 1) (top 52 bits);
/// x = u x[i] is a normal variate at once when |u| < x[i+1]/x[i] (inside the strip's core).
inline bool ziggurat_core(std::uint64_t bits, double& x) {
  const int i = static_cast<int>(bits & ZigguratTable::strip_mask);
  const double u = Xoshiro256::symmetric_uniform_of(bits);
  x = u * ziggurat_table.x[i];
  return std::abs(u) < ziggurat_table.ratio[i];
}

/// A uniform on (0, 1) from the engine.
inline double unit_open(Xoshiro256& engine) { return (Xoshiro256::top53(engine()) + 0.5) * 0x1.0p-53; }

/// The ziggurat's slow path for a draw outside its strip's core: the tail (strip 0) or the wedge
/// between the core and the density, drawing what it needs from `engine`; nothing when the
/// point falls above the density (the caller then starts again with a fresh draw).
inline std::optional<double> ziggurat_wedge_or_tail(std::uint64_t bits, Xoshiro256& engine) {
  const int i = static_cast<int>(bits & ZigguratTable::strip_mask);
  const double u = Xoshiro256::symmetric_uniform_of(bits);
  if (i == 0) {
    // The tail beyond r (Marsaglia 1964): x = -ln(U1) / r, accepted when -2 ln(U2) > x^2.
    double t, y;
    do {
      t = -std::log(unit_open(engine)) / ZigguratTable::r;
      y = -std::log(unit_open(engine));
    } while (y + y < t * t);
    return u > 0.0 ? ZigguratTable::r + t : -(ZigguratTable::r + t);
  }
  // In the wedge between the core and the density: a point uniform in height over the strip,
  // f(x[i]) .. f(x[i+1]), accepted under the curve.
  const double x = u * ziggurat_table.x[i];
  const double f0 = ziggurat_table.f[i], f1 = ziggurat_table.f[i + 1];
  if (f0 + unit_open(engine) * (f1 - f0) < std::exp(-0.5 * x * x)) return x;
  return std::nullopt;
}

/// A standard normal from `engine`.
inline double ziggurat_normal(Xoshiro256& engine) {
  while (true) {
    const std::uint64_t bits = engine();
    double x;
    if (ziggurat_core(bits, x)) return x;
    if (const auto v = ziggurat_wedge_or_tail(bits, engine)) return *v;
  }
}

/// The normal variate of a draw that missed its strip's core: the wedge or tail test, else a fresh
/// normal (a restart of the algorithm, so the distribution stays exact).
inline double ziggurat_outside_core(std::uint64_t bits, Xoshiro256& engine) {
  if (const auto v = ziggurat_wedge_or_tail(bits, engine)) return *v;
  return ziggurat_normal(engine);
}

/// Standard normal, uniform and triangular variates, one at a time or a block at a time, from one
/// engine (and a second one for the blocks). The Monte Carlo of the stacks draws eight engines at
/// once instead (lane_variates.hpp); this is the scalar reference.
class Variates {
 public:
  explicit Variates(std::uint64_t seed) : engine_(seed), second_(seed ^ 0xD1B54A32D192ED03ull) {}

  /// n standard normals. Two engines take turns so that their updates overlap, and a strip's core
  /// (99.6 % of the draws) is taken without a branch; the rest follow the wedge and tail,
  /// which keeps the distribution exact.
  void normals(double* out, std::size_t n) {
    std::size_t got = 0;
    while (got + 1 < n) {
      double x0, x1;
      const std::uint64_t b0 = engine_(), b1 = second_();
      const bool in0 = ziggurat_core(b0, x0), in1 = ziggurat_core(b1, x1);
      if (in0 && in1) {
        out[got] = x0;
        out[got + 1] = x1;
        got += 2;
        continue;
      }
      out[got++] = in0 ? x0 : ziggurat_outside_core(b0, engine_);
      out[got++] = in1 ? x1 : ziggurat_outside_core(b1, second_);
    }
    if (got < n) out[got] = normal();
  }
  /// n uniforms on [-1, 1) and n triangular Tri(-1, 0, 1) variates.
  void uniforms(double* out, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) out[i] = engine_.symmetric_uniform();
  }
  void triangulars(double* out, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) out[i] = 0.5 * (engine_.symmetric_uniform() - second_.symmetric_uniform());
  }

  double normal() { return ziggurat_normal(engine_); }
  double uniform() { return engine_.symmetric_uniform(); }                                   // U(-1, 1)
  double triangular() { return 0.5 * (engine_.symmetric_uniform() - engine_.symmetric_uniform()); }  // Tri(-1, 0, 1)

 private:
  Xoshiro256 engine_, second_;
};

}  // namespace mechgraph::backlash
