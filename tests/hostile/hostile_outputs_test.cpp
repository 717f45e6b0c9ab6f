// Issue 28, classes 4 to 6: files that are silently wrong (JSON with a key twice or a raw control
// character, gnuplot reading quoted labels its own way), resume and merge mixing inputs, and
// outputs on a full disk. Each test runs the built command as a subprocess and checks the exit
// code, the message and what is on disk; JSON is read back by Python's strict parser.
#include "hostile/hostile_support.hpp"
#include "file_support.hpp"
#include "test_support.hpp"
#include "sanitizer_build.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <fstream>
#include <random>
#include <regex>
#include <sstream>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return scratch_dir("mechgraph_hostile_outputs"); }

fs::path fresh_dir(const std::string& name) { return mechgraph::testing::fresh_dir(work_dir(), name); }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }
std::string plugins() { return "--plugin-dir '" + std::string(MECHGRAPH_PLUGIN_DIR) + "' "; }

// "" when `file` is JSON as RFC 8259 has it, read by Python's json module strictly: no raw control
// character in a string, no NaN or Infinity, no key twice in one object, nothing after the value
// (JSON Lines: every line on its own). Else Python's complaint.
std::string strict_json_problem(const fs::path& file, bool lines = false) {
  const std::string program =
      "import json,sys\n"
      "def pairs(p):\n"
      "    keys=[k for k,_ in p]\n"
      "    if len(keys)!=len(set(keys)): raise ValueError('a key twice: '+repr(keys))\n"
      "    return dict(p)\n"
      "def constant(c): raise ValueError('not JSON: '+c)\n"
      "text=open(sys.argv[1],'rb').read().decode('utf-8')\n"
      "docs=text.splitlines() if sys.argv[2]=='1' else [text]\n"
      "for d in docs: json.loads(d, strict=True, object_pairs_hook=pairs, parse_constant=constant)\n";
  const fs::path script = work_dir() / "strict_json.py";
  write_file(script, program);
  const auto r = run_command("python3 " + q(script) + " " + q(file) + (lines ? " 1" : " 0"));
  return r.exit_code == 0 ? std::string() : r.err;
}

std::string strict_json_text_problem(const std::string& text) {
  const fs::path file = work_dir() / "stdout.json";
  write_file(file, text);
  return strict_json_problem(file);
}

// A chain whose link labels and title are `labels` and `title` (YAML double-quoted escapes).
std::string chain_scene(const std::string& title, const std::vector<std::string>& labels) {
  std::string text = "title: \"" + title + "\"\nnodes:\n  c:\n    type: stack.linear\n    params:\n      links:\n";
  for (std::size_t i = 0; i < labels.size(); ++i)
    text += "        - { label: \"" + labels[i] + "\", nominal: " + std::to_string(10 + i) + " mm, upper: 0." + std::to_string(i + 1) +
            " mm, lower: -0.1 mm, sensitivity: " + (i % 2 ? "-1" : "1") + " }\n";
  return text + "outputs: [ c.contribution_rss, c.contribution_worst_case, c.mean ]\n";
}

// A scene of the arithmetic test plugin, swept over `len`.
const char* arith_scene = R"(title: sweep
params: { len: 2 mm }
nodes:
  a: { type: test.constant, params: { value: $len } }
  s: { type: test.add, inputs: { a: a.out, b: a.out }, params: { gain: 1.5 } }
outputs: [ s.sum ]
)";

// A finished sweep made to look stopped: FILE back to FILE.part, the manifest not complete.
void as_if_stopped(const fs::path& out) {
  fs::rename(out, out.string() + ".part");
  const fs::path manifest = out.string() + ".json";
  std::string m = slurp(manifest);
  const auto at = m.find("\"complete\":true");
  REQUIRE(at != std::string::npos);
  m.replace(at, 15, "\"complete\":false");
  write_file(manifest, m);
}

// The folder's entries whose name holds `part` (a temporary or staging left behind).
std::vector<std::string> entries_with(const fs::path& dir, const std::string& part) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(part) != std::string::npos) found.push_back(e.path().filename().string());
  return found;
}

// A fake helper program (gnuplot, chromium) on a PATH of its own, ahead of the real one: a Python
// script, so the test controls what "the helper" writes.
std::string path_with_fake(const fs::path& bin, const std::string& name, const std::string& python) {
  fs::create_directories(bin);
  const fs::path program = bin / name;
  write_file(program, "#!/usr/bin/env python3\n" + python);
  fs::permissions(program, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read);
  return "PATH=" + q(bin) + ":\"$PATH\" ";
}

}  // namespace

TEST_CASE("hostile JSON: the shipped tolerance stack's links sharing a label are no key twice", "[hostile][json]") {
  const auto r = run_cli(plugins() + "-q run '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/tolerance_stack.yaml' --json");
  REQUIRE(r.exit_code == 0);
  CHECK(strict_json_text_problem(r.out).empty());
  // Each of the two bearings and sleeves is numbered; none hides behind the other.
  CHECK_THAT(r.out, Contains("\"bearing #1\":") && Contains("\"bearing #2\":") && Contains("\"sleeve #1\":") && Contains("\"sleeve #2\":"));
  CHECK_THAT(r.out, Contains("\"shaft\":"));
}

TEST_CASE("hostile JSON: random control characters in scene text always give strict JSON", "[hostile][json]") {
  // A property test: titles and labels of random C0 controls, DEL, C1 controls, quotes, backslashes,
  // commas and repeated labels; run --json and run --out's results.json must parse strictly.
  std::mt19937 random(28);
  const std::vector<std::string> pieces = {"\\x01", "\\x07", "\\x08", "\\t", "\\n", "\\r", "\\x0b", "\\x0c", "\\e", "\\x1f", "\\x7f",
                                           "\\x85", "\\x9b", "\\u2028", "\\\"", "\\\\", ",", "'", "a", " ", "\\0", "]0;title\\x07"};
  auto text = [&] {
    std::string t;
    const int n = 1 + static_cast<int>(random() % 8);
    for (int i = 0; i < n; ++i) t += pieces[random() % pieces.size()];
    return t;
  };
  const fs::path dir = fresh_dir("json_property");
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<std::string> labels{text(), text(), text()};
    labels.push_back(labels[trial % 3]);  // a label twice
    const std::string scene = write_file(dir / "scene.yaml", chain_scene(text(), labels));
    const auto r = run_cli(plugins() + "-q run " + q(scene) + " --json --out " + q(dir / "out") + " --force");
    INFO(slurp(scene) << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(strict_json_text_problem(r.out).empty());
    CHECK(strict_json_problem(dir / "out" / "results.json").empty());
    CHECK(r.out.find('\x1b') == std::string::npos);
  }
}

TEST_CASE("hostile gnuplot: labels with quotes and commas reach the plot whole", "[hostile][report]") {
  if (find_on_path("gnuplot").empty()) FAIL("gnuplot is not installed (scripts/install-deps.sh installs gnuplot-nox): the report cannot be drawn");
  const fs::path dir = fresh_dir("gnuplot_labels");
  const std::vector<std::string> labels{"shaft 1\\\", ground", "a,b", "it''s", "\\\"", "'lead", "plain"};
  const std::string scene = write_file(dir / "scene.yaml", chain_scene("labels", labels));
  const auto r = run_cli(plugins() + "-q report " + q(scene) + " --out " + q(dir / "report"));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string page = slurp(dir / "report" / "report.html");
  // The bar chart's tic labels as gnuplot drew them: every label once per chart, in order.
  std::vector<std::string> drawn;
  const std::regex text_element("<text>([^<]*)</text>");
  for (std::sregex_iterator it(page.begin(), page.end(), text_element), end; it != end; ++it) drawn.push_back((*it)[1]);
  // (Two quotes in a row are drawn with a zero-width space between them: gnuplot_string.)
  const std::vector<std::string> expected{"shaft 1\", ground", "a,b", "it'\xE2\x80\x8B's", "\"", "\xE2\x80\x8B'lead", "plain"};
  std::size_t charts = 0;
  for (std::size_t i = 0; i + expected.size() <= drawn.size(); ++i)
    if (std::equal(expected.begin(), expected.end(), drawn.begin() + static_cast<long>(i))) ++charts;
  CHECK(charts == 2);  // contribution_rss and contribution_worst_case
}

TEST_CASE("hostile sweep --out: a folder is refused before any lock, missing folders are made", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("out_folder");
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  const std::string sweep = arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:3mm:3 ";
  fs::create_directories(dir / "DIR");
  auto r = run_cli(sweep + "--out " + q(dir / "DIR") + "/");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("name a file"));
  CHECK(fs::is_empty(dir / "DIR"));  // no DIR/.lock
  r = run_cli(sweep + "--out " + q(dir / "DIR"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("is a folder"));
  // A user's own DIR/.lock is never touched.
  write_file(dir / "DIR" / ".lock", "12345\n");
  CHECK(run_cli(sweep + "--out " + q(dir / "DIR") + "/").exit_code == 2);
  CHECK(slurp(dir / "DIR" / ".lock") == "12345\n");
  // As run --out makes a/b/DIR, sweep and merge make a/b for a/b/x.csv.
  r = run_cli(sweep + "--out " + q(dir / "a" / "b" / "x.csv"));
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::is_regular_file(dir / "a" / "b" / "x.csv"));
  r = run_cli("merge " + q(dir / "a" / "b" / "x.csv") + " --out " + q(dir / "c" / "d" / "all.csv"));
  CHECK(r.exit_code == 0);
  CHECK(slurp(dir / "c" / "d" / "all.csv") == slurp(dir / "a" / "b" / "x.csv"));
}

TEST_CASE("hostile sweep --resume: an edited lift table is another sweep", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("fingerprint_files");
  fs::create_directories(dir / "data");
  fs::copy_file(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/cam_table.yaml", dir / "cam_table.yaml");
  fs::copy_file(std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/data/cycloidal_lift.csv", dir / "data" / "cycloidal_lift.csv");
  const std::string sweep = plugins() + "-q sweep " + q(dir / "cam_table.yaml") + " --vary rpm=5000rpm:6000rpm:3 --out " + q(dir / "rows.csv");
  REQUIRE(run_cli(sweep).exit_code == 0);
  as_if_stopped(dir / "rows.csv");
  // The table changes while the sweep is stopped: its rows must not be carried on with the new one.
  std::ofstream(dir / "data" / "cycloidal_lift.csv", std::ios::app) << "# measured again\n";
  const auto r = run_cli(sweep + " --resume");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("another sweep") && Contains("a file it reads"));
  CHECK_FALSE(fs::exists(dir / "rows.csv"));
}

TEST_CASE("hostile sweep --resume: JSON Lines rows must carry their case's inputs", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("jsonl_inputs");
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  const std::string sweep =
      arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:4mm:4 --format jsonl --out " + q(dir / "rows.jsonl");
  REQUIRE(run_cli(sweep).exit_code == 0);
  CHECK(strict_json_problem(dir / "rows.jsonl", true).empty());
  as_if_stopped(dir / "rows.jsonl");
  std::string rows = slurp(dir / "rows.jsonl.part");
  const auto at = rows.find(":2,");  // case 1's len, 2 mm
  REQUIRE(at != std::string::npos);
  rows.replace(at, 3, ":7,");
  write_file(dir / "rows.jsonl.part", rows);
  const auto r = run_cli(sweep + " --resume");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("rows.jsonl.part:2") && Contains("holds '7'"));
}

TEST_CASE("hostile sweep --resume: FILE.part is checked before its last line is cut", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("resume_cut");
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  const std::string sweep = arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:4mm:4 --out " + q(dir / "rows.csv");
  REQUIRE(run_cli(sweep).exit_code == 0);
  const std::string whole = slurp(dir / "rows.csv");
  as_if_stopped(dir / "rows.csv");
  const fs::path part = dir / "rows.csv.part";
  // Not rows: a line that is no row before the unfinished one; the file stays as it was.
  for (const std::string& tail : {std::string("not a row\n3,"), std::string("zzz")}) {
    const std::string before = whole.substr(0, whole.find('\n', whole.find('\n') + 1) + 1) + tail;
    write_file(part, before);
    const auto r = run_cli(sweep + " --resume");
    INFO(tail);
    CHECK(r.exit_code == 2);
    CHECK(slurp(part) == before);
  }
  // A row cut by a kill ("2,2" of "2,3,...") is cut, and the sweep goes on to the same rows.
  const std::size_t third = whole.find('\n', whole.find('\n', whole.find('\n') + 1) + 1) + 1;
  write_file(part, whole.substr(0, third) + "2,3");
  const auto r = run_cli(sweep + " --resume");
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(slurp(dir / "rows.csv") == whole);
}

TEST_CASE("hostile merge: JSON Lines shards must have the same keys", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("merge_keys");
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  const std::string sweep = arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:4mm:4 --format jsonl ";
  REQUIRE(run_cli(sweep + "--shard 0/2 --out " + q(dir / "p0.jsonl")).exit_code == 0);
  REQUIRE(run_cli(sweep + "--shard 1/2 --out " + q(dir / "p1.jsonl")).exit_code == 0);
  auto r = run_cli("merge " + q(dir / "p0.jsonl") + " " + q(dir / "p1.jsonl"));
  REQUIRE(r.exit_code == 0);
  write_file(dir / "all.jsonl", r.out);
  CHECK(strict_json_problem(dir / "all.jsonl", true).empty());
  // Shard 1's output column renamed in every row: the rows would read as another quantity.
  std::string rows = slurp(dir / "p1.jsonl");
  for (std::size_t at = rows.find("\"s.sum"); at != std::string::npos; at = rows.find("\"s.sum", at)) rows.replace(at, 6, "\"other");
  write_file(dir / "p1.jsonl", rows);
  r = run_cli("merge " + q(dir / "p0.jsonl") + " " + q(dir / "p1.jsonl"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("other keys"));
  CHECK(r.out.empty());
}

TEST_CASE("hostile merge: memory does not grow with the rows", "[hostile][sweep][slow]") {
#if defined(MECHGRAPH_TEST_ADDRESS_SANITIZER) || defined(MECHGRAPH_TEST_THREAD_SANITIZER)
  WARN("built with a sanitizer, whose shadow memory makes resident size meaningless: not measured");
  return;
#endif
  if (!fs::exists("/usr/bin/time")) FAIL("no /usr/bin/time (scripts/install-deps.sh installs time): the memory of merge cannot be measured");
  const fs::path dir = fresh_dir("merge_memory");
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  // The largest resident set of merging two shards of `cases` cases, in KiB.
  auto merge_kib = [&](std::size_t cases) {
    const std::string sweep =
        arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:9mm:" + std::to_string(cases) + " --force ";
    REQUIRE(run_cli(sweep + "--shard 0/2 --out " + q(dir / "p0.csv")).exit_code == 0);
    REQUIRE(run_cli(sweep + "--shard 1/2 --out " + q(dir / "p1.csv")).exit_code == 0);
    const auto r = run_command("/usr/bin/time -f '%M' '" + std::string(MECHGRAPH_CLI) + "' -q merge " + q(dir / "p0.csv") + " " +
                               q(dir / "p1.csv") + " --out " + q(dir / "all.csv") + " --force");
    REQUIRE(r.exit_code == 0);
    return std::stol(r.err.substr(r.err.find_last_of('\n', r.err.size() - 2) + 1));
  };
  const long small = merge_kib(2000);
  const long large = merge_kib(200000);  // about 9.5 MB of rows
  INFO("merge of 2000 cases: " << small << " KiB, of 200000 cases: " << large << " KiB");
  CHECK(fs::file_size(dir / "all.csv") > 9'000'000);
  CHECK(large - small < 4096);  // holding the rows took about 6x their size
}

TEST_CASE("hostile disk: a file-size limit (a full disk) is exit 5 and publishes nothing", "[hostile][disk]") {
  if (find_on_path("prlimit").empty()) FAIL("no prlimit (util-linux): the full-disk cases cannot run");
  const fs::path dir = fresh_dir("fsize");
  const std::string limited = "prlimit --fsize=3000 '" + std::string(MECHGRAPH_CLI) + "' " + plugins() + "-q ";
  const std::string stack = "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/tolerance_stack.yaml' ";
  // run --out: results.json is larger than the limit.
  auto r = run_command(limited + "run " + stack + "--out " + q(dir / "run"));
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.err, Contains("File too large"));
  CHECK_FALSE(fs::exists(dir / "run"));
  CHECK(entries_with(dir, "staging").empty());
  // report --out: its page and data.
  r = run_command(limited + "report " + stack + "--out " + q(dir / "report"));
  CHECK(r.exit_code == 5);
  CHECK_FALSE(fs::exists(dir / "report"));
  CHECK(entries_with(dir, "staging").empty());
  // sweep --out and merge --out.
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  const std::string sweep = arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:9mm:500 ";
  r = run_command("prlimit --fsize=3000 '" + std::string(MECHGRAPH_CLI) + "' " + sweep + "--out " + q(dir / "rows.csv"));
  CHECK(r.exit_code == 5);
  CHECK_FALSE(fs::exists(dir / "rows.csv"));
  REQUIRE(run_cli(sweep + "--out " + q(dir / "big.csv")).exit_code == 0);
  r = run_command("prlimit --fsize=3000 '" + std::string(MECHGRAPH_CLI) + "' -q merge " + q(dir / "big.csv") + " --out " + q(dir / "all.csv"));
  CHECK(r.exit_code == 5);
  CHECK_FALSE(fs::exists(dir / "all.csv"));
  CHECK(entries_with(dir, "tmp").empty());
}

TEST_CASE("hostile disk: bench --out never keeps an empty or cut SVG", "[hostile][disk]") {
  const fs::path dir = fresh_dir("bench_svg");
  // A gnuplot that stops after a part of the SVG and says nothing (what a full disk did).
  const std::string path = path_with_fake(dir / "bin", "gnuplot",
                                          "open('bench.svg','w').write('<?xml version=\"1.0\"?>\\n<svg width=\"900\" ')\n");
  const std::string bench = "bench '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/backlash_chain.yaml' " +
                            "--steps 1 --repeats 1 --seeds 2 --node chain --set chain.samples=2000 --out " + q(dir / "out");
  const auto r = run_command(path + "'" + std::string(MECHGRAPH_CLI) + "' " + plugins() + "-q " + bench);
  INFO(r.err);
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.err, Contains("bench.svg"));
  CHECK_FALSE(fs::exists(dir / "out"));
  CHECK(entries_with(dir, "staging").empty());
}

TEST_CASE("hostile disk: report --pdf keeps no cut PDF, chromium's files stay out of HOME", "[hostile][disk][report]") {
  if (find_on_path("gnuplot").empty()) FAIL("gnuplot is not installed (scripts/install-deps.sh installs gnuplot-nox): the report cannot be drawn");
  const fs::path dir = fresh_dir("report_pdf");
  const fs::path seen = dir / "chromium-env.txt";
  // A chromium that notes its environment and arguments, then writes a PDF cut short (a full disk)
  // and exits 0, as the real one did.
  const std::string path = path_with_fake(dir / "bin", "chromium",
                                          "import os,sys\n"
                                          "open('" + seen.string() + "','w').write(repr((dict(os.environ), sys.argv)))\n"
                                          "pdf=[a for a in sys.argv if a.startswith('--print-to-pdf=')][0].split('=',1)[1]\n"
                                          "open(pdf,'wb').write(b'%PDF-1.4\\n%\\xe2\\xe3\\n1 0 obj\\n<< /Type /Catalog /Pages 2 0 R')\n");
  const std::string report =
      "report '" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/tolerance_stack.yaml' --pdf --out " + q(dir / "report");
  const auto r = run_command(path + "'" + std::string(MECHGRAPH_CLI) + "' " + plugins() + "-q " + report);
  INFO(r.err);
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.err, Contains("no whole PDF") && Contains("%%EOF"));
  CHECK_FALSE(fs::exists(dir / "report"));
  CHECK(entries_with(dir, "staging").empty());
  // Its HOME, XDG folders and crash dumps: a private folder, not the user's home, removed after.
  const std::string env = slurp(seen);
  const char* home = std::getenv("HOME");
  const std::smatch found = [&] {
    std::smatch m;
    std::regex_search(env, m, std::regex("'HOME': '([^']*)'"));
    return m;
  }();
  REQUIRE(found.size() == 2);
  const std::string chromium_home = found[1];
  CHECK(chromium_home.find("mechgraph-chromium-") != std::string::npos);
  if (home) CHECK(chromium_home != home);
  CHECK_FALSE(fs::exists(chromium_home));
  CHECK_THAT(env, Contains("'XDG_CONFIG_HOME': '" + chromium_home) && Contains("--crash-dumps-dir=") && Contains("--disable-breakpad"));
}

TEST_CASE("hostile names: a 240-byte --out works, a name too long for FILE.part is refused clearly", "[hostile][out]") {
  const fs::path dir = fresh_dir("long_names");
  const std::string stack = "'" + std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/tolerance_stack.yaml' ";
  const std::string long_name(240, 'x');
  auto r = run_cli(plugins() + "-q run " + stack + "--out " + q(dir / long_name));
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::is_regular_file(dir / long_name / "results.json"));
  r = run_cli(plugins() + "-q run " + stack + "--out " + q(dir / long_name) + " --force");  // the swap's staging too
  CHECK(r.exit_code == 0);
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  const std::string sweep = arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:3mm:3 ";
  r = run_cli(sweep + "--out " + q(dir / (long_name + ".csv")));
  CHECK(r.exit_code == 0);
  CHECK(fs::is_regular_file(dir / (long_name + ".csv.json")));
  r = run_cli(sweep + "--out " + q(dir / std::string(252, 'y')));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("at most 250"));
}

TEST_CASE("hostile JSON: every command's JSON is strict JSON", "[hostile][json]") {
  const fs::path dir = fresh_dir("json_writers");
  const std::string scenes = std::string(MECHGRAPH_SOURCE_DIR) + "/scenes/";
  const std::vector<std::string> commands = {"plugins --json", "describe stack.linear --json", "describe cam.table --json",
                                             "plugin-test stack.linear --json",
                                             "bench '" + scenes + "culling_demo.yaml' --node ta_kurz --steps 1 --repeats 1 --json",
                                             "run '" + scenes + "backlash_chain.yaml' --json"};
  for (const std::string& c : commands) {
    const auto r = run_cli(plugins() + "-q " + c);
    INFO(c << "\n" << r.err);
    CHECK(r.exit_code == 0);
    CHECK(strict_json_text_problem(r.out).empty());
  }
  // A sweep's manifest, and the rows as JSON Lines.
  const std::string scene = write_file(dir / "scene.yaml", arith_scene);
  REQUIRE(run_cli(arith_plugin_dir_option() + " -q sweep " + q(scene) + " --vary len=1mm:3mm:3 --format jsonl --out " + q(dir / "r.jsonl"))
              .exit_code == 0);
  CHECK(strict_json_problem(dir / "r.jsonl.json").empty());
  CHECK(strict_json_problem(dir / "r.jsonl", true).empty());
}
