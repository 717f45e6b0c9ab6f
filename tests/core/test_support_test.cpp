// Definitions the test helpers need from the ABI header (kept out of the shared header so that
// only one translation unit includes Boost.DLL's alias machinery).
#include "test_support.hpp"

#include <mechgraph/plugin_abi.hpp>

#include <catch2/catch.hpp>

namespace mechgraph::testing {
std::string build_fingerprint_for_tests() { return build_fingerprint; }
std::uint32_t plugin_abi_version_for_tests() { return plugin_abi_version; }
}  // namespace mechgraph::testing

TEST_CASE("the build fingerprint names the ABI version and the compiler", "[plugins]") {
  const std::string f = mechgraph::testing::build_fingerprint_for_tests();
  CHECK(f.rfind("abi" + std::to_string(mechgraph::plugin_abi_version), 0) == 0);
  CHECK(f.find("cxx") != std::string::npos);
}
