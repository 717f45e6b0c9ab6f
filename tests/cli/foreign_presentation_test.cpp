// A node type from outside the built-in set (tests/test_plugins/stroke_plugin.cpp: a pump's
// plunger, its own names, frames, codes and note) is presented from its declarations alone: the
// report draws its derivative family in its derived frame with that frame's marks and its points,
// tags degrees with its frames, shows its codes by name in the terminal, CSV, JSON and the page,
// and `run` wants the output its declared note is made with. Nothing in the host names it. Each
// case runs on the plugin built twice: with the pre-1.0 entry and through the SDK 1.x C boundary
// (test_stroke_sdk1), whose declarations cross as the C structs of c/present.h.
#include "file_support.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

namespace fs = std::filesystem;

// The pump built with the pre-1.0 entry and through the SDK 1.x C boundary.
const char* const stroke_plugins[] = {"test_stroke", "test_stroke_sdk1"};
std::string stroke_dir(const char* plugin) { return "--only-plugin-dir '" + test_plugin(plugin).parent_path().string() + "' "; }

fs::path stroke_scene(const fs::path& dir, bool phase) {
  fs::create_directories(dir);
  const fs::path file = dir / (phase ? "pump_phase.yaml" : "pump.yaml");
  std::ofstream(file) << "title: A pump\nnodes:\n  p: { type: pump.stroke, params: { " << (phase ? "phase: 30 deg, " : "")
                      << "stroke: 20 mm } }\noutputs: [p.motion, p.peak_angle]\n";
  return file;
}

}  // namespace

TEST_CASE("a foreign node type's report: its family in its derived frame, marks, points, codes by name", "[cli][report][presentation]") {
  for (const char* plugin : stroke_plugins) {
    INFO(plugin);
    const fs::path dir = scratch_dir(std::string("foreign_presentation_") + plugin);
    const fs::path out = dir / "report";
    fs::remove_all(out);
    const auto r = run_cli("-q " + stroke_dir(plugin) + "report '" + stroke_scene(dir, true).string() + "' --out '" + out.string() + "'");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const std::string page = slurp(out / "report.html");
    // The family: its title, its channels' labels and their frames' tags, drawn in the rotor frame.
    CHECK_THAT(page, Contains("Plunger position, speed and acceleration of p"));
    CHECK_THAT(page, Contains("rotor angle after port one [deg (rotor)]"));
    CHECK_THAT(page, Contains("plunger position [mm]"));
    CHECK_THAT(page, Contains("speed [mm/deg (shaft)]"));
    CHECK_THAT(page, Contains("acceleration [mm/deg^2 (shaft)]"));
    // The rotor frame's marks and the port events as labelled points quoted from the nearest mark:
    // opens at -150 deg rotor (30 before P3 at -120), closes at 30 + 5.73 deg (after P1 at 0).
    CHECK_THAT(page, Contains("<text>P1</text>") && Contains("<text>P3</text>"));
    CHECK_THAT(page, Contains("opens 30.0 -P3") && Contains("closes 35.7 +P1"));
    CHECK_THAT(page, Contains("ports at 5 mm travel: p opens 30.0 -P3, closes 35.7 +P1"));
    // The events table: columns of two frames say which, codes by name.
    CHECK_THAT(page, Contains("opening<br><span class=\"u\">[deg (shaft)]"));
    CHECK_THAT(page, Contains("opening on the rotor<br><span class=\"u\">[deg (rotor)]"));
    CHECK_THAT(page, Contains("suction_port (1)") && Contains("delivery_port (2)"));
    CHECK_THAT(slurp(out / "p.port_events.csv"), Contains("kind [1],kind_name,") && Contains(",suction_port,"));
  }
}

TEST_CASE("a foreign node type's run: its note wanted, codes named, angles tagged with its frame", "[cli][presentation]") {
  for (const char* plugin : stroke_plugins) {
    INFO(plugin);
    const fs::path dir = scratch_dir(std::string("foreign_run_") + plugin);
    const auto r = run_cli("-q " + stroke_dir(plugin) + "run '" + stroke_scene(dir, true).string() + "'");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    // port_events is not an output of the scene: the declared note wants it.
    CHECK_THAT(r.out, Contains("p: ports: suction opens at rotor angle -150 deg"));
    CHECK_THAT(r.out, Contains("deg (shaft)"));
    const auto json = run_cli("-q " + stroke_dir(plugin) + "run --json '" + stroke_scene(dir, true).string() + "' --set p.phase=0deg");
    REQUIRE(json.exit_code == 0);
    // No phase, no note: without the parameter the output is not wanted for it.
    const auto plain = run_cli("-q " + stroke_dir(plugin) + "run '" + stroke_scene(dir, false).string() + "'");
    REQUIRE(plain.exit_code == 0);
    CHECK_THAT(plain.out, !Contains("ports:"));
    // Listed, the events table's codes are named in the terminal and in JSON.
    std::ofstream(dir / "events.yaml") << "nodes:\n  p: { type: pump.stroke }\noutputs: [p.port_events]\n";
    const auto events = run_cli("-q " + stroke_dir(plugin) + "run '" + (dir / "events.yaml").string() + "'");
    CHECK_THAT(events.out, Contains("1 suction_port") && Contains("2 delivery_port"));
    const auto events_json = run_cli("-q " + stroke_dir(plugin) + "run --json '" + (dir / "events.yaml").string() + "'");
    CHECK_THAT(events_json.out, Contains("\"names\":[\"suction_port\",\"delivery_port\"]"));
    CHECK_THAT(events_json.out, Contains("\"name\":\"delivery_port\""));
  }
}

TEST_CASE("a foreign node type without its frame's offset is drawn over its own axis", "[cli][report][presentation]") {
  for (const char* plugin : stroke_plugins) {
    INFO(plugin);
    const fs::path dir = scratch_dir(std::string("foreign_plain_") + plugin);
    const fs::path out = dir / "report";
    fs::remove_all(out);
    const auto r = run_cli("-q " + stroke_dir(plugin) + "report '" + stroke_scene(dir, false).string() + "' --out '" + out.string() + "'");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const std::string page = slurp(out / "report.html");
    CHECK_THAT(page, Contains("shaft angle [deg (shaft)]"));
    CHECK_THAT(page, !Contains("rotor angle after port one"));
    CHECK_THAT(page, !Contains("<text>P1</text>"));
  }
}

TEST_CASE("describe and plugin-test show and check a foreign type's declarations", "[cli][describe][presentation]") {
  for (const char* plugin : stroke_plugins) {
    INFO(plugin);
    const auto d = run_cli(stroke_dir(plugin) + "describe pump.stroke");
    INFO(d.out << d.err);
    CHECK_THAT(d.out, Contains("angle frames:") && Contains("rotor: rotor angle after port one") && Contains("= 3 x shaft + phase"));
    CHECK_THAT(d.out, Contains("presented as derivative_family") && Contains("codes 1 suction_port, 2 delivery_port"));
    CHECK_THAT(d.out, Contains("with phase, made with port_events"));
    const auto j = run_cli(stroke_dir(plugin) + "describe pump.stroke --json");
    CHECK_THAT(j.out, Contains("\"frames\":[{\"id\":\"shaft\"") && Contains("\"role\":\"derivative_family\""));
    const auto t = run_cli("plugin-test '" + test_plugin(plugin).string() + "'");
    INFO(t.out << t.err);
    CHECK(t.exit_code == 0);
    CHECK_THAT(t.out, Contains("presentation: frames declared and acyclic"));
  }
}

TEST_CASE("a foreign type's declarations read the same through the SDK 1.x C boundary", "[cli][describe][presentation][sdk]") {
  // Frames, channels, codes, points and notes crossed as C structs describe exactly what the C++
  // classes describe: describe --json of the two builds is one text.
  const auto old_path = run_cli(stroke_dir("test_stroke") + "describe pump.stroke --json");
  const auto c_path = run_cli(stroke_dir("test_stroke_sdk1") + "describe pump.stroke --json");
  INFO(old_path.err << c_path.err);
  REQUIRE(old_path.exit_code == 0);
  REQUIRE(c_path.exit_code == 0);
  CHECK_THAT(c_path.out, Contains("\"frames\":[{\"id\":\"shaft\"") && Contains("\"notes\""));
  CHECK(c_path.out == old_path.out);
}

TEST_CASE("a sweep's header names the angle frame an output's port declares, as the report does", "[cli][sweep][presentation]") {
  for (const char* plugin : stroke_plugins) {
    INFO(plugin);
    const fs::path dir = scratch_dir(std::string("foreign_sweep_") + plugin);
    const fs::path rows = dir / "rows.csv";
    fs::remove(rows);
    const auto r = run_cli("-q " + stroke_dir(plugin) + "sweep '" + stroke_scene(dir, false).string() +
                           "' --vary p.stroke=10mm:20mm:2 --outputs p.peak_angle --out '" + rows.string() + "'");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const std::string text = slurp(rows);
    CHECK(text.substr(0, text.find('\n')) == "case,p.stroke [mm],p.peak_angle [deg (shaft)],exit,error");
    // --resume reads the header back as its own (the second case still to run).
    const std::size_t second_row = text.find('\n', text.find('\n') + 1) + 1;
    fs::remove(rows);
    std::ofstream(rows.string() + ".part") << text.substr(0, second_row);
    const auto resumed = run_cli("-q " + stroke_dir(plugin) + "sweep '" + stroke_scene(dir, false).string() +
                                 "' --vary p.stroke=10mm:20mm:2 --outputs p.peak_angle --out '" + rows.string() + "' --resume");
    INFO(resumed.err);
    CHECK(resumed.exit_code == 0);
    CHECK(slurp(rows) == text);
  }
}

TEST_CASE("a plain table's declared figure title is the title of its figure", "[cli][report][presentation]") {
  for (const char* plugin : stroke_plugins) {
    INFO(plugin);
    const fs::path dir = scratch_dir(std::string("foreign_gaps_") + plugin);
    const fs::path out = dir / "report";
    fs::remove_all(out);
    std::ofstream(dir / "gaps.yaml") << "nodes:\n  p: { type: pump.stroke }\n  q: { type: pump.stroke, params: { stroke: 10 mm } }\n"
                                        "outputs: [p.gaps]\n";
    std::ofstream(dir / "two.yaml") << "nodes:\n  p: { type: pump.stroke }\n  q: { type: pump.stroke, params: { stroke: 10 mm } }\n"
                                       "outputs: [p.gaps, q.gaps]\n";
    const auto r = run_cli("-q " + stroke_dir(plugin) + "report '" + (dir / "gaps.yaml").string() + "' --out '" + out.string() + "'");
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const std::string page = slurp(out / "report.html");
    CHECK_THAT(page, Contains("Seal gaps over a turn of p"));
    CHECK_THAT(page, !Contains("upper gap, lower gap of p"));
    CHECK_THAT(page, Contains("shaft angle [deg (shaft)]"));
    fs::remove_all(out);
    const auto two = run_cli("-q " + stroke_dir(plugin) + "report '" + (dir / "two.yaml").string() + "' --out '" + out.string() + "'");
    REQUIRE(two.exit_code == 0);
    // Two nodes' tables: each node's figure, titled as declared.
    CHECK_THAT(slurp(out / "report.html"), Contains("Seal gaps over a turn of p") && Contains("Seal gaps over a turn of q"));
  }
}
