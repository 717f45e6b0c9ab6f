// The loaded cams plugin exports exactly the cam law types the conformance suite walks, plus
// cam.contour (tests/plugins/cams/contour_test.cpp), so a law added to the plugin cannot escape the suite.
#include "cam_test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

TEST_CASE("the cams plugin exports exactly the types of the registration lists", "[cams][conformance]") {
  std::vector<std::string> registered;
  for (const auto& t : mechgraph::cams::testing::all_cam_types()) registered.push_back(t->info().type);
  registered.push_back("cam.contour");
  registered.push_back("cam.program");  // tests/plugins/cams/program_law_test.cpp
  std::vector<std::string> loaded;
  for (const auto& p : mechgraph::testing::project_registry().plugins())
    if (p.id == "cams") loaded = p.node_types;
  std::sort(registered.begin(), registered.end());
  std::sort(loaded.begin(), loaded.end());
  CHECK(loaded == registered);
  CHECK(loaded.size() >= 10);
}
