#pragma once
// Eight xoshiro256++ engines side by side ("lanes"), stepped together in vector registers, and the
// normal, uniform and triangular variates of variates.hpp drawn eight at a time
// (docs/methods/backlash.md, "Monte Carlo sampler").
//
// The vectors are GCC's generic vector extension: eight 64-bit lanes, which the compiler maps on
// whatever the target has (one AVX-512 register; on baseline x86-64 four SSE2 registers' worth),
// so the same source gives the same bits everywhere: only integer operations and correctly
// rounded additions, subtractions and multiplications are used, and a comparison is the sign bit
// of a difference (exact for doubles; GCC takes vector comparisons lane by lane without AVX-512).
//
// Lane j starts where its first engine is advanced by j long jumps (2^192 steps), so the eight
// streams never overlap. The ziggurat's fast path (a strip's core: one draw, two table loads, a
// multiplication and a comparison) runs in all lanes at once; a lane whose draw misses its core
// (0.43 % of the draws) takes the scalar wedge or tail of variates.hpp on its own engine, so
// each lane's normals are exactly the scalar algorithm's.
#include "variates.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <utility>

namespace mechgraph::backlash {

inline constexpr int lanes = 8;

// 64-byte vectors passed between inlined functions only; GCC notes that their ABI would differ
// with and without AVX-512 for out-of-line calls, which these never are.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
typedef std::uint64_t LaneBits __attribute__((vector_size(64)));
typedef std::int64_t LaneMask __attribute__((vector_size(64)));  // flags, non-zero for true
inline constexpr std::uint64_t sign_bit = 0x8000000000000000ull;
typedef double LaneDoubles __attribute__((vector_size(64)));

[[gnu::always_inline]] inline LaneDoubles splat(double x) { return LaneDoubles{} + x; }

/// Whether any lane's flag is set (a tree of halvings: no lane-by-lane branch).
[[gnu::always_inline]] inline bool any(LaneMask m) {
  m |= __builtin_shufflevector(m, m, 4, 5, 6, 7, 0, 1, 2, 3);
  m |= __builtin_shufflevector(m, m, 2, 3, 0, 1, 6, 7, 4, 5);
  m |= __builtin_shufflevector(m, m, 1, 0, 3, 2, 5, 4, 7, 6);
  return m[0] != 0;
}

class LaneVariates {
 public:
  /// Lane j from `first` advanced by j long jumps.
  explicit LaneVariates(Xoshiro256 first) {
    for (int j = 0; j < lanes; ++j) {
      set_lane(j, first);
      first.long_jump();
    }
  }

  /// One xoshiro256++ step in every lane.
  [[gnu::always_inline]] LaneBits next() {
    const LaneBits sum = s0_ + s3_;
    const LaneBits result = ((sum << 23) | (sum >> 41)) + s0_;
    const LaneBits t = s1_ << 17;
    s2_ ^= s0_;
    s3_ ^= s1_;
    s1_ ^= s2_;
    s0_ ^= s3_;
    s2_ ^= t;
    s3_ = (s3_ << 45) | (s3_ >> 19);
    return result;
  }

  /// Uniforms on [-1, 1): the top 52 bits as the mantissa of a double in [2, 4), less 3.
  [[gnu::always_inline]] static LaneDoubles symmetric_uniform_of(LaneBits bits) {
    const LaneBits in_2_4 = (bits >> 12) | 0x4000000000000000ull;
    return std::bit_cast<LaneDoubles>(in_2_4) - 3.0;
  }
  [[gnu::always_inline]] LaneDoubles uniforms() { return symmetric_uniform_of(next()); }
  /// Tri(-1, 0, 1): half the difference of two uniforms, both from the same lane.
  [[gnu::always_inline]] LaneDoubles triangulars() {
    const LaneDoubles a = uniforms();
    return 0.5 * (a - uniforms());
  }

  /// Eight normal candidates: u x[i] of each lane's draw (`bits`), a standard normal in every lane
  /// whose draw fell inside its strip's core; `missed` 1 in the others (0 in these), for fix_normals.
  [[gnu::always_inline]] LaneDoubles normal_candidates(LaneBits& bits, LaneMask& missed) {
    bits = next();
    const LaneDoubles u = symmetric_uniform_of(bits);
    // Each lane's strip from the tables, the vectors put together in registers (a vector filled
    // lane by lane through memory would be read back before its stores could be forwarded).
    alignas(64) std::uint64_t strip[lanes];
    std::memcpy(strip, &bits, sizeof strip);
    const LaneDoubles strip_x = lookup(ziggurat_table.x.data(), strip);
    const LaneDoubles core_ratio = lookup(ziggurat_table.ratio.data(), strip);
    // missed = |u| >= ratio, from the sign of |u| - ratio (exact for a difference of doubles):
    // arithmetic on the bits, which every instruction set has for 64-bit lanes (a comparison of
    // eight doubles is taken lane by lane without AVX-512).
    const LaneDoubles magnitude = std::bit_cast<LaneDoubles>(std::bit_cast<LaneBits>(u) & ~sign_bit);
    missed = std::bit_cast<LaneMask>((std::bit_cast<LaneBits>(magnitude - core_ratio) >> 63) ^ 1u);  // 1 or 0
    return u * strip_x;
  }

  /// The slow path of `count` sets of candidates at once: in each lane, in the order of the sets,
  /// each candidate that missed its core (`missed`) replaced by ziggurat_outside_core on that
  /// lane's engine (the wedge, the tail, or a fresh normal); `missed_any` is their union. The fast
  /// draws of later sets were taken before these; every draw is still used once, so the variates
  /// stay independent.
  void fix_normals(LaneDoubles* z, const LaneBits* bits, const LaneMask* missed, const LaneMask& missed_any,
                   std::size_t count) {
    alignas(64) std::uint64_t state[4][lanes];
    alignas(64) std::int64_t lanes_missed[lanes];
    std::memcpy(state[0], &s0_, sizeof state[0]);
    std::memcpy(state[1], &s1_, sizeof state[1]);
    std::memcpy(state[2], &s2_, sizeof state[2]);
    std::memcpy(state[3], &s3_, sizeof state[3]);
    std::memcpy(lanes_missed, &missed_any, sizeof lanes_missed);
    outside_core(state, reinterpret_cast<double*>(z), reinterpret_cast<const std::uint64_t*>(bits),
                 reinterpret_cast<const std::int64_t*>(missed), lanes_missed, count);
    std::memcpy(&s0_, state[0], sizeof state[0]);
    std::memcpy(&s1_, state[1], sizeof state[1]);
    std::memcpy(&s2_, state[2], sizeof state[2]);
    std::memcpy(&s3_, state[3], sizeof state[3]);
  }

  /// Eight standard normals, lane j's from lane j's engine.
  [[gnu::always_inline]] LaneDoubles normals() {
    LaneBits bits;
    LaneMask missed;
    LaneDoubles z = normal_candidates(bits, missed);
    if (any(missed)) [[unlikely]] fix_normals(&z, &bits, &missed, missed, 1);
    return z;
  }

  Xoshiro256 lane(int j) const { return Xoshiro256::from_state({s0_[j], s1_[j], s2_[j], s3_[j]}); }

 private:
  void set_lane(int j, const Xoshiro256& e) {
    const auto s = e.state();
    s0_[j] = s[0];
    s1_[j] = s[1];
    s2_[j] = s[2];
    s3_[j] = s[3];
  }
  // The eight table entries of the lanes' strips, put together as a tree (pairs, quadruples, the
  // eight) so that the loads and insertions run side by side rather than one after another.
  [[gnu::always_inline]] static LaneDoubles lookup(const double* table, const std::uint64_t* strip) {
    typedef double Pair __attribute__((vector_size(16)));
    typedef double Quad __attribute__((vector_size(32)));
    constexpr std::uint64_t m = ZigguratTable::strip_mask;
    const Pair p0{table[strip[0] & m], table[strip[1] & m]}, p1{table[strip[2] & m], table[strip[3] & m]};
    const Pair p2{table[strip[4] & m], table[strip[5] & m]}, p3{table[strip[6] & m], table[strip[7] & m]};
    const Quad q0 = __builtin_shufflevector(p0, p1, 0, 1, 2, 3), q1 = __builtin_shufflevector(p2, p3, 0, 1, 2, 3);
    return __builtin_shufflevector(q0, q1, 0, 1, 2, 3, 4, 5, 6, 7);
  }

  // The candidates that missed their strip's core, lane by lane, each on its own engine.
  [[gnu::noinline]] static void outside_core(std::uint64_t (&state)[4][lanes], double* z, const std::uint64_t* bits,
                                             const std::int64_t* missed, const std::int64_t* lanes_missed, std::size_t count) {
    for (int j = 0; j < lanes; ++j) {
      if (!lanes_missed[j]) continue;
      Xoshiro256 e = Xoshiro256::from_state({state[0][j], state[1][j], state[2][j], state[3][j]});
      for (std::size_t k = 0; k < count; ++k)
        if (missed[k * lanes + j]) z[k * lanes + j] = ziggurat_outside_core(bits[k * lanes + j], e);
      const auto s = e.state();
      for (int i = 0; i < 4; ++i) state[i][j] = s[i];
    }
  }

  LaneBits s0_{}, s1_{}, s2_{}, s3_{};
};
#pragma GCC diagnostic pop

}  // namespace mechgraph::backlash
