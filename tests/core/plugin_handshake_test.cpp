// The build fingerprint's language standard, named the way each compiler gives it.
#include "../../core/src/plugin_handshake.hpp"

#include <catch2/catch.hpp>

using mechgraph::detail::cxx_standard_name;

TEST_CASE("a fingerprint's __cplusplus names its standard, drafts included, whichever compiler gave it", "[plugins][fingerprint]") {
  CHECK(cxx_standard_name("201703L") == "C++17 (__cplusplus 201703L)");
  CHECK(cxx_standard_name("201709L") == "C++20 (__cplusplus 201709L)");  // gcc 8/9 -std=c++2a
  CHECK(cxx_standard_name("202002L") == "C++20 (__cplusplus 202002L)");
  CHECK(cxx_standard_name("202100L") == "C++23 (__cplusplus 202100L)");  // gcc 12 -std=c++23
  CHECK(cxx_standard_name("202101L") == "C++23 (__cplusplus 202101L)");  // clang 14 -std=c++2b
  CHECK(cxx_standard_name("202302L") == "C++23 (__cplusplus 202302L)");
  CHECK(cxx_standard_name("202400L") == "a standard after C++23 (__cplusplus 202400L)");
  CHECK(cxx_standard_name("201402L") == "C++14 (__cplusplus 201402L)");
  CHECK(cxx_standard_name("unknown") == "__cplusplus unknown");
  CHECK(cxx_standard_name("") == "__cplusplus ");
  CHECK(cxx_standard_name("1") == "__cplusplus 1");  // gcc before 4.7
  CHECK(cxx_standard_name("2017x") == "__cplusplus 2017x");
  CHECK(cxx_standard_name("201703") == "C++17 (__cplusplus 201703)");
}
