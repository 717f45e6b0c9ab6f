// Scenes and command lines from a stranger (issue 18): no text of theirs becomes code in any output
// format, names follow a grammar, every scene read is bounded, every write to stdout is checked, and
// work is estimated against a budget before it starts. Each case runs the real `mechgraph` command
// with an argument vector (no shell between the test and the program).
#include "hostile/hostile_support.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

using Catch::Matchers::Contains;
using namespace mechgraph::hostile;

namespace {

const std::string kurz_params = "{ max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm }";

// A scene of one Kurz cam named `name` (YAML-quoted by the caller) and its svaj table requested.
std::string one_cam(const std::string& yaml_name, const std::string& output, const std::string& title = "t") {
  return "title: " + title + "\nnodes:\n  " + yaml_name + ": { type: cam.kurz, params: " + kurz_params + " }\noutputs: [ " + output + " ]\n";
}

const std::string marker = "/tmp/mechgraph_hostile_PWNED";

}  // namespace

TEST_CASE("hostile: node names outside the grammar are refused at load with their location", "[hostile]") {
  Scratch s("names");
  // A gnuplot command behind newlines, a path, a dot, a '$', a space, quotes, markup, non-ASCII, empty, too long.
  const std::vector<std::string> names = {
      R"("k\nsystem(\"id > /tmp/mechgraph_hostile_PWNED\")\n#")", R"("/tmp/x/evil")", R"("a.b")", R"("$k")", R"("k k")",
      R"("k\"")", R"("<b>k</b>")", R"("k\u00e9")", R"("")", std::string(65, 'k'), R"("1k")"};
  for (const std::string& name : names) {
    CAPTURE(name);
    const auto scene = s.write("names.yaml", one_cam(name, "x.svaj"));
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"validate", scene.string()}, {"graph", scene.string()}, {"run", scene.string(), "--out", (s.dir / "out").string()},
             {"report", scene.string(), "--out", (s.dir / "out").string()}}) {
      const Outcome o = run_mechgraph(args);
      CHECK(o.exit_code == 2);
      CHECK_THAT(o.err, Contains("names.yaml:3:3: node name"));
    }
  }
  CHECK_FALSE(std::filesystem::exists(marker));
  CHECK_FALSE(std::filesystem::exists("/tmp/x/evil.svaj.csv"));
  // The longest allowed name and every allowed character work.
  const auto good = s.write("good.yaml", one_cam(std::string(61, 'k') + "_-9", std::string(61, 'k') + "_-9.svaj"));
  CHECK(run_mechgraph({"validate", good.string()}).exit_code == 0);
  // Scene parameter names follow the same grammar.
  const auto param = s.write("param.yaml", "params: { \"l\\nx\": 8 mm }\nnodes: {}\n");
  const Outcome p = run_mechgraph({"validate", param.string()});
  CHECK(p.exit_code == 2);
  CHECK_THAT(p.err, Contains("param.yaml:1:11: scene parameter name"));
}

TEST_CASE("hostile: hostile text in titles and labels reaches every output as text, parsed back by real parsers", "[hostile]") {
  Scratch s("report");
  std::filesystem::remove(marker);
  // The title and the report's labels are free text: each format's escaping must hold them. The
  // title is the issue's own payload: out of a gnuplot string, then a command at a line's start.
  const std::string gp = "x'\\nsystem(\\\"touch " + marker + "\\\")\\n#";
  const std::string markup = "<script>alert(1)</script> &amp; `id` @a";
  const std::string scene_text =
      "title: \"T " + gp + " " + markup + "\"\n"
      "nodes:\n  k: { type: cam.kurz, params: " + kurz_params + " }\n"
      "outputs: [ k.svaj, k.max_lift ]\n"
      "report:\n  title: \"R " + gp + " " + markup + "\"\n  columns: [\"C, \\\"q\\\" " + markup + "\"]\n"
      "  rows:\n    - [\"=HYPERLINK(\\\"x\\\"), " + gp + "\", [k.max_lift], mm]\n";
  const auto scene = s.write("evil.yaml", scene_text);
  const std::string title = "T x'\nsystem(\"touch " + marker + "\")\n# " + markup;  // as YAML reads it
  // A results folder whose name is itself an injection attempt: no shell ever reads it.
  const std::filesystem::path out = s.dir / "John's results';touch PWN;'";
  const Outcome r = run_mechgraph({"report", scene.string(), "--out", out.string()}, s.dir);
  REQUIRE(r.exit_code == 0);
  CHECK_FALSE(std::filesystem::exists(marker));
  CHECK_FALSE(std::filesystem::exists(s.dir / "PWN"));
  // The page's text holds the title as written; the CSVs hold the labels as whole cells, the
  // formula neutralised by a leading quote.
  const Outcome check = run_argv("/usr/bin/python3", {source_file("tests/hostile/check_outputs.py"), out.string(), "--expect-text", title,
                                                       "--expect-cell", "C, \"q\" " + markup, "--expect-cell",
                                                       "'=HYPERLINK(\"x\"), x' system(\"touch " + marker + "\") #"});
  CHECK(check.exit_code == 0);
  CHECK(check.err.empty());
  // run --out: results.json and the curves' CSV.
  const std::filesystem::path run_out = s.dir / "run out";
  REQUIRE(run_mechgraph({"run", scene.string(), "--out", run_out.string()}).exit_code == 0);
  CHECK(run_argv("/usr/bin/python3", {source_file("tests/hostile/check_outputs.py"), run_out.string()}).exit_code == 0);
  // graph: DOT that Graphviz reads, the title as the graph's label, no attribute smuggled in.
  const std::filesystem::path dot_dir = s.dir / "dot";
  std::filesystem::create_directories(dot_dir);
  const Outcome g = run_mechgraph({"graph", scene.string()}, s.dir, (dot_dir / "g.dot").string());
  REQUIRE(g.exit_code == 0);
  const Outcome dot = run_argv("/usr/bin/python3", {source_file("tests/hostile/check_outputs.py"), dot_dir.string(), "--expect-label", title});
  CHECK(dot.exit_code == 0);
  CHECK(dot.err.empty());
  // run --json: one JSON object (the checker parses it strictly).
  const std::filesystem::path json_dir = s.dir / "json";
  std::filesystem::create_directories(json_dir);
  REQUIRE(run_mechgraph({"run", scene.string(), "--json"}, s.dir, (json_dir / "r.json").string()).exit_code == 0);
  CHECK(run_argv("/usr/bin/python3", {source_file("tests/hostile/check_outputs.py"), json_dir.string()}).exit_code == 0);
  CHECK_FALSE(std::filesystem::exists(marker));
}

TEST_CASE("hostile: YAML aliases cannot recurse or explode, keys cannot repeat, bytes must be UTF-8", "[hostile]") {
  Scratch s("yaml");
  struct Case {
    std::string text, expected;
  };
  std::string bomb = "params:\n  a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 10; ++i) {
    bomb += "  a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) bomb += (k ? ", *a" : "*a") + std::to_string(i - 1);
    bomb += "]\n";
  }
  bomb += "nodes: {}\n";
  const std::vector<Case> cases = {
      {"params: &a {p: *a}\nnodes: {}\n", "s.yaml:1:16: an alias refers to a node that contains it"},
      {"nodes:\n  k: &n { type: cam.kurz, params: { max_lift: [*n] } }\n", "s.yaml:2:48: an alias refers to a node that contains it"},
      {bomb, "more than 1000000 YAML nodes"},
      {"title: a\nnodes: {}\ntitle: b\n", "s.yaml:3:1: the key 'title' is given twice in one map (first at line 1, column 1)"},
      {"nodes:\n  k: { type: cam.kurz, type: cam.kurz }\n", "s.yaml:2:24: the key 'type' is given twice in one map (first at line 2, column 8)"},
      {"title: \"caf\xC3\"\nnodes: {}\n", "s.yaml:1:12: byte 0xC3 is not UTF-8"},
      {"nodes: {}\n# \xED\xA0\x80 a surrogate\n", "s.yaml:2:3: byte 0xED is not UTF-8"},
      {std::string(200, '[') + std::string(200, ']') + "\n", "s.yaml"},
      // 300000 numbers in 600 kB: refused from the parser's events, before yaml-cpp builds a tree of them.
      {"params:\n  x: [" + [] { std::string l; for (int i = 0; i < 300000; ++i) l += i ? ",0" : "0"; return l; }() + "]\nnodes: {}\n",
       "s.yaml:2:"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.expected);
    const auto scene = s.write("s.yaml", c.text);
    const auto start = std::chrono::steady_clock::now();
    const Outcome o = run_mechgraph({"validate", scene.string()});
    CHECK(o.exit_code == 2);
    CHECK_THAT(o.err, Contains(c.expected));
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
  }
  // --set values go through the same bounds.
  const Outcome set = run_mechgraph({"validate", source_file("scenes/valvetrain_cams.yaml"), "--set", "kurz.max_lift=&a [*a]"});
  CHECK(set.exit_code == 2);
  CHECK_THAT(set.err, Contains("an alias refers to a node that contains it"));
}

TEST_CASE("hostile: a scene file must be a regular file of bounded size, read without blocking", "[hostile]") {
  Scratch s("files");
  REQUIRE(::mkfifo((s.dir / "fifo.yaml").c_str(), 0600) == 0);
  std::filesystem::create_directories(s.dir / "folder.yaml");
  {
    std::ofstream big(s.dir / "big.yaml");
    big << "title: \"" << std::string((1u << 20) + 10, 'x') << "\"\nnodes: {}\n";
  }
  const std::vector<std::pair<std::string, std::string>> cases = {
      {(s.dir / "fifo.yaml").string(), "is a FIFO (named pipe), not a regular file"},
      {"/dev/zero", "is a character device, not a regular file"},
      {(s.dir / "folder.yaml").string(), "is a folder"},
      {(s.dir / "big.yaml").string(), "more than the limit of 1048576 bytes (1 MiB)"},
      {(s.dir / "missing.yaml").string(), "cannot open"},
  };
  for (const auto& [file, expected] : cases) {
    CAPTURE(file);
    const Outcome o = run_mechgraph({"validate", file});
    CHECK_FALSE(o.timed_out);
    CHECK(o.exit_code == 2);
    CHECK_THAT(o.err, Contains(expected));
  }
}

TEST_CASE("hostile: a failed write to standard output is exit 5, never a silent 0", "[hostile]") {
  const std::string scene = source_file("scenes/tolerance_stack.yaml");
  const std::vector<std::vector<std::string>> commands = {
      {"run", scene, "--json"}, {"run", scene}, {"graph", scene}, {"plugins"}, {"plugins", "--json"},
      {"describe", "cam.kurz"}, {"validate", scene}};
  for (const auto& args : commands) {
    CAPTURE(args);
    CHECK(run_mechgraph(args, std::filesystem::temp_directory_path(), "/dev/full").exit_code == 5);
  }
}

TEST_CASE("hostile: work beyond the budget is refused before it starts, naming the biggest term", "[hostile]") {
  Scratch s("budget");
  std::string text = "nodes:\n";
  for (int i = 1; i <= 3; ++i)
    text += "  k" + std::to_string(i) + ": { type: cam.kurz, params: { max_lift: 8 mm, action_angle: 130 deg, accel_angle: 18 deg, "
            "base_radius: 17 mm, curve_points: " + std::to_string(i * 100000) + " } }\n";
  text += "outputs: [ k1.svaj, k2.svaj, k3.svaj ]\n";
  const auto scene = s.write("big.yaml", text);
  // 600000 rows of curves: about 100 MiB of CSV, over a budget of 10 MB.
  const Outcome o = run_mechgraph({"run", scene.string(), "--out", (s.dir / "o").string(), "--max-output", "1e7"});
  CHECK(o.exit_code == 2);
  CHECK_THAT(o.err, Contains("the biggest term is k3's curves (300000 rows)"));
  CHECK_THAT(o.err, Contains("--max-output"));
  CHECK_FALSE(std::filesystem::exists(s.dir / "o"));
  const Outcome w = run_mechgraph({"validate", scene.string(), "--max-work", "1e5"});
  CHECK(w.exit_code == 2);
  CHECK_THAT(w.err, Contains("the biggest term is k3.curve_points = 300000"));
  CHECK_THAT(w.err, Contains("--max-work"));
  // Within the budget (the same scene without files) it runs.
  CHECK(run_mechgraph({"validate", scene.string()}).exit_code == 0);
  CHECK(run_mechgraph({"run", scene.string(), "--max-work", "0"}).exit_code == 2);
}

TEST_CASE("hostile: a 100 kB value gives a short error message", "[hostile]") {
  // 100 kB: one argument of a program may hold at most 128 KiB (MAX_ARG_STRLEN); a scene value may be longer.
  const std::string huge(100000, '9');
  const Outcome o = run_mechgraph({"validate", source_file("scenes/valvetrain_cams.yaml"), "--set", "kurz.max_lift=" + huge + " furlongs"});
  CHECK(o.exit_code == 2);
  CHECK(o.err.size() < 5000);
}

TEST_CASE("hostile: a half-megabyte value in a scene gives a short error message", "[hostile]") {
  Scratch s("mega");
  const auto scene = s.write("mega.yaml", "nodes:\n  k: { type: cam.kurz, params: { max_lift: \"" + std::string(1 << 19, '9') +
                                              " furlongs\", action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }\n");
  const Outcome o = run_mechgraph({"validate", scene.string()});
  CHECK(o.exit_code == 2);
  CHECK_THAT(o.err, Contains("mega.yaml:2:"));
  CHECK(o.err.size() < 5000);
}

TEST_CASE("hostile: contours with a hostile title are written as DXF that ezdxf reads and audits clean", "[hostile]") {
  Scratch s("dxf");
  std::string scene = slurp(source_file("scenes/cam_contour.yaml"));
  const std::string title = "title: Kurz cam for a flat tappet and an offset roller";
  REQUIRE(scene.find(title) != std::string::npos);
  scene.replace(scene.find(title), title.size(), "title: \"0\\nSECTION\\n2\\nENTITIES <x> 'q' \\\"d\\\" `id`\"");
  const auto file = s.write("contour.yaml", scene);
  const Outcome r = run_mechgraph({"run", file.string(), "--out", (s.dir / "cam").string()});
  REQUIRE(r.exit_code == 0);
  std::size_t dxf = 0;
  for (const auto& e : std::filesystem::directory_iterator(s.dir / "cam")) dxf += e.path().extension() == ".dxf";
  CHECK(dxf == 2);
  const Outcome check = run_argv("/usr/bin/python3", {source_file("tests/hostile/check_outputs.py"), (s.dir / "cam").string()});
  CHECK(check.exit_code == 0);
  CHECK(check.err.empty());
}

TEST_CASE("hostile: which nodes are evaluated and which reused does not depend on --threads", "[hostile]") {
  Scratch s("threads");
  std::string text = "nodes:\n";
  for (const char* k : {"a", "b", "c", "d"})
    text += std::string("  ") + k + ": { type: cam.kurz, params: " + kurz_params + " }\n";
  text += "  e: { type: cam.kurz, params: { max_lift: 9 mm, action_angle: 130 deg, accel_angle: 18 deg, base_radius: 17 mm } }\n";
  for (const char* k : {"a", "b", "c", "d", "e"})
    text += std::string("  v") + k + ": { type: valvetrain.valve_motion, inputs: { cam: " + k + ".law }, params: { rpm: 5600 rpm } }\n";
  text += "outputs: [ va.max_velocity, vb.max_velocity, vc.max_velocity, vd.max_velocity, ve.max_velocity ]\n";
  const auto scene = s.write("same.yaml", text);
  const Outcome one = run_mechgraph({"run", scene.string(), "--json", "--threads", "1"});
  REQUIRE(one.exit_code == 0);
  const auto lists = [](const std::string& json) {
    const auto from = json.find("\"evaluated\"");
    return json.substr(from, json.find(']', json.find("\"reused\"")) + 1 - from);
  };
  CHECK(lists(one.out) == R"("evaluated":["a","e","va","ve"],"reused":["b","c","d","vb","vc","vd"])");
  for (int repeat = 0; repeat < 5; ++repeat)
    for (const char* threads : {"2", "4", "16"}) {
      const Outcome many = run_mechgraph({"run", scene.string(), "--json", "--threads", threads});
      REQUIRE(many.exit_code == 0);
      CHECK(lists(many.out) == lists(one.out));
    }
  for (const char* threads : {"-1", "5000"}) {
    const Outcome bad = run_mechgraph({"run", scene.string(), "--threads", threads});
    CHECK(bad.exit_code == 2);
  }
}

TEST_CASE("hostile: a sweep's work is estimated over all its cases before the first runs", "[hostile]") {
  Scratch s("sweep_budget");
  const std::string scene = source_file("scenes/tolerance_stack.yaml");
  // Each case with its own value (issue 28): 11 cases of 100000 .. 200000 samples. (A case whose value
  // the parameter refuses, a sampled 1234.5 samples, fails before any work and costs nothing.)
  const Outcome o = run_mechgraph({"sweep", scene, "--vary", "gap.samples=100000:200000:11", "--max-work", "1e5",
                                   "--out", (s.dir / "rows.csv").string()});
  CHECK(o.exit_code == 2);
  CHECK_THAT(o.err, Contains("over 11 cases, more than the budget of 100000"));
  CHECK_THAT(o.err, Contains("gap.samples = 200000"));
  CHECK_FALSE(std::filesystem::exists(s.dir / "rows.csv"));
}
