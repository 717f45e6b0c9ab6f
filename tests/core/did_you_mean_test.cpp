#include <mechgraph/did_you_mean.hpp>

#include <catch2/catch.hpp>

using namespace mechgraph;
using Catch::Matchers::Contains;

TEST_CASE("edit distance", "[did_you_mean]") {
  CHECK(edit_distance("kurz", "kurtz") == 1);
  CHECK(edit_distance("", "abc") == 3);
  CHECK(edit_distance("three_arc", "three_arc") == 0);
  CHECK(edit_distance("flaw", "lawn") == 2);
}

TEST_CASE("unknown names suggest the closest and list all", "[did_you_mean]") {
  const std::vector<std::string> cams{"cam.kurz", "cam.polydyne", "cam.three_arc", "cam.cycloidal"};
  const std::string msg = unknown_name_message("node type", "cam.kurtz", cams);
  CHECK_THAT(msg, Contains("unknown node type 'cam.kurtz'") && Contains("did you mean 'cam.kurz'?") &&
                      Contains("(cam.cycloidal cam.kurz cam.polydyne cam.three_arc)"));
  CHECK(closest_match("zzzzzz", cams).empty());
  CHECK_THAT(unknown_name_message("effect", "x", {}), Contains("there are none"));
  CHECK_THAT(unknown_name_message("node type", "x", cams), Contains("valid node types are"));
  CHECK_THAT(unknown_name_message("failure class", "x", {"any", "scene"}), Contains("valid failure classes are"));
}
