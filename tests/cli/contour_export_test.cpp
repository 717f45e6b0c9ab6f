// Contours for manufacturing, end to end: `run --out` writes each contour as CSV and DXF, and an
// independent reader (ezdxf, Debian's python3-ezdxf) opens the DXF and finds the CSV's points.
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

TEST_CASE("contours go out as CSV and DXF, ezdxf reads the DXF back with the CSV's points", "[cli][contour]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("mg_contour_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto r = run_cli("-q run '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/cam_contour.yaml' --out '" + dir.string() + "'");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("largest Hertz contact pressure"));
  for (const char* f : {"flat.contour.dxf", "roller.contour.dxf", "flat.contour.csv", "kurz.svaj.csv", "kurz.events.csv"})
    CHECK(fs::exists(dir / f));
  CHECK_FALSE(fs::exists(dir / "kurz.svaj.dxf"));  // only closed curves are drawings
  const std::string reader = "/usr/bin/python3 '" + std::string(MECHGRAPH_SOURCE_DIR) + "/tests/cli/read_dxf.py' ";
  const auto flat = run_command(reader + "'" + (dir / "flat.contour.dxf").string() + "' '" + (dir / "flat.contour.csv").string() + "' CONTOUR FOLLOWER:open");
  INFO(flat.out << flat.err);
  CHECK(flat.exit_code == 0);
  const auto roller = run_command(reader + "'" + (dir / "roller.contour.dxf").string() + "' '" +
                                  (dir / "roller.contour.csv").string() + "' CONTOUR PITCH FOLLOWER:open");
  INFO(roller.out << roller.err);
  CHECK(roller.exit_code == 0);
  CHECK_THAT(roller.out, Contains("PITCH: 571 points, closed"));
  // Which way the cam turns: a comment in the drawing, a note in results.json.
  auto text_of = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  CHECK_THAT(text_of(dir / "flat.contour.dxf"), Contains("999\ncontour: the cam turns counterclockwise seen from the front"));
  CHECK_THAT(text_of(dir / "results.json"), Contains("contour: the cam turns counterclockwise seen from the front"));
  // ... and the CSV's first column is named for it.
  CHECK(text_of(dir / "flat.contour.csv").rfind("cam_angle_ccw [deg],x [mm],y [mm]", 0) == 0);
  const auto cw = run_cli("-q run '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/cam_contour.yaml' --set flat.rotation=cw --out '" +
                          (dir / "cw").string() + "'");
  REQUIRE(cw.exit_code == 0);
  CHECK(text_of(dir / "cw" / "flat.contour.csv").rfind("cam_angle_cw [deg],x [mm],y [mm]", 0) == 0);
  CHECK_THAT(text_of(dir / "cw" / "flat.contour.dxf"), Contains("999\ncontour: the cam turns clockwise seen from the front"));
}
