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
       {"Lift, velocity, acceleration and jerk of three-arc, Kurz, polydyne (kinematic) (arc, kurz, poly)",
        "Lift, velocity, acceleration and jerk of three-arc, Kurz, polydyne (kinematic) (v_arc, v_kurz, v_poly)",
        "Stage 4 by the source", "kurz.events", "v_kurz.events", "Spring force over valve lift of Kurz (sd_kurz)",
        "intake: opens"}},
      {"backlash_chain.yaml", "chain", 3,
       {"chain.joint_contribution_rss", "Against the specification", "samples outside spec",
        "chain.mc_histogram against the spec limits", ">USL<"}},
      {"cam_contour.yaml", "contour", 4, {"contour of flat tappet (flat) (to scale)", "contour of roller 11 mm, offset 3 mm (roller) (to scale)", "pitch curve"}},
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
  // Histograms the plot must survive: a spec limit far from the samples (named in the title, not
  // stretching the axis), and samples all equal (one bin: a stack without spread).
  {
    const fs::path scene = base / "histograms.yaml";
    std::ofstream(scene) << R"(title: Histograms at the edges
effects: [ monte_carlo ]
nodes:
  far:
    type: stack.linear
    params:
      samples: 20000
      spec: { upper: 1000 mm }
      links: [ { nominal: 10 mm, upper: 0.02 mm, lower: -0.02 mm }, { nominal: 5 mm, upper: 0.01 mm, lower: -0.01 mm } ]
  exact:
    type: stack.linear
    params:
      samples: 20000
      links: [ { nominal: 10 mm, upper: 0 mm, lower: 0 mm } ]
)";
    const fs::path dir = base / "histograms";
    const auto r = run_cli("-q report '" + scene.string() + "' --out '" + dir.string() + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::string page = read(dir / "report.html");
    CHECK_THAT(page, Contains("off the plot: USL = 1000 mm"));
    CHECK_THAT(page, Contains("exact.mc_histogram"));
    const auto check = run_command(checker + "'" + dir.string() + "' 2");
    INFO(check.out << check.err);
    CHECK(check.exit_code == 0);
  }
  // The report's own folder is regenerated without --force (report_folder_test.cpp has the other cases).
  const auto again = run_cli("-q report '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/cam_contour.yaml' --out '" + (base / "contour").string() + "'");
  CHECK(again.exit_code == 0);
}

TEST_CASE("mechgraph report: every example scene makes its report", "[cli][report]") {
  // A report draws more than the scene lists (every curve of the nodes it needs): an output made
  // only with an optional input (cam.table's deviation from a master law) must not be asked for
  // when that input is not connected.
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / ("mg_report_all_" + std::to_string(::getpid()));
  fs::remove_all(base);
  std::size_t scenes = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(MECHGRAPH_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    INFO(entry.path().filename().string());
    const auto r = run_cli("-q report '" + entry.path().string() + "' --out '" + (base / entry.path().stem()).string() + "'");
    INFO(r.err);
    CHECK(r.exit_code == 0);
    CHECK(fs::exists(base / entry.path().stem() / "report.html"));
    // A list of contact events is a table however many rows it has, never a plot of codes.
    if (entry.path().filename() == "valvetrain_dynamics.yaml")
    {
      const std::string page = read(base / entry.path().stem() / "report.html");
      CHECK_THAT(page, Contains("<h2>contacts.events</h2>\n<div class=\"scroll\"><table"));
      CHECK_THAT(page, Contains("event 1 contact lost, 2 contact regained"));  // the codes, under the table
    }
    ++scenes;
  }
  CHECK(scenes >= 10);
  fs::remove_all(base);
}
