// mechgraph/large_arrays.hpp: large arrays reserved with the advice to back them by huge pages.
#include <mechgraph/large_arrays.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace mechgraph;

namespace {

// The flags /proc/self/smaps gives the mapping that holds `address` ("" when none is found).
std::string mapping_flags(const void* address) {
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t from = 0, to = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> from >> dash >> to && dash == '-' && line.find(' ') != std::string::npos) {
      inside = at >= from && at < to;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return {};
}

}  // namespace

TEST_CASE("Large arrays: reserved with the huge-page advice, contents as ever", "[core]") {
  // 8 MiB: advised. Where the kernel takes the advice (it has transparent huge pages), the mapping
  // that holds the array is marked "hg" (MADV_HUGEPAGE); the values are what was written, either way.
  std::vector<double> large;
  reserve_large(large, std::size_t{1} << 20);
  REQUIRE(large.capacity() >= std::size_t{1} << 20);
  large.assign(std::size_t{1} << 20, 0.5);
  CHECK(large[0] == 0.5);
  CHECK(large.back() == 0.5);
  const bool taken = advise_huge_pages(large.data(), large.size() * sizeof(double));  // again: the same advice
  const std::string flags = mapping_flags(large.data() + large.size() / 2);
  INFO(flags);
  if (taken) CHECK(flags.find(" hg") != std::string::npos);
  if (std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled")) CHECK(taken);  // this project's machines
  // 64 KiB: below large_array_bytes, not advised; a vector with elements keeps its contents.
  std::vector<int> small{1, 2, 3};
  reserve_large(small, 16384);
  CHECK(small.capacity() >= 16384);
  CHECK(small == std::vector<int>{1, 2, 3});
  // Whatever pointer and length: only the whole pages inside are advised, none outside; a length
  // of zero or less than a page is nothing.
  CHECK_FALSE(advise_huge_pages(large.data(), 0));
  CHECK_FALSE(advise_huge_pages(large.data() + 1, 100));
  CHECK_FALSE(advise_huge_pages(nullptr, 0));
  CHECK(large[1] == 0.5);
}
