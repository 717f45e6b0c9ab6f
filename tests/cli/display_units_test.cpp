// The scene's `units:` end to end: CSV columns and printed outputs in the units asked for (composed
// for derived dimensions), JSON in SI, and located errors for wrong quantities and units.
#include "file_support.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <unistd.h>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

std::string scene_file(const std::string& name, const std::string& yaml) {
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_units_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / name;
  std::ofstream(file) << yaml;
  return file.string();
}

const char* cam_nodes = R"(
nodes:
  cam: { type: cam.harmonic, params: { max_lift: 9 mm, action_angle: 140 deg, base_radius: 40 mm } }
outputs: [cam.svaj, cam.duration, cam.max_acceleration]
)";

}  // namespace

TEST_CASE("units: CSV headers and values in the scene's units, composed for derived dimensions, JSON stays SI", "[cli][units]") {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / ("mg_units_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const std::string with_units = scene_file("with.yaml", std::string("units: { length: mm, angle: deg }\n") + cam_nodes);
  const std::string si = scene_file("si.yaml", cam_nodes);
  const auto a = run_cli("-q run '" + with_units + "' --out '" + (base / "mm").string() + "'");
  const auto b = run_cli("-q run '" + si + "' --out '" + (base / "si").string() + "'");
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  const auto mm = csv_cells(base / "mm" / "cam.svaj.csv");
  const auto raw = csv_cells(base / "si" / "cam.svaj.csv");
  REQUIRE(mm.size() == 362);
  // Degrees carry their frame (the port's declared angle frame), radians and SI none.
  CHECK(mm[0] == std::vector<std::string>{"cam_angle [deg (cam)]", "crank_angle [deg (crank)]", "lift [mm]",
                                          "velocity [mm/deg (cam)]", "acceleration [mm/deg^2 (cam)]", "jerk [mm/deg^3 (cam)]"});
  CHECK(raw[0] == std::vector<std::string>{"cam_angle [rad]", "crank_angle [rad]", "lift [m]", "velocity [m/rad]",
                                           "acceleration [m/rad^2]", "jerk [m/rad^3]"});
  const double d = std::numbers::pi / 180.0;
  const double scale[6] = {1 / d, 1 / d, 1e3, 1e3 * d, 1e3 * d * d, 1e3 * d * d * d};
  for (std::size_t row = 1; row < mm.size(); row += 30)
    for (std::size_t k = 0; k < 6; ++k)
      CHECK_THAT(std::stod(mm[row][k]), Catch::Matchers::WithinRel(std::stod(raw[row][k]) * scale[k], 1e-14) ||
                                            Catch::Matchers::WithinAbs(0.0, 1e-300));
  // Printed outputs follow the scene's units too.
  CHECK_THAT(a.out, Contains("cam.max_acceleration = ") && Contains("mm/deg^2"));
  CHECK_THAT(a.out, Contains("cam.duration = ") && Contains(" deg"));
  // JSON stays SI.
  const auto json = run_cli("-q run '" + with_units + "' --json");
  CHECK_THAT(json.out, Contains("\"unit\":\"m/rad^2\""));
}

TEST_CASE("units: an unknown quantity or a unit of another dimension is a located scene error", "[cli][units]") {
  const auto typo = run_cli("-q validate '" + scene_file("typo.yaml", std::string("units: { lenght: mm }\n") + cam_nodes) + "'");
  CHECK(typo.exit_code == 2);
  CHECK_THAT(typo.err, Contains("typo.yaml:1:10: units: unknown quantity 'lenght'") && Contains("length"));
  const auto wrong = run_cli("-q validate '" + scene_file("wrong.yaml", std::string("units: { length: deg }\n") + cam_nodes) + "'");
  CHECK(wrong.exit_code == 2);
  CHECK_THAT(wrong.err, Contains("wrong.yaml:1:18: units: length is a length but 'deg' is a angle"));
  const auto bad = run_cli("-q validate '" + scene_file("bad.yaml", std::string("units: { force: kN*furlong }\n") + cam_nodes) + "'");
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Contains("bad.yaml:1:") && Contains("furlong"));
}
