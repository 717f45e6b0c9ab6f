#include <mechgraph/hash.hpp>

#include <cstring>

namespace mechgraph {

Hasher& Hasher::add_bytes(const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    state_ ^= p[i];
    state_ *= 0x100000001b3ULL;
  }
  return *this;
}

Hasher& Hasher::add(std::string_view bytes) {
  add(static_cast<std::uint64_t>(bytes.size()));  // length prefix: "ab"+"c" differs from "a"+"bc"
  return add_bytes(bytes.data(), bytes.size());
}

Hasher& Hasher::add_joined(std::initializer_list<std::string_view> parts) {
  std::size_t size = 0;
  for (const std::string_view part : parts) size += part.size();
  add(static_cast<std::uint64_t>(size));
  for (const std::string_view part : parts) add_bytes(part.data(), part.size());
  return *this;
}

Hasher& Hasher::add(double v) {
  if (v == 0.0) v = 0.0;
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return add(bits);
}

Hasher& Hasher::add(std::uint64_t v) { return add_bytes(&v, sizeof v); }

}  // namespace mechgraph
