// `mechgraph report` end to end: the page opens in a real headless browser (chromium) and renders
// its plots without console errors, loads nothing from outside, and every plot and table has its
// CSV beside it (tests/cli/check_report_page.py); the overlays, bars and to-scale contours are there.
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>

#include <unistd.h>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("mechgraph report: a self-contained page with every curve plotted, rendered by chromium", "[cli][report]") {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / ("mg_report_" + std::to_string(::getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  const std::string checker = "/usr/bin/python3 '" + std::string(MECHGRAPH_SOURCE_DIR) + "/tests/cli/check_report_page.py' ";
  struct Case {
    const char* scene;
    const char* folder;
    int min_plots;
    std::vector<const char*> expected;  // in the page
  };
  const std::vector<Case> cases{
      {"valvetrain_cams.yaml", "cams", 5,
       {"svaj of arc, kurz, poly: acceleration", "svaj of v_arc, v_kurz, v_poly: acceleration", "Stage 4 by the source",
        "kurz.events", "v_kurz.events", "sd_kurz.force_curve: spring_force, inertia_force, required_force, contact_force",
        "intake: opens"}},
      {"backlash_chain.yaml", "chain", 3,
       {"chain.joint_contribution_rss", "Against the specification", "samples outside spec",
        "chain.mc_histogram against the spec limits", ">USL<"}},
      {"cam_contour.yaml", "contour", 4, {"flat.contour (to scale)", "roller.contour (to scale)", "pitch curve"}},
  };
  for (const Case& c : cases) {
    INFO(c.scene);
    const fs::path dir = base / c.folder;
    const auto r = run_cli("-q report '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + c.scene + "' --out '" + dir.string() + "'");
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("report.html"));
    CHECK(fs::exists(dir / "results.json"));
    const std::string page = read(dir / "report.html");
    for (const char* text : c.expected) CHECK_THAT(page, Contains(text));
    const auto check = run_command(checker + "'" + dir.string() + "' " + std::to_string(c.min_plots));
    INFO(check.out << check.err);
    CHECK(check.exit_code == 0);
  }
  // An existing folder needs --force, as for run --out.
  const auto again = run_cli("-q report '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/cam_contour.yaml' --out '" + (base / "contour").string() + "'");
  CHECK(again.exit_code == 2);
  CHECK_THAT(again.err, Contains("--force"));
}
