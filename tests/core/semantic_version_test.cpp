// Plugin versions and the scene's `requires:` (core/include/mechgraph/semantic_version.hpp).
#include "test_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/semantic_version.hpp>

#include <catch2/catch.hpp>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {
bool satisfies(const char* version, const char* requirement) {
  return VersionRequirement::parse(requirement).satisfied_by(*SemanticVersion::parse(version));
}
}  // namespace

TEST_CASE("semantic versions: MAJOR.MINOR.PATCH, ordered part by part", "[plugins][versions]") {
  CHECK(SemanticVersion::parse("0.2.0") == SemanticVersion{0, 2, 0});
  CHECK(SemanticVersion::parse("10.0.3") > SemanticVersion::parse("9.12.40"));
  CHECK_FALSE(SemanticVersion::parse("0.2"));      // a plugin states all three parts
  CHECK_FALSE(SemanticVersion::parse("v1.0.0"));
  CHECK_FALSE(SemanticVersion::parse("1.0.0.1"));
  CHECK_FALSE(SemanticVersion::parse("1..0"));
  CHECK_FALSE(SemanticVersion::parse("-1.0.0"));
  CHECK(SemanticVersion::parse_partial("0.2") == SemanticVersion{0, 2, 0});
}

TEST_CASE("version requirements: comparisons, caret, tilde, several joined by commas", "[plugins][versions]") {
  CHECK(satisfies("0.2.0", ">=0.2"));
  CHECK_FALSE(satisfies("0.1.9", ">=0.2"));
  CHECK(satisfies("0.2.1", ">0.2"));
  CHECK_FALSE(satisfies("0.2.0", ">0.2"));
  CHECK(satisfies("0.9.9", ">=0.2, <1"));
  CHECK_FALSE(satisfies("1.0.0", ">=0.2, <1"));
  CHECK(satisfies("1.2.3", "1.2.3"));
  CHECK(satisfies("1.2.3", "==1.2.3"));
  CHECK_FALSE(satisfies("1.2.4", "=1.2.3"));
  CHECK(satisfies("1.4.0", "^1.2"));       // same major
  CHECK_FALSE(satisfies("2.0.0", "^1.2"));
  CHECK(satisfies("0.2.7", "^0.2.1"));     // before 1.0 the minor is the major
  CHECK_FALSE(satisfies("0.3.0", "^0.2.1"));
  CHECK(satisfies("0.3.9", "~0.3.1"));
  CHECK_FALSE(satisfies("0.4.0", "~0.3.1"));
  CHECK(satisfies("2.0.0", "<=2"));
  CHECK_THROWS_WITH(VersionRequirement::parse("at least two"), Contains("is not a version requirement") && Contains(">=0.2"));
  CHECK_THROWS_AS(VersionRequirement::parse(">=0.2,"), std::invalid_argument);
}

TEST_CASE("a scene's requires: met, unmet, unknown plugin, malformed", "[plugins][versions][scene]") {
  // The arithmetic test plugin is version 1.2.3.
  const std::string body = "nodes: { c: { type: test.constant, params: { value: 1 mm } } }\noutputs: [c.out]\n";
  CHECK_NOTHROW(graph_from("requires: { test_arith: \">=1.2, <2\" }\n" + body));
  CHECK_THROWS_WITH(graph_from("requires: { test_arith: \">=1.3\" }\n" + body),
                    Contains("1:25: the scene requires plugin 'test_arith' >=1.3, but the loaded one is 1.2.3") &&
                        Contains("mechgraph_test_arith.so"));
  CHECK_THROWS_WITH(graph_from("requires: { cams: \">=0.2\" }\n" + body),
                    Contains("requires plugin 'cams' >=0.2, which is not loaded") && Contains("test_arith"));
  CHECK_THROWS_WITH(graph_from("requires: { test_arith: \"new enough\" }\n" + body),
                    Contains("1:25: requires test_arith: 'new enough' is not a version requirement"));
  CHECK_THROWS_AS(graph_from("requires: [test_arith]\n" + body), SceneError);
}
