// The README's results: every terminal listing it shows is what the command prints now (line by
// line, each figure at the digits the README prints), and the figures quoted in its prose are
// recomputed. Timings ("Speed", "23 s on the shared 2-core build machine") are measurements, not
// recomputed (docs_numbers_inventory_test.cpp lists them as such).
#include "docs/doc_numbers.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>

using namespace mechgraph::testing;
using namespace mechgraph::testing::docs;

namespace {

std::string scene(const std::string& name) { return "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/" + name + "'"; }
std::string plugins() { return "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' "; }

// `mechgraph run SCENE [extra]`'s standard output (run from the source tree, as the README does).
std::string run_output(const std::string& scene_name, const std::string& extra = "") {
  const CommandResult r = run_cli(plugins() + "-q run " + scene(scene_name) + " " + extra);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  return r.out;
}

}  // namespace

TEST_CASE("docs: README's valve-train study listing is what run-study.sh and run print", "[docs][readme]") {
  const std::string out = run_output("valvetrain_cams.yaml");
  check_block("README.md", "Three cams of equal tappet lift", out);
  // The same notes once more under "What engineers see".
  check_block("README.md", "v_kurz: intake: opens", out);
}

TEST_CASE("docs: README's valve dynamics listing is what run prints", "[docs][readme]") {
  const std::string out = run_output("valvetrain_dynamics.yaml");
  check_block("README.md", "Kurz cam, spring for 5600 rpm", out);
  // "cosine ramps land the valve at less than half the speed": the seating velocities with
  // contacts, without and with ramps (the third and fourth columns).
  quoted(doc_text("README.md"), "cosine ramps land the valve at less than half the speed");
  const std::string n = number;
  const auto v = quoted(out, "seating velocity +m/s +" + n + " +" + n + " +" + n + " +" + n + " +" + n);
  CHECK(std::stod(v[3]) < 0.5 * std::stod(v[2]));
}

TEST_CASE("docs: README's backlash listing and provenance excerpt are what run prints", "[docs][readme]") {
  check_block("README.md", "Free play of each hinge along the rod", run_output("backlash_chain.yaml"));

  // The provenance excerpt of `run scenes/backlash_chain.yaml --set chain.seed=7 --json`: the
  // scene's SHA-1 (the scene file as it is now), the random node's seed and samples, and the RSS
  // contribution quoted by label.
  const YAML::Node j = YAML::Load(run_output("backlash_chain.yaml", "--set chain.seed=7 --json"));
  const std::string readme = doc_text("README.md");
  const auto sha = quoted(readme, "\"file\": \"scenes/backlash_chain.yaml\", \"sha1\": \"([0-9a-f]{40})\"");
  CHECK(sha[0] == j["provenance"]["scene"]["sha1"].as<std::string>());
  const auto random = quoted(readme, "\"random\": \\{\"chain\": \\{\"seed\": ([0-9]+), \"samples\": ([0-9]+)\\}\\}");
  CHECK(std::stoi(random[0]) == j["provenance"]["random"]["chain"]["seed"].as<int>());
  CHECK(std::stoi(random[1]) == j["provenance"]["random"]["chain"]["samples"].as<int>());
  const auto share = quoted(readme, "\"by_label\": \\{\"h1 bracket pin\": " + std::string(number));
  check_quote("h1's share of the RSS variance, %", share[0],
              j["outputs"]["chain.joint_contribution_rss"]["by_label"]["h1 bracket pin"].as<double>());
}

TEST_CASE("docs: README's contour listing, its note and the events CSV are what run writes", "[docs][readme]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("mechgraph_docs_contour_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::string out = run_output("cam_contour.yaml", "--out '" + dir.string() + "'");
  check_block("README.md", "One lift law, two followers", out);
  check_block("README.md", "flat: contour: the cam turns", out);
  std::ifstream events(dir / "kurz.events.csv");
  REQUIRE(events);
  check_block("README.md", "checking_lift [mm],opening [deg (cam)]", std::string(std::istreambuf_iterator<char>(events), {}));
  std::filesystem::remove_all(dir);
}

TEST_CASE("docs: README's finger-follower listing is what run prints", "[docs][readme]") {
  check_block("README.md", "Roller finger follower", run_output("finger_follower.yaml"));
  // The recomputation it describes: the turn 6.5/36 rad at the nose, the ratio (50/36) cos(psi - 4 deg).
  const std::string readme = doc_text("README.md");
  quoted(readme, "the turn 6\\.5/36 rad, the ratio \\(50/36\\) cos\\(psi - 4 deg\\), the valve lift 50 \\(sin\\(psi - 4 deg\\) \\+ "
                 "sin 4 deg\\) - 0\\.05 mm");
  const double pi = 3.14159265358979323846, psi = 6.5 / 36, a = 4 * pi / 180;
  const auto turn = quoted(readme, "finger turn at the nose +deg +" + std::string(number));
  check_quote("finger turn, deg", turn[0], psi * 180 / pi);
  const auto ratios = quoted(readme, "valve / cam lift ratio, valve closed +" + std::string(number) +
                                         " valve / cam lift ratio, at the nose +" + number);
  check_quote("ratio closed", ratios[0], 50.0 / 36 * std::cos(-a));
  check_quote("ratio at the nose", ratios[1], 50.0 / 36 * std::cos(psi - a));
  const auto lift = quoted(readme, "valve lift \\(lash taken up\\) +mm +" + std::string(number));
  check_quote("valve lift, mm", lift[0], 50 * (std::sin(psi - a) + std::sin(a)) - 0.05);
}

TEST_CASE("docs: README's prose figures of the tolerance stack and the measured table", "[docs][readme]") {
  const std::string readme = doc_text("README.md");
  {
    const YAML::Node j = YAML::Load(run_output("tolerance_stack.yaml", "--json"));
    const auto rss = quoted(readme, "every part normal, RSS \\+-" + std::string(number) + " mm\\) and the same parts with a "
                                    "uniformly spread case \\(RSS \\+-" + number + " mm\\)");
    // The stack's RSS half-width is 3 sigma of the linear stack.
    auto half_width = [&](const std::string& node) {
      const double upper = j["outputs"][node + ".rss_max"]["value"].as<double>();
      const double mean = j["outputs"][node + ".mean"]["value"].as<double>();
      return (upper - mean) / 1e-3;
    };
    check_quote("MITCalc stack, RSS half-width, mm", rss[0], half_width("mitcalc"));
    check_quote("uniform case, RSS half-width, mm", rss[1], half_width("gap"));
  }
  {
    const YAML::Node j = YAML::Load(run_output("cam_table_measured.yaml", "--json"));
    auto radius = [&](const std::string& node) { return j["outputs"][node + ".min_curvature_radius"]["value"].as<double>() / 1e-3; };
    const auto raw = quoted(readme, "gives a smallest radius of curvature of " + std::string(number) + " mm for the design's " + number);
    check_quote("raw table, min radius, mm", raw[0], radius("raw"));
    check_quote("design, min radius, mm", raw[1], radius("design"));
    const auto smoothed = quoted(readme, "or `smoothing: gcv` it gives " + std::string(number) + " and " + number + " mm");
    check_quote("smoothed by resolution, min radius, mm", smoothed[0], radius("smoothed"));
    check_quote("smoothed by GCV, min radius, mm", smoothed[1], radius("gcv"));
  }
}

// `mechgraph study` of the valve timing scene runs 448 evaluations (tens of seconds): hidden from
// the default run, registered in CTest on its own with the label docs-slow.
TEST_CASE("docs: README's uncertainty study listing is what study prints", "[.docs-slow]") {
  const std::string readme = doc_text("README.md");
  const auto counts = quoted(readme, "the float speed and coil bind at overspeed \\(([0-9]+) evaluations,");
  const CommandResult r = run_cli(plugins() + "-q study " + scene("valve_timing_tolerances.yaml"));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find(counts[0] + " evaluations") != std::string::npos);
  check_block("README.md", "v.opening_angle [deg (cam)]: n 128", r.out);
}
