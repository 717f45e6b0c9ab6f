// Hasher (core/src/hash.cpp): FNV-1a 64 over bytes, a string after its length. A text hashed from
// its parts (add_joined) is the text hashed whole: the sweep's fingerprint of a cases file's
// "CELL UNIT" must not move with how the text is kept.
#include <mechgraph/hash.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <string>

using namespace mechgraph;

namespace {

// FNV-1a 64 written out (Fowler, Noll, Vo): offset basis 0xcbf29ce484222325, prime 0x100000001b3.
std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

// What add(text) hashes: the length as 8 bytes in memory order, then the text.
std::string with_length(const std::string& text) {
  const std::uint64_t n = text.size();
  std::string bytes(sizeof n, '\0');
  std::memcpy(bytes.data(), &n, sizeof n);
  return bytes + text;
}

}  // namespace

TEST_CASE("Hasher: FNV-1a 64 of a string after its length, against the algorithm written out", "[core][hash]") {
  CHECK(fnv1a("a") == 0xaf63dc4c8601ec8cULL);  // the published vector of the reference written out
  for (const std::string text : {"", "a", "8.883708691782472 mm", "abc"}) {
    INFO(text);
    CHECK(Hasher().add(std::string_view(text)).value() == fnv1a(with_length(text)));
  }
}

TEST_CASE("Hasher: a text hashed from its parts is the text hashed whole", "[core][hash]") {
  CHECK(Hasher().add_joined({"8.883708691782472", " ", "mm"}).value() == Hasher().add(std::string_view("8.883708691782472 mm")).value());
  CHECK(Hasher().add_joined({"", "x", ""}).value() == Hasher().add(std::string_view("x")).value());
  CHECK(Hasher().add_joined({}).value() == Hasher().add(std::string_view("")).value());
  // The length comes first: "ab" + "c" as one text is not "a" then "bc" as two.
  CHECK(Hasher().add_joined({"ab", "c"}).value() != Hasher().add(std::string_view("a")).add(std::string_view("bc")).value());
}
