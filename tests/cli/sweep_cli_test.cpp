// `mechgraph sweep` and `mechgraph merge` end to end: the rows a user gets, a sweep killed with
// kill -9 and resumed (no case lost or doubled), Ctrl-C, shards merged back and checked.
#include "file_support.hpp"
#include "test_support.hpp"

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::StartsWith;
namespace fs = std::filesystem;

namespace {

std::string arith_dir() { return arith_plugin_dir_option(); }
fs::path work_dir() { return scratch_dir("mechgraph_sweep_cli"); }

// `text` as the file `name` in this test's scratch folder.
std::string scratch_file(const std::string& name, const std::string& text) {
  return mechgraph::testing::write_file(work_dir() / name, text);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

const char* scene_text = R"(title: sweep
params: { len: 2 mm }
nodes:
  a: { type: test.constant, params: { value: $len } }
  s: { type: test.add, inputs: { a: a.out, b: a.out }, params: { gain: 1.5 } }
  c: { type: test.series, params: { points: 3 } }
outputs: [ s.sum, c.curve ]
)";

// A sweep slow enough to be caught mid-way: each case waits `delay` in a node.
const char* slow_scene = R"(title: slow
params: { x: 1 mm }
nodes:
  slow: { type: test.slow, params: { value: $x, delay: 15 ms } }
outputs: [ slow.out ]
)";

// Starts the command in the background; returns its process id. Its exit status lands in
// `status_file` when it ends.
pid_t start_cli(const std::string& args, const fs::path& status_file) {
  return mechgraph::testing::start_cli_in_background(args, status_file, work_dir() / "pid");
}

// Waits until `file` has at least `lines` lines (or 20 s pass).
void wait_for_lines(const fs::path& file, std::size_t lines) {
  for (int i = 0; i < 2000; ++i) {
    if (fs::exists(file) && lines_of(slurp(file)).size() >= lines) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  FAIL("no rows appeared in " << file);
}

// Waits for the status a command started by start_cli leaves, and returns it.
std::string wait_status(const fs::path& status_file) {
  for (int i = 0; i < 3000; ++i) {
    const std::string s = slurp(status_file);
    if (!s.empty() && s.back() == '\n') return s;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return "(still running)";
}

}  // namespace

TEST_CASE("sweep: one tidy CSV row per case with inputs, outputs in display units, exit and error", "[cli][sweep]") {
  const std::string scene = scratch_file("scene.yaml", scene_text);
  const auto r = run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm:3mm:3 --vary s.gain=1,-2 --threads 2");
  REQUIRE(r.exit_code == 0);
  const auto rows = lines_of(r.out);
  REQUIRE(rows.size() == 7);
  CHECK(rows[0] == "case,len [mm],s.gain,s.sum [m],c.curve[0] [m],c.curve[1] [m],c.curve[2] [m],exit,error");
  CHECK(rows[1] == "0,1,1,0.002,0,0.25,1,0,");
  // A case out of range fails alone, with its exit class and the reason.
  CHECK_THAT(rows[2], StartsWith("1,1,-2,,,,,2,") && Contains("out of range: it must be > 0"));
  CHECK_THAT(rows[5], StartsWith("4,3,1,0.006,"));  // the shortest text that reads back the same double
  CHECK_THAT(r.err, Contains("3 of 6 cases failed"));
  // The same value as a single run with --set: the second method.
  const auto one = run_cli(arith_dir() + " run '" + scene + "' --set len=3mm --set s.gain=1 --json");
  REQUIRE(one.exit_code == 0);
  CHECK(YAML::Load(one.out)["outputs"]["s.sum"]["value"].as<double>() == std::stod("0.006"));
}

TEST_CASE("sweep --format jsonl: one JSON object per case, keys as the CSV's columns", "[cli][sweep]") {
  const std::string scene = scratch_file("scene.yaml", scene_text);
  const auto r = run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm,2mm --outputs s.sum --format jsonl");
  REQUIRE(r.exit_code == 0);
  const auto rows = lines_of(r.out);
  REQUIRE(rows.size() == 2);
  const YAML::Node second = YAML::Load(rows[1]);
  CHECK(second["case"].as<int>() == 1);
  CHECK(second["len [mm]"].as<double>() == 2.0);
  CHECK(second["s.sum [m]"].as<double>() == 0.006);
  CHECK(second["exit"].as<int>() == 0);
  CHECK(second["error"].IsNull());
}

TEST_CASE("sweep --vary: a bare number in a list takes the list's unit where the parameter has its dimension",
          "[cli][sweep]") {
  const std::string scene = scratch_file("scene.yaml", scene_text);
  // len is a length: 1 is 1 mm, as in len=1:3mm:3; the rows show it as 1, in the column's mm.
  const auto lengths = run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1,2.5mm,3 --outputs s.sum --format jsonl");
  INFO(lengths.out << lengths.err);
  REQUIRE(lengths.exit_code == 0);
  const auto rows = lines_of(lengths.out);
  REQUIRE(rows.size() == 3);
  const double sums[] = {0.003, 0.0075, 0.009};  // gain 1.5 * (len + len)
  for (std::size_t i = 0; i < 3; ++i) {
    const YAML::Node row = YAML::Load(rows[i]);
    CHECK(row["exit"].as<int>() == 0);
    CHECK_THAT(row["s.sum [m]"].as<double>(), Catch::Matchers::WithinRel(sums[i], 1e-15));
  }
  CHECK(YAML::Load(rows[0])["len [mm]"].as<std::string>() == "1");
  // The same value as --set len=1mm gives, bit for bit.
  const auto set = run_cli(arith_dir() + " run '" + scene + "' --set len=1mm --json");
  REQUIRE(set.exit_code == 0);
  CHECK(YAML::Load(set.out)["outputs"]["s.sum"]["value"].as<double>() == YAML::Load(rows[0])["s.sum [m]"].as<double>());
  // gain is dimensionless: its bare numbers stay numbers and the 1mm is the mistake, in its own row.
  const auto gains = run_cli(arith_dir() + " sweep '" + scene + "' --vary s.gain=-1,2,1mm --outputs s.sum --format jsonl");
  INFO(gains.out << gains.err);
  const auto gain_rows = lines_of(gains.out);
  REQUIRE(gain_rows.size() == 3);
  CHECK_THAT(YAML::Load(gain_rows[0])["error"].as<std::string>(), Contains("out of range"));
  CHECK(YAML::Load(gain_rows[1])["exit"].as<int>() == 0);
  CHECK_THAT(YAML::Load(gain_rows[2])["error"].as<std::string>(), Contains("is dimensionless") && Contains("the value is length"));
  // A bare number beyond a double in the list's unit (1e308 h) fails its case as 1e308h written
  // out does, naming node and parameter; the others run.
  const std::string slow = scratch_file("slow.yaml", slow_scene);
  const auto huge = run_cli(arith_dir() + " sweep '" + slow + "' --vary slow.delay=1e308,0h --format jsonl");
  INFO(huge.out << huge.err);
  const auto huge_rows = lines_of(huge.out);
  REQUIRE(huge_rows.size() == 2);
  CHECK_THAT(YAML::Load(huge_rows[0])["error"].as<std::string>(),
             Contains("parameter 'delay' of node 'slow'") && Contains("beyond the range of a double"));
  CHECK(YAML::Load(huge_rows[1])["exit"].as<int>() == 0);
}

TEST_CASE("sweep: usage errors name the fix", "[cli][sweep]") {
  const std::string scene = scratch_file("scene.yaml", scene_text);
  CHECK_THAT(run_cli(arith_dir() + " sweep '" + scene + "'").err, Contains("give the cases one way"));
  CHECK(run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm:2mm:2 --cases x.csv").exit_code == 2);
  CHECK_THAT(run_cli(arith_dir() + " sweep '" + scene + "' --sample len=1mm:2mm").err, Contains("--sample needs --n"));
  CHECK_THAT(run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm:2mm:2 --outputs c.curv").err, Contains("did you mean 'curve'"));
  const auto twice = run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm:2mm:2 --outputs s.sum,s.sum");
  CHECK(twice.exit_code == 2);  // before: one column, without a word
  CHECK_THAT(twice.err, Contains("--outputs: 's.sum' is listed twice; each output is one column: list it once"));
  CHECK_THAT(run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm:2mm:2 --shard 3/3").err, Contains("needs 0 <= I < N"));
  CHECK_THAT(run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm:2mm:2 --resume").err, Contains("--resume needs --out"));
  const auto shard = run_cli(arith_dir() + " sweep '" + scene + "' --vary len=1mm:2mm:2 --shard auto");
  CHECK_THAT(shard.err, Contains("SLURM_ARRAY_TASK_ID"));
}

TEST_CASE("sweep --out: complete under its name at the end, refused when it exists, manifest beside it", "[cli][sweep]") {
  const std::string scene = scratch_file("scene.yaml", scene_text);
  const fs::path out = work_dir() / "rows.csv";
  fs::remove(out);
  const std::string args = arith_dir() + " sweep '" + scene + "' --vary len=1mm:5mm:5 --out '" + out.string() + "'";
  REQUIRE(run_cli(args).exit_code == 0);
  CHECK(lines_of(slurp(out)).size() == 6);
  CHECK_FALSE(fs::exists(out.string() + ".part"));
  const YAML::Node manifest = YAML::LoadFile(out.string() + ".json");
  CHECK(manifest["complete"].as<bool>());
  CHECK(manifest["cases"].as<int>() == 5);
  CHECK(manifest["rows"].as<int>() == 5);
  const auto again = run_cli(args);
  CHECK(again.exit_code == 2);
  CHECK_THAT(again.err, Contains("exists; use --force"));
  CHECK(run_cli(args + " --force").exit_code == 0);
}

// A sweep of the arith scene whose rows and manifest fingerprint (which --resume and merge
// compare) a build before wrote: they must not move with how the table of cases is kept.
struct PinnedSweep {
  std::string cases;  // the options that make the table: --sample ..., --vary ..., --cases FILE
  std::vector<std::string> rows;
  std::string fingerprint;
};

void check_pinned(const PinnedSweep& p) {
  INFO(p.cases);
  const std::string scene = scratch_file("scene.yaml", scene_text);
  const fs::path out = work_dir() / "pinned.csv";
  const auto r = run_cli(arith_dir() + " -q sweep '" + scene + "' " + p.cases + " --out '" + out.string() + "' --force");
  REQUIRE(r.exit_code == 0);
  CHECK(lines_of(slurp(out)) == p.rows);
  CHECK(YAML::LoadFile(out.string() + ".json")["sweep"].as<std::string>() == p.fingerprint);
}

TEST_CASE("sweep --sample: the rows and the fingerprint of a seeded sample are pinned", "[cli][sweep]") {
  // Written by the build before samples were kept as numbers (each value with its exact text): a
  // sample's draw, its values on the unit's numbers, the digits a row shows (a column in mm, one
  // in the SI unit itself at magnitudes where %.15g and the shortest digits differ, a unitless
  // one) and the fingerprint.
  check_pinned({"--sample len=1e15m:2e17m --sample s.gain=0.5:2 --n 4 --seed 3",
                {"case,len [m],s.gain,s.sum [m],c.curve[0] [m],c.curve[1] [m],c.curve[2] [m],exit,error",
                 "0,153875120154396320,0.7619135545255051,234479079499750592,0,0.25,1,0,",
                 "1,61517845661878880,1.516957347676121,186639895979985504,0,0.25,1,0,",
                 "2,132152060207450464,1.0550616890203839,278857151699992288,0,0.25,1,0,",
                 "3,7723506464412241,1.751000223702433,27047723093906040,0,0.25,1,0,"},
                "249865a986934544"});
  check_pinned({"--sample len=1mm:3mm --sample s.gain=0.5:2 --n 4 --seed 3",
                {"case,len [mm],s.gain,s.sum [m],c.curve[0] [m],c.curve[1] [m],c.curve[2] [m],exit,error",
                 "0,2.536433368385892,0.7619135545255051,0.0038650859270479903,0,0.25,1,0,",
                 "1,1.6082195543907427,1.516957347676121,0.004879200939418908,0,0.25,1,0,",
                 "2,2.318111157863824,1.0550616890203839,0.004891500547105607,0,0.25,1,0,",
                 "3,1.0675729292905753,1.751000223702433,0.003738640876012918,0,0.25,1,0,"},
                "cfabda5dec2f859c"});
}

TEST_CASE("sweep --vary: the rows and the fingerprint of a grid of ranges are pinned", "[cli][sweep]") {
  // Written by the build before grids of ranges were kept as numbers (each value with its exact
  // text): the points, the digits a row shows (a column in the SI unit itself at magnitudes where
  // %.15g and the shortest digits differ, one in mm, a unitless one) and the fingerprint.
  check_pinned({"--vary len=1e15m:2e17m:4 --vary s.gain=0.3:0.7:3",
                {"case,len [m],s.gain,s.sum [m],c.curve[0] [m],c.curve[1] [m],c.curve[2] [m],exit,error",
                 "0,1e+15,0.3,6e+14,0,0.25,1,0,", "1,1e+15,0.5,1e+15,0,0.25,1,0,", "2,1e+15,0.7,1.4e+15,0,0.25,1,0,",
                 "3,67333333333333296,0.3,40399999999999976,0,0.25,1,0,", "4,67333333333333296,0.5,67333333333333296,0,0.25,1,0,",
                 "5,67333333333333296,0.7,94266666666666608,0,0.25,1,0,", "6,133666666666667008,0.3,80200000000000208,0,0.25,1,0,",
                 "7,133666666666667008,0.5,133666666666667008,0,0.25,1,0,", "8,133666666666667008,0.7,187133333333333792,0,0.25,1,0,",
                 "9,2e+17,0.3,1.2e+17,0,0.25,1,0,", "10,2e+17,0.5,2e+17,0,0.25,1,0,", "11,2e+17,0.7,279999999999999968,0,0.25,1,0,"},
                "84ad8f67c721c108"});
  check_pinned({"--vary len=1mm:3mm:3 --vary s.gain=0.5:2:2",
                {"case,len [mm],s.gain,s.sum [m],c.curve[0] [m],c.curve[1] [m],c.curve[2] [m],exit,error",
                 "0,1,0.5,0.001,0,0.25,1,0,", "1,1,2,0.004,0,0.25,1,0,", "2,2,0.5,0.002,0,0.25,1,0,", "3,2,2,0.008,0,0.25,1,0,",
                 "4,3,0.5,0.003,0,0.25,1,0,", "5,3,2,0.012,0,0.25,1,0,"},
                "ab34b8a904d3c2a9"});
}

TEST_CASE("sweep --cases: the rows and the fingerprint of a cases file are pinned", "[cli][sweep]") {
  // Written by the build before a cases file's values were kept as numbers with their texts
  // beside them (a string each): bare numbers under the header's unit, a cell with its own unit,
  // quoted and padded cells, a sign, a word the parameter refuses, and the fingerprint.
  const std::string cases = scratch_file("pinned_cases.csv", "# pinned\nlen [mm],s.gain\n1,0.5\n2.5 mm,+2\n\"0.003 m\",1.5\n 4 ,abc\n"
                                                            "1e-1,\"2\"\n5.000,0.25\n");
  check_pinned({"--cases '" + cases + "'",
                {"case,len [mm],s.gain,s.sum [m],c.curve[0] [m],c.curve[1] [m],c.curve[2] [m],exit,error",
                 "0,1,0.5,0.001,0,0.25,1,0,", "1,2.5,2,0.01,0,0.25,1,0,", "2,3,1.5,0.009000000000000001,0,0.25,1,0,",
                 "3,4,abc,,,,,2,s.gain = 'abc': parameter 'gain' of node 's' (test.add): expected a number at the start of 'abc'",
                 "4,1e-1,2,4e-04,0,0.25,1,0,", "5,5.000,0.25,0.0025,0,0.25,1,0,"},
                "f2fe776143d4eb98"});
}

TEST_CASE("sweep: the memory budget counts the table of cases and their order", "[cli][sweep][bounds]") {
  // 10^5 sampled cases of one value: 0.8 MB of table and 0.8 MB of order beside cases of a few
  // bytes each. Within 1 MB they are refused, naming the table as the larger part; within 10 MB
  // they run.
  const std::string scene = scratch_file("scene.yaml", scene_text);
  const std::string sweep = arith_dir() + " -q sweep '" + scene + "' --sample len=1mm:2mm --n 100000 --outputs s.sum ";
  const auto refused = run_cli(sweep + "--max-memory 1e6");
  CHECK(refused.exit_code == 2);
  CHECK_THAT(refused.err, Contains("MiB the sweep's table of cases and order holds beside them") &&
                              Contains("the biggest term is what the sweep's table of cases and order holds beside them") &&
                              Contains("--max-memory"));
  const auto runs = run_cli(sweep + "--max-memory 1e7");
  CHECK(runs.exit_code == 0);
  CHECK(lines_of(runs.out).size() == 100001);
}

TEST_CASE("sweep killed with kill -9, then --resume: no case lost or written twice", "[cli][sweep][slow]") {
  const std::string scene = scratch_file("slow.yaml", slow_scene);
  const fs::path out = work_dir() / "killed.csv", reference = work_dir() / "reference.csv";
  for (const fs::path& p : {out, reference}) {
    fs::remove(p);
    fs::remove(p.string() + ".part");
  }
  const std::string sweep = arith_dir() + " sweep '" + scene + "' --vary x=1mm:60mm:60 --threads 2 -q --out ";
  REQUIRE(run_cli(sweep + "'" + reference.string() + "'").exit_code == 0);

  const fs::path status = work_dir() / "killed-status";
  const pid_t pid = start_cli(sweep + "'" + out.string() + "'", status);
  wait_for_lines(out.string() + ".part", 8);
  ::kill(pid, SIGKILL);
  CHECK(wait_status(status) == "137\n");
  REQUIRE(fs::exists(out.string() + ".part"));
  CHECK_FALSE(fs::exists(out));
  const std::size_t before = lines_of(slurp(out.string() + ".part")).size();
  CHECK(before < 61);
  // A half-written last line (the kill may land mid-write) is cut on resume.
  std::ofstream(out.string() + ".part", std::ios::app) << "57,57";
  const auto fresh = run_cli(sweep + "'" + out.string() + "'");
  CHECK(fresh.exit_code == 2);
  CHECK_THAT(fresh.err, Contains("--resume goes on with it"));
  const auto resumed = run_cli(sweep + "'" + out.string() + "' --resume");
  REQUIRE(resumed.exit_code == 0);
  CHECK(slurp(out) == slurp(reference));
  // Resuming with other cases is refused: the rows belong to another sweep.
  std::ofstream(out.string() + ".part") << "case\n";
  const auto other = run_cli(arith_dir() + " sweep '" + scene + "' --vary x=1mm:61mm:61 -q --out '" + out.string() + "' --resume");
  CHECK(other.exit_code == 2);
  CHECK_THAT(other.err, Contains("another sweep"));
}

TEST_CASE("sweep stopped by Ctrl-C keeps every finished row and exits 130, --resume completes it", "[cli][sweep][slow]") {
  const std::string scene = scratch_file("slow.yaml", slow_scene);
  const fs::path out = work_dir() / "interrupted.csv";
  fs::remove(out);
  fs::remove(out.string() + ".part");
  const std::string sweep = arith_dir() + " sweep '" + scene + "' --vary x=1mm:60mm:60 --threads 2 -q --out '" + out.string() + "'";
  const fs::path status = work_dir() / "interrupted-status";
  const pid_t pid = start_cli(sweep, status);
  wait_for_lines(out.string() + ".part", 6);
  ::kill(pid, SIGINT);
  CHECK(wait_status(status) == "130\n");
  const auto rows = lines_of(slurp(out.string() + ".part"));
  REQUIRE(rows.size() >= 6);
  for (std::size_t r = 1; r < rows.size(); ++r) CHECK_THAT(rows[r], StartsWith(std::to_string(r - 1) + ","));
  REQUIRE(run_cli(sweep + " --resume").exit_code == 0);
  CHECK(lines_of(slurp(out)).size() == 61);
}

TEST_CASE("shards merged back equal the single-process sweep, gaps and overlaps are refused", "[cli][sweep]") {
  const std::string scene = scratch_file("scene.yaml", scene_text);
  const std::string base = arith_dir() + " sweep '" + scene + "' --vary len=1mm:9mm:9 --vary s.gain=1,2 -q";
  std::string parts;
  for (int i = 0; i < 3; ++i) {
    const fs::path part = work_dir() / ("part-" + std::to_string(i) + ".csv");
    fs::remove(part);
    REQUIRE(run_cli(base + " --shard " + std::to_string(i) + "/3 --out '" + part.string() + "'").exit_code == 0);
    parts += " '" + part.string() + "'";
  }
  const auto merged = run_cli("merge" + parts);
  REQUIRE(merged.exit_code == 0);
  CHECK(merged.out == run_cli(base).out);
  const std::string first_two = " '" + (work_dir() / "part-0.csv").string() + "' '" + (work_dir() / "part-1.csv").string() + "'";
  const auto gap = run_cli("merge" + first_two);
  CHECK(gap.exit_code == 2);
  CHECK_THAT(gap.err, Contains("12 of the sweep's 18 cases; missing: 2, 5, 8"));
  const auto twice = run_cli("merge" + parts + " '" + (work_dir() / "part-1.csv").string() + "'");
  CHECK(twice.exit_code == 2);
  CHECK_THAT(twice.err, Contains("case 1 is in both"));
  // Slurm's array variables pick the shard.
  const fs::path auto_part = work_dir() / "auto.csv";
  fs::remove(auto_part);
  ::setenv("SLURM_ARRAY_TASK_ID", "3", 1);
  ::setenv("SLURM_ARRAY_TASK_MIN", "1", 1);
  ::setenv("SLURM_ARRAY_TASK_COUNT", "3", 1);
  const auto by_slurm = run_cli(base + " --shard auto --out '" + auto_part.string() + "'");
  ::unsetenv("SLURM_ARRAY_TASK_ID");
  ::unsetenv("SLURM_ARRAY_TASK_MIN");
  ::unsetenv("SLURM_ARRAY_TASK_COUNT");
  REQUIRE(by_slurm.exit_code == 0);
  CHECK(slurp(auto_part) == slurp(work_dir() / "part-2.csv"));  // task 3 of 1..3 is shard 2/3
  // An array with a step (--array=0-6:2: tasks 0, 2, 4, 6) or with gaps would leave shards out:
  // refused in every task, not found by merge at the end.
  ::setenv("SLURM_ARRAY_TASK_ID", "2", 1);
  ::setenv("SLURM_ARRAY_TASK_MIN", "0", 1);
  ::setenv("SLURM_ARRAY_TASK_MAX", "6", 1);
  ::setenv("SLURM_ARRAY_TASK_COUNT", "4", 1);
  ::setenv("SLURM_ARRAY_TASK_STEP", "2", 1);
  const auto stepped = run_cli(base + " --shard auto");
  ::unsetenv("SLURM_ARRAY_TASK_STEP");
  const auto gaps = run_cli(base + " --shard auto");  // 0 to 6 are 7 tasks, not the 4 the array has
  for (const char* v : {"SLURM_ARRAY_TASK_ID", "SLURM_ARRAY_TASK_MIN", "SLURM_ARRAY_TASK_MAX", "SLURM_ARRAY_TASK_COUNT"}) ::unsetenv(v);
  CHECK(stepped.exit_code == 2);
  CHECK_THAT(stepped.err, Contains("SLURM_ARRAY_TASK_STEP is 2"));
  CHECK(gaps.exit_code == 2);
  CHECK_THAT(gaps.err, Contains("not 4 consecutive tasks"));
}

// The manifest of `rows` with its rows_format set to `format` (0: the key removed, as mechgraph
// wrote manifests before it recorded the format).
static void set_rows_format(const fs::path& rows, int format) {
  const std::string path = rows.string() + ".json";
  std::string manifest = slurp(path);
  std::size_t at = manifest.find(",\"rows_format\":"), end = at;
  if (at == std::string::npos) at = end = manifest.rfind('}');  // removed before: added back at the end
  else end = manifest.find_first_of(",}", at + 1);
  REQUIRE(at != std::string::npos);
  manifest.replace(at, end - at, format ? ",\"rows_format\":" + std::to_string(format) : std::string());
  std::ofstream(path) << manifest;
}

TEST_CASE("rows another mechgraph wrote are refused as such by --resume and merge, not as edited", "[cli][sweep]") {
  const std::string scene = scratch_file("scene.yaml", scene_text);
  const std::string base = arith_dir() + " sweep '" + scene + "' --vary len=1mm:4mm:4 -q";
  std::string parts;
  for (int i = 0; i < 3; ++i) {
    const fs::path part = work_dir() / ("format-" + std::to_string(i) + ".csv");
    fs::remove(part);
    REQUIRE(run_cli(base + " --shard " + std::to_string(i) + "/3 --out '" + part.string() + "'").exit_code == 0);
    CHECK_THAT(slurp(part.string() + ".json"), Contains(",\"rows_format\":2"));
    parts += " '" + part.string() + "'";
  }
  const std::string whole = run_cli(base).out;
  // A manifest that does not record the format (one written before the key) is not refused for
  // that: its rows are checked as they are, and these are this program's.
  set_rows_format(work_dir() / "format-1.csv", 0);
  const fs::path merged = work_dir() / "format-all.csv";
  fs::remove(merged);
  const auto unrecorded = run_cli("merge" + parts + " --out '" + merged.string() + "'");
  REQUIRE(unrecorded.exit_code == 0);
  CHECK(slurp(merged) == whole);
  CHECK_THAT(slurp(merged.string() + ".json"), Contains(",\"rows_format\":2"));  // what the others record
  // Shards of different recorded formats: every odd one named in one refusal.
  set_rows_format(work_dir() / "format-1.csv", 1);
  set_rows_format(work_dir() / "format-2.csv", 1);
  const auto mixed = run_cli("merge" + parts);
  CHECK(mixed.exit_code == 2);
  CHECK_THAT(mixed.err, Contains("the shards were written by different mechgraphs") && Contains("format-1.csv (format 1)") &&
                            Contains("format-2.csv (format 1)"));
  // Shards all of one older format merge as they are.
  set_rows_format(work_dir() / "format-0.csv", 1);
  CHECK(run_cli("merge" + parts).out == whole);
  // --resume of an unfinished file whose manifest a newer mechgraph wrote: refused up front.
  const fs::path unfinished = work_dir() / "format-0.csv";
  fs::rename(unfinished, unfinished.string() + ".part");
  set_rows_format(unfinished, 3);
  const auto newer = run_cli(base + " --shard 0/3 --out '" + unfinished.string() + "' --resume");
  CHECK(newer.exit_code == 2);
  CHECK_THAT(newer.err, Contains("format-0.csv.part: its rows were written by a newer mechgraph (rows format 3") &&
                            Contains("or start over with --force"));
  // Without the key it is resumed, its rows checked as they are.
  set_rows_format(unfinished, 0);
  CHECK(run_cli(base + " --shard 0/3 --out '" + unfinished.string() + "' --resume").exit_code == 0);
  CHECK(fs::exists(unfinished));
}

TEST_CASE("sweep: a list value in --vary stays whole, and a node's parameter wins over the scene's that reaches it", "[cli][sweep]") {
  const std::string scene = std::string(MECHGRAPH_SOURCE_DIR) + "/bench/peers/stages123_study.yaml";
  // The commas inside a value's brackets separate its elements, not the values varied.
  const auto lists = run_cli("sweep '" + scene + "' --vary 'poly.exponents=[2,14,26,38,50],[2,12,22,32,42]' --outputs v_poly.max_acceleration");
  REQUIRE(lists.exit_code == 0);
  const auto rows = lines_of(lists.out);
  REQUIRE(rows.size() == 3);
  CHECK_THAT(rows[1], StartsWith("0,\"[2,14,26,38,50]\",") && EndsWith(",0,"));
  CHECK_THAT(rows[2], StartsWith("1,\"[2,12,22,32,42]\",") && EndsWith(",0,"));
  // v_arc.rpm and the scene's rpm, which reaches it too: the node's own value, whatever the order of
  // the columns or the path (case by case, blocks), as run --set gives it.
  const auto value_of = [](const std::string& out) { return lines_of(out).at(1).substr(0, lines_of(out).at(1).rfind(",0,")); };
  const auto node_first = run_cli("sweep '" + scene + "' --vary v_arc.rpm=5000rpm --vary rpm=6000rpm --outputs v_arc.max_acceleration --block-size 0");
  const auto scene_first = run_cli("sweep '" + scene + "' --vary rpm=6000rpm --vary v_arc.rpm=5000rpm --outputs v_arc.max_acceleration");
  REQUIRE(node_first.exit_code == 0);
  REQUIRE(scene_first.exit_code == 0);
  const std::string a = value_of(node_first.out), b = value_of(scene_first.out);
  CHECK(a.substr(a.rfind(',') + 1) == b.substr(b.rfind(',') + 1));
  const auto one = run_cli("run '" + scene + "' --set v_arc.rpm=5000rpm --set rpm=6000rpm --json");
  REQUIRE(one.exit_code == 0);
  CHECK(YAML::Load(one.out)["outputs"]["v_arc.max_acceleration"]["value"].as<double>() == std::stod(a.substr(a.rfind(',') + 1)));
}
