#pragma once
// Random variates for Monte Carlo of tolerance stacks, fast and the same on every platform.
//
// The engine is xoshiro256++ (Blackman and Vigna, 2018): 256 bits of state, period 2^256 - 1, a
// few additions, shifts and rotations per 64-bit output; seeded through splitmix64 so that
// neighbouring seeds give unrelated streams. Normal variates come from a ziggurat (Marsaglia and
// Tsang, "The ziggurat method for generating random variables", 2000, in the double-precision form
// Doornik describes, 2005): 256 strips of equal area under the density, one 64-bit draw and one
// comparison in about 99 % of the calls. Uniform variates are the top 53 bits scaled; a triangular
// Tri(-1, 0, 1) variate is half the difference of two uniforms (the convolution of two boxes).
// Everything is fixed here, so a seed gives the same samples on every platform (the standard
// library's distributions are implementation-defined).
#include <array>
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
  double symmetric_uniform() { return top53((*this)()) * 0x1.0p-52 - 1.0; }
  /// The top 53 bits as a double (through a signed integer: the unsigned conversion branches).
  static double top53(std::uint64_t bits) { return static_cast<double>(static_cast<std::int64_t>(bits >> 11)); }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

/// The ziggurat's strips for the standard normal density f(x) = exp(-x^2/2) (unnormalised):
/// x[1] = r is where the tail starts, each strip [x[i+1], x[i]] x [f(x[i]), f(x[i+1])] plus the
/// base (the rectangle below f(r) out to x[0] = v / f(r), with the tail beyond r) has area v.
struct ZigguratTable {
  static constexpr int strips = 256;
  static constexpr double r = 3.6541528853610088;         // for 256 strips
  static constexpr double v = 0.00492867323399;            // each strip's area
  std::array<double, strips + 1> x{};
  std::array<double, strips> ratio{};                      // x[i+1] / x[i]: the strip's core
  ZigguratTable() {
    const double f_r = std::exp(-0.5 * r * r);
    x[0] = v / f_r;
    x[1] = r;
    for (int i = 2; i < strips; ++i) x[i] = std::sqrt(-2.0 * std::log(v / x[i - 1] + std::exp(-0.5 * x[i - 1] * x[i - 1])));
    x[strips] = 0.0;
    for (int i = 0; i < strips; ++i) ratio[i] = x[i + 1] / x[i];
  }
};

inline const ZigguratTable ziggurat_table;

/// Standard normal, uniform and triangular variates, one at a time or a block at a time.
class Variates {
 public:
  explicit Variates(std::uint64_t seed) : engine_(seed), second_(seed ^ 0xD1B54A32D192ED03ull) {}

  /// n standard normals. Two engines take turns so that their updates overlap, and a strip's core
  /// (about 99 % of the draws) is taken without a branch; the rest follow normal()'s wedge and
  /// tail, which keeps the distribution exact.
  void normals(double* out, std::size_t n) {
    std::size_t got = 0;
    while (got + 1 < n) {
      double x0, x1;
      const std::uint64_t b0 = engine_(), b1 = second_();
      const bool in0 = core(b0, x0), in1 = core(b1, x1);
      if (in0 && in1) {
        out[got] = x0;
        out[got + 1] = x1;
        got += 2;
        continue;
      }
      out[got++] = in0 ? x0 : outside_core(b0);
      out[got++] = in1 ? x1 : outside_core(b1);
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

  double normal() {
    while (true) {
      const std::uint64_t bits = engine_();
      double x;
      if (core(bits, x)) return x;
      if (const auto v = wedge_or_tail(bits)) return *v;
    }
  }
  double uniform() { return engine_.symmetric_uniform(); }                                   // U(-1, 1)
  double triangular() { return 0.5 * (engine_.symmetric_uniform() - engine_.symmetric_uniform()); }  // Tri(-1, 0, 1)

 private:
  // The strip (low 8 bits) and a uniform u in (-1, 1) (top 53 bits) of one draw; x = u x[i] is
  // taken at once when |u| is inside the strip's core.
  static bool core(std::uint64_t bits, double& x) {
    const int i = static_cast<int>(bits & 0xFF);
    const double u = Xoshiro256::top53(bits) * 0x1.0p-52 - 1.0;
    x = u * ziggurat_table.x[i];
    return std::abs(u) < ziggurat_table.ratio[i];
  }
  // A draw outside its strip's core: the wedge or tail test, else a fresh normal (a restart of the
  // algorithm, so the distribution stays exact).
  double outside_core(std::uint64_t bits) {
    if (const auto v = wedge_or_tail(bits)) return *v;
    return normal();
  }
  std::optional<double> wedge_or_tail(std::uint64_t bits) {
    const int i = static_cast<int>(bits & 0xFF);
    const double u = Xoshiro256::top53(bits) * 0x1.0p-52 - 1.0;
    if (i == 0) {
      // The tail beyond r (Marsaglia 1964): x = -ln(U1) / r, accepted when -2 ln(U2) > x^2.
      double t, y;
      do {
        t = -std::log(unit_open()) / ZigguratTable::r;
        y = -std::log(unit_open());
      } while (y + y < t * t);
      return u > 0.0 ? ZigguratTable::r + t : -(ZigguratTable::r + t);
    }
    // In the wedge between the core and the density: accept under the curve.
    const double x = u * ziggurat_table.x[i];
    const double f0 = std::exp(-0.5 * (ziggurat_table.x[i] * ziggurat_table.x[i] - x * x));
    const double f1 = std::exp(-0.5 * (ziggurat_table.x[i + 1] * ziggurat_table.x[i + 1] - x * x));
    if (f1 + unit_open() * (f0 - f1) < 1.0) return x;
    return std::nullopt;
  }
  double unit_open() { return (Xoshiro256::top53(engine_()) + 0.5) * 0x1.0p-53; }  // (0, 1)
  Xoshiro256 engine_, second_;
};

}  // namespace mechgraph::backlash
