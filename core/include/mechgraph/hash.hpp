#pragma once
// 64-bit FNV-1a hashing for memoisation keys: deterministic across runs and machines, so a
// cached result can be recognised in a sweep (and later in a cache on disk).
#include <cstdint>
#include <initializer_list>
#include <string_view>

namespace mechgraph {

class Hasher {
 public:
  Hasher& add(std::string_view bytes);
  /// The parts one after another, hashed as add() hashes them made into one string.
  Hasher& add_joined(std::initializer_list<std::string_view> parts);
  Hasher& add(double v);  // -0.0 is hashed as 0.0
  Hasher& add(std::uint64_t v);
  std::uint64_t value() const { return state_; }

 private:
  Hasher& add_bytes(const void* data, std::size_t n);
  std::uint64_t state_ = 0xcbf29ce484222325ULL;
};

}  // namespace mechgraph
