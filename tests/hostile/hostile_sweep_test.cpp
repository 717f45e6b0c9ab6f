// Issue 18, the sweep side: a scene, a cases file or a folder from someone else cannot make
// `mechgraph sweep`, `merge`, `--resume` or `--out DIR` write through a planted symlink, replace
// something mechgraph did not write, hang on a FIFO, spin on a huge manifest, carry over edited
// rows, send a non-finite value into a node or write a CSV a spreadsheet would run. Each test runs
// the built command as a subprocess and checks the exit code, the message and what is on disk.
#include "file_support.hpp"
#include "test_support.hpp"

#include <mechgraph/csv.hpp>

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

std::string arith_dir() { return arith_plugin_dir_option(); }
fs::path work_dir() { return scratch_dir("mechgraph_hostile_sweep"); }

fs::path fresh_dir(const std::string& name) { return mechgraph::testing::fresh_dir(work_dir(), name); }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

const char* scene_text = R"(title: sweep
params: { len: 2 mm }
nodes:
  a: { type: test.constant, params: { value: $len } }
  s: { type: test.add, inputs: { a: a.out, b: a.out }, params: { gain: 1.5 } }
outputs: [ s.sum ]
)";

const char* slow_scene = R"(title: slow
params: { x: 1 mm }
nodes:
  slow: { type: test.slow, params: { value: $x, delay: 30 ms } }
outputs: [ slow.out ]
)";

std::string scene() { return write_file(work_dir() / "scene.yaml", scene_text); }
std::string sweep_of(const std::string& scene_file) { return arith_dir() + " -q sweep '" + scene_file + "' "; }

// Every row of a CSV as Python's csv module reads it (an independent RFC 4180 reader).
std::vector<std::vector<std::string>> python_csv(const fs::path& file) {
  const fs::path json = file.string() + ".py.json";
  const auto r = run_command("python3 -c 'import csv,json,sys; json.dump(list(csv.reader(open(sys.argv[1], newline=\"\"))), open(sys.argv[2], \"w\"))' " +
                             q(file) + " " + q(json));
  REQUIRE(r.exit_code == 0);
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : YAML::LoadFile(json.string())) {
    rows.emplace_back();
    for (const auto& cell : row) rows.back().push_back(cell.as<std::string>());
  }
  fs::remove(json);
  return rows;
}

// Starts the command in the background (no shell quoting tricks: the test's own fixed text);
// returns its pid; its exit status lands in `status_file`.
pid_t start_cli(const std::string& args, const fs::path& status_file) {
  return mechgraph::testing::start_cli_in_background(args, status_file, work_dir() / "pid");
}

std::string wait_status(const fs::path& status_file) {
  for (int i = 0; i < 3000; ++i) {
    const std::string s = slurp(status_file);
    if (!s.empty() && s.back() == '\n') return s;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return "(still running)";
}

void wait_for_file(const fs::path& file) {
  for (int i = 0; i < 2000 && !fs::exists(file); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(fs::exists(file));
}

}  // namespace

TEST_CASE("hostile sweep: a planted symlink at FILE.part or a temporary's old name is never written through", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("symlinks");
  const std::string victim = write_file(dir / "victim.txt", "precious\n");
  const fs::path out = dir / "rows.csv";
  const std::string sweep = sweep_of(scene()) + "--vary len=1mm:3mm:3 --out " + q(out);
  // The old fixed temporary names: FILE.json.tmp, and merge's FILE.tmp.
  fs::create_symlink(victim, out.string() + ".json.tmp");
  fs::create_symlink(victim, (dir / "merged.csv.tmp").string());
  REQUIRE(run_cli(sweep).exit_code == 0);
  CHECK(slurp(victim) == "precious\n");
  const auto merged = run_cli("merge " + q(out) + " --out " + q(dir / "merged.csv"));
  REQUIRE(merged.exit_code == 0);
  CHECK(slurp(dir / "merged.csv") == slurp(out));
  CHECK(slurp(victim) == "precious\n");

  // FILE.part planted as a symlink: a fresh sweep, --force and --resume all leave its target alone.
  fs::remove(out);
  fs::create_symlink(victim, out.string() + ".part");
  for (const std::string extra : {"", " --force", " --resume"}) {
    INFO("sweep" << extra);
    const auto r = run_cli(sweep + extra);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("symbolic link"));
    CHECK(slurp(victim) == "precious\n");
    CHECK(fs::is_symlink(out.string() + ".part"));
  }
  // The manifest and the lock file planted as symlinks: refused, their target untouched.
  const fs::path other = dir / "other.csv";
  fs::create_symlink(victim, other.string() + ".json");
  auto r = run_cli(sweep_of(scene()) + "--vary len=1mm:3mm:3 --out " + q(other));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("symbolic link"));
  fs::remove(other.string() + ".json");
  fs::remove(other.string() + ".lock");  // the first attempt made the lock file; a symlink takes its place
  fs::create_symlink(victim, other.string() + ".lock");
  r = run_cli(sweep_of(scene()) + "--vary len=1mm:3mm:3 --out " + q(other));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("symbolic link"));
  CHECK(slurp(victim) == "precious\n");
  CHECK_FALSE(fs::exists(other));
}

TEST_CASE("hostile sweep: --force replaces only what mechgraph wrote", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("force");
  const std::string sweep = sweep_of(scene()) + "--vary len=1mm:3mm:3 --force --out ";
  // A foreign regular file.
  const std::string notes = write_file(dir / "notes.txt", "my notes\n");
  auto r = run_cli(sweep + q(notes));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("mechgraph did not write it"));
  CHECK(slurp(notes) == "my notes\n");
  // A symlink to a file.
  fs::create_symlink(notes, dir / "link.csv");
  r = run_cli(sweep + q(dir / "link.csv"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("symbolic link"));
  CHECK(fs::is_symlink(dir / "link.csv"));
  CHECK(slurp(notes) == "my notes\n");
  // A FIFO.
  REQUIRE(::mkfifo((dir / "fifo.csv").c_str(), 0644) == 0);
  r = run_command("timeout 20 '" + std::string(MECHGRAPH_CLI) + "' " + sweep + q(dir / "fifo.csv"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("FIFO"));
  CHECK(fs::is_fifo(dir / "fifo.csv"));
  // A device (tests run as root; elsewhere mknod fails and the case is skipped).
  if (::mknod((dir / "null.csv").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    r = run_cli(sweep + q(dir / "null.csv"));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("device"));
    CHECK(fs::is_character_file(dir / "null.csv"));
  } else {
    WARN("mknod failed (not root?): the device case is skipped");
  }
  // What mechgraph wrote (a manifest beside it) is replaced.
  REQUIRE(run_cli(sweep + q(dir / "ours.csv")).exit_code == 0);
  CHECK(run_cli(sweep + q(dir / "ours.csv")).exit_code == 0);
  // merge --out: the same rules.
  r = run_cli("merge " + q(dir / "ours.csv") + " --force --out " + q(notes));
  CHECK(r.exit_code == 2);
  CHECK(slurp(notes) == "my notes\n");
}

TEST_CASE("hostile results folder: --force refuses foreign folders and links, DIR/ works, stale staging is removed", "[hostile][out]") {
  const fs::path dir = fresh_dir("folders");
  const std::string run = arith_dir() + " -q run '" + scene() + "' --out ";
  // DIR/ with a trailing slash, twice (the second replaces the first).
  REQUIRE(run_cli(run + q(dir.string() + "/results/")).exit_code == 0);
  CHECK(fs::exists(dir / "results" / ".mechgraph-results"));
  CHECK(run_cli(run + q(dir.string() + "/results/") + " --force").exit_code == 0);
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().find("staging") == std::string::npos);
  // A folder mechgraph did not make (no marker) is left alone even with --force.
  fs::create_directories(dir / "mine");
  write_file(dir / "mine" / "thesis.tex", "work\n");
  auto r = run_cli(run + q(dir / "mine") + " --force");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("did not write"));
  CHECK(slurp(dir / "mine" / "thesis.tex") == "work\n");
  // A symlink to mechgraph's own results folder, a file, a device.
  fs::create_directory_symlink(dir / "results", dir / "link");
  r = run_cli(run + q(dir / "link") + " --force");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("symbolic link"));
  CHECK(fs::is_symlink(dir / "link"));
  write_file(dir / "file", "x\n");
  CHECK(run_cli(run + q(dir / "file") + " --force").exit_code == 2);
  CHECK(slurp(dir / "file") == "x\n");
  if (::mknod((dir / "dev").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    r = run_cli(run + q(dir / "dev") + " --force");
    CHECK(r.exit_code == 2);
    CHECK(fs::is_character_file(dir / "dev"));
  }
  // Stale staging folders: a dead one of ours goes, a live one (its marker locked) and a foreign one stay.
  for (const char* name : {".results.staging-dead01", ".results.staging-live01", ".results.staging-other1"})
    fs::create_directories(dir / name);
  write_file(dir / ".results.staging-dead01" / ".mechgraph-results", "x\n");
  write_file(dir / ".results.staging-live01" / ".mechgraph-results", "x\n");
  const int held = ::open((dir / ".results.staging-live01" / ".mechgraph-results").c_str(), O_RDONLY);
  REQUIRE(held >= 0);
  REQUIRE(::flock(held, LOCK_EX) == 0);
  write_file(dir / ".results.staging-other1" / "data", "x\n");
  REQUIRE(run_cli(run + q(dir / "results") + " --force").exit_code == 0);
  CHECK_FALSE(fs::exists(dir / ".results.staging-dead01"));
  CHECK(fs::exists(dir / ".results.staging-live01"));
  CHECK(fs::exists(dir / ".results.staging-other1"));
  ::close(held);
}

TEST_CASE("hostile sweep: a second writer of the same --out is refused while the first runs", "[hostile][sweep][slow]") {
  const fs::path dir = fresh_dir("lock");
  const std::string slow = write_file(dir / "slow.yaml", slow_scene);
  const fs::path out = dir / "same.csv";
  const std::string sweep = sweep_of(slow) + "--vary x=1mm:100mm:100 --threads 1 --out " + q(out);
  const fs::path status = dir / "status";
  const pid_t first = start_cli(sweep, status);
  wait_for_file(out.string() + ".part");
  const std::string who = "pid " + std::to_string(first);
  for (const std::string extra : {"", " --resume", " --force"}) {
    INFO("second sweep" << extra);
    const auto r = run_cli(sweep + extra);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("being written by another mechgraph") && Contains(who));
  }
  const auto merge = run_cli("merge " + q(dir / "whatever.csv") + " --out " + q(out));
  CHECK(merge.exit_code == 2);
  CHECK_THAT(merge.err, Contains(who));
  ::kill(first, SIGINT);
  CHECK(wait_status(status) == "130\n");
  CHECK(run_cli(sweep + " --resume").exit_code == 0);  // the lock went with its holder
  CHECK(python_csv(out).size() == 101);
}

TEST_CASE("hostile sweep: a FILE.lock that is not mechgraph's is never truncated", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("foreign_lock");
  const fs::path out = dir / "Cargo";
  write_file(out.string() + ".lock", "# the user's own lock file\n[[package]]\n");
  for (const std::string& command : {sweep_of(scene()) + "--vary len=1mm:2mm:2 --out " + q(out), std::string("merge ") + q(dir / "none.csv") + " --out " + q(out)}) {
    INFO(command);
    const auto r = run_cli(command);
    CHECK(r.exit_code == 2);
    CHECK(slurp(out.string() + ".lock") == "# the user's own lock file\n[[package]]\n");
  }
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("hostile sweep: numbers on the command line are range-checked as usage errors", "[hostile][sweep]") {
  const std::string sweep = sweep_of(scene());
  const std::string vary = "--vary len=1mm:2mm:2 ";
  for (const std::string bad : {"-1", "1025", "abc", "4294967297", " 2"}) {
    const auto r = run_cli(sweep + vary + "--threads '" + bad + "'");
    INFO("--threads " << bad);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("--threads"));
  }
  CHECK(run_cli(sweep + vary + "--threads 0").exit_code == 0);
  const auto cache = run_cli(sweep + vary + "--cache-size -1");
  CHECK(cache.exit_code == 2);
  CHECK_THAT(cache.err, Contains("--cache-size"));
  for (const std::string bad : {"0", "-5", "250000001", "1.5", "18446744073709551615", "1e7"}) {
    const auto r = run_cli(sweep + "--sample len=1mm:2mm --n '" + bad + "'");
    INFO("--n " << bad);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("--n"));
  }
  for (const std::string bad : {"18446744073709551615/3", "0/0", "1/2000000", "-1/3", "3/3", "1/18446744073709551617", "+1/3"}) {
    const auto r = run_cli(sweep + vary + "--shard '" + bad + "'");
    INFO("--shard " << bad);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("--shard"));
  }
  struct Slurm {
    const char *id, *min, *count, *named;
  };
  for (const Slurm& s : {Slurm{"0", "1", "3", "SLURM_ARRAY_TASK_MIN"}, Slurm{"x1", "1", "3", "SLURM_ARRAY_TASK_ID"},
                         Slurm{"18446744073709551616", "0", "3", "SLURM_ARRAY_TASK_ID"}, Slurm{"1", "0", "-3", "SLURM_ARRAY_TASK_COUNT"},
                         Slurm{"9", "1", "3", "SLURM_ARRAY_TASK_COUNT"}}) {
    const auto r = run_command(std::string("SLURM_ARRAY_TASK_ID='") + s.id + "' SLURM_ARRAY_TASK_MIN='" + s.min +
                               "' SLURM_ARRAY_TASK_COUNT='" + s.count + "' '" + MECHGRAPH_CLI + "' " + sweep + vary + "--shard auto");
    INFO("SLURM id " << s.id << " min " << s.min << " count " << s.count);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(s.named));
  }
}

TEST_CASE("hostile merge and resume: huge manifests and edited rows are refused naming FILE:line", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("rows");
  const fs::path out = dir / "rows.csv";
  const std::string sweep = sweep_of(scene()) + "--vary len=1mm:5mm:5 --out " + q(out);
  REQUIRE(run_cli(sweep).exit_code == 0);
  const std::string rows = slurp(out), manifest = slurp(out.string() + ".json");
  // A manifest claiming 10^15 cases: refused at once, not spun on.
  std::string huge = manifest;
  huge.replace(huge.find("\"cases\":5"), 9, "\"cases\":1000000000000000");
  write_file(out.string() + ".json", huge);
  const auto start = std::chrono::steady_clock::now();
  auto r = run_cli("merge " + q(out));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("cases"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
  write_file(out.string() + ".json", manifest);
  CHECK(run_cli("merge " + q(out)).exit_code == 0);
  // Rows a user (or anyone) edited: each refused with the file and the line.
  struct Edit {
    std::string rows, says;
  };
  const std::vector<Edit> edits = {{rows + "199,garbage\n", ":7:"},
                                   {rows + "4,5,0.015,0,\n", "after case 4"},
                                   {rows.substr(0, rows.find('\n') + 1) + "0,1,abc,0,\n", "not a finite number"},
                                   {rows.substr(0, rows.find('\n') + 1) + "0,1,inf,0,\n", "not a finite number"},
                                   {rows.substr(0, rows.find('\n') + 1) + "x,1,0.003,0,\n", "not a whole number"},
                                   {rows.substr(0, rows.find('\n') + 1) + "0,1,0.003,7,\n", "exit"}};
  for (const Edit& e : edits) {
    INFO(e.rows);
    write_file(out, e.rows);
    r = run_cli("merge " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(out.string() + ":") && Contains(e.says));
  }
  // A formula planted in an input or error cell, or a line break's trace: not as csv_field writes, refused.
  const std::string header = rows.substr(0, rows.find('\n') + 1);
  for (const std::string bad : {"0,\"=cmd|' /C calc'!A0\",0.003,0,\n", "0,1,,3,=HYPERLINK(\"http://x\")\n", "0,1,,3,\"a\rb\"\n"}) {
    INFO(bad);
    write_file(out, header + bad);
    r = run_cli("merge " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(out.string() + ":2:") && Contains("not as mechgraph writes cells"));
  }
  // A manifest that no longer says how many input columns there are: outputs could not be told apart.
  write_file(out, rows);
  std::string no_inputs = manifest;
  no_inputs.replace(no_inputs.find(",\"inputs\":1"), 11, "");
  write_file(out.string() + ".json", no_inputs);
  r = run_cli("merge " + q(out));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("input columns"));
  write_file(out.string() + ".json", manifest);
  // JSON Lines: merged back as written; edited objects refused.
  const fs::path jsonl = dir / "rows.jsonl";
  REQUIRE(run_cli(sweep_of(scene()) + "--vary len=1mm:5mm:5 --format jsonl --out " + q(jsonl)).exit_code == 0);
  const std::string objects = slurp(jsonl);
  r = run_cli("merge " + q(jsonl));
  REQUIRE(r.exit_code == 0);
  CHECK(r.out == objects);
  const std::string first = objects.substr(0, objects.find('\n') + 1);
  for (const std::string bad : {"{\"case\":0,\"len [mm]\":1,\"s.sum [m]\":[1],\"exit\":0,\"error\":null}",
                                "{\"case\":0,\"len [mm]\":1,\"s.sum [m]\":\"0.003\",\"exit\":0,\"error\":null}",
                                "{\"case\":0,\"case\":0,\"s.sum [m]\":0.003,\"exit\":0,\"error\":null}",
                                "{case: 0, len [mm]: 1, s.sum [m]: 0.003, exit: 0, error: null}"}) {
    INFO(bad);
    write_file(jsonl, first + bad + "\n");
    r = run_cli("merge " + q(jsonl));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(jsonl.string() + ":2:"));
  }
  // --resume re-checks the rows it carries over the same way.
  fs::remove(out);
  write_file(out.string() + ".part", rows.substr(0, rows.find('\n') + 1) + "0,1,0.003,0,\n1,2,garbage,0,\n");
  r = run_cli(sweep + " --resume");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains(out.string() + ".part:3:"));
  // A row whose inputs were edited (case 1 is len = 2 mm in this sweep).
  write_file(out.string() + ".part", rows.substr(0, rows.find('\n') + 1) + "0,1,0.003,0,\n1,7,0.021,0,\n");
  r = run_cli(sweep + " --resume");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains(out.string() + ".part:3:") && Contains("has '2'"));
  // Untouched rows resume to the same file as a run in one go.
  write_file(out.string() + ".part", rows.substr(0, rows.find("2,3,")));
  REQUIRE(run_cli(sweep + " --resume").exit_code == 0);
  CHECK(slurp(out) == rows);
}

TEST_CASE("hostile merge and resume: CR LF line ends and a byte order mark are read past by merge, refused by resume", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("line_ends");
  const fs::path out = dir / "rows.csv", jsonl = dir / "rows.jsonl";
  const std::string sweep = sweep_of(scene()) + "--vary len=1mm:5mm:5 --out " + q(out);
  REQUIRE(run_cli(sweep).exit_code == 0);
  REQUIRE(run_cli(sweep_of(scene()) + "--vary len=1mm:5mm:5 --format jsonl --out " + q(jsonl)).exit_code == 0);
  const std::string rows = slurp(out), objects = slurp(jsonl);
  const auto windows = [](const std::string& text) {
    std::string saved;
    for (char c : text) saved += c == '\n' ? std::string("\r\n") : std::string(1, c);
    return saved;
  };
  const std::string mark = "\xEF\xBB\xBF";
  // merge: the shards as another tool saved them merge to the rows as the sweep wrote them.
  for (const fs::path& file : {out, jsonl}) {
    const std::string written = file == out ? rows : objects;
    for (const std::string& saved : {windows(written), mark + written, mark + windows(written)}) {
      write_file(file, saved);
      const auto r = run_cli("merge " + q(file));
      CHECK(r.exit_code == 0);
      CHECK(r.out == written);
      // Said once for the file, though merge to standard output reads it twice (check, then write).
      const auto said = r.err.find("merged as LF lines");
      CHECK(said != std::string::npos);
      CHECK(r.err.find("merged as LF lines", said + 1) == std::string::npos);
    }
    write_file(file, written);
  }
  // No files at all: said in words, not as a missing option.
  const auto none = run_cli("merge");
  CHECK(none.exit_code == 2);
  CHECK_THAT(none.err, Contains("no rows files to merge"));
  // --resume appends to FILE.part as it is: refused at line 1, the file left untouched.
  fs::remove(out);
  const std::string begun = rows.substr(0, rows.find("2,3,"));
  for (const std::string& part : {windows(begun), mark + begun}) {
    write_file(out.string() + ".part", part);
    const auto r = run_cli(sweep + " --resume");
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(out.string() + ".part:1:") && Contains("where mechgraph writes LF alone") && Contains("dos2unix"));
    CHECK(slurp(out.string() + ".part") == part);
  }
  write_file(out.string() + ".part", begun);
  REQUIRE(run_cli(sweep + " --resume").exit_code == 0);
  CHECK(slurp(out) == rows);
}

TEST_CASE("hostile sweep values: finite, range-checked like scene values, one bad case does not end JSON Lines", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("values");
  const std::string sweep = sweep_of(scene());
  // The endpoints' difference overflows a double: every generated value is still finite.
  auto r = run_cli(sweep + "--sample 'len=-1e308m:1e308m' --n 5 --format jsonl");
  CHECK(r.exit_code == 0);
  std::istringstream lines(r.out);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) {
    const YAML::Node row = YAML::Load(line);
    CHECK(row["case"].as<int>() == count);
  }
  CHECK(count == 5);
  // Infinite ends: a usage error naming the option (the unit parser or the finiteness check says why).
  for (const std::string bad : {"--vary 'len=1e400m:1mm:3'", "--sample 'len=-inf:1mm' --n 2", "--sample 'len=1mm:1e309mm' --n 2"}) {
    r = run_cli(sweep + bad);
    INFO(bad);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(bad.substr(0, 6)) && Contains("len="));
  }
  // "nan" is no number to the unit parser: a word, which the length parameter refuses in its row alone.
  r = run_cli(sweep + "--vary 'len=1mm,nan' --format jsonl");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("\"case\":1,\"len [mm]\":\"nan\"") && Contains("\"exit\":2"));
  const std::string cases = write_file(dir / "inf.csv", "len [mm]\n1\ninf\n");
  r = run_cli(sweep + "--cases " + q(cases));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("inf.csv:3:1") && Contains("'inf'"));
  // Outside the declared range: the same words a scene value gets.
  const auto scene_error = run_cli(arith_dir() + " run '" + scene() + "' --set s.gain=-2");
  CHECK(scene_error.exit_code == 2);
  CHECK_THAT(scene_error.err, Contains("is out of range: it must be > 0"));
  r = run_cli(sweep + "--vary s.gain=1,-2 --format jsonl");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("is out of range: it must be > 0"));
  // A swept input named like a reserved column: JSON keys stay unique.
  const std::string reserved = write_file(dir / "reserved.yaml", R"(title: a scene parameter named like a column
params: { len: 2 mm, error: 1.5 }
nodes:
  a: { type: test.constant, params: { value: $len } }
  s: { type: test.add, inputs: { a: a.out, b: a.out }, params: { gain: $error } }
outputs: [ s.sum ]
)");
  r = run_cli(sweep_of(reserved) + "--vary error=1,2 --format jsonl");
  REQUIRE(r.exit_code == 0);
  const fs::path jsonl = write_file(dir / "reserved.jsonl", r.out);
  const auto dup = run_command("python3 -c 'import json,sys\nfor l in open(sys.argv[1]):\n  json.loads(l, object_pairs_hook=lambda p: "
                               "(_ for _ in ()).throw(ValueError(\"dup\")) if len(set(k for k,_ in p)) != len(p) else dict(p))' " +
                               q(jsonl));
  CHECK(dup.exit_code == 0);
  CHECK_THAT(r.out, Contains("\"in.error\":1"));
}

TEST_CASE("hostile CSV: one csv_field, RFC 4180 quoting, formulas neutralised, BOM skipped", "[hostile][csv]") {
  using mechgraph::csv_field;
  using mechgraph::csv_row;
  using mechgraph::csv_text;
  using mechgraph::split_csv_line;
  CHECK(csv_field("=1+2") == "'=1+2");
  CHECK(csv_field("@SUM(A1)") == "'@SUM(A1)");
  CHECK(csv_field("+cmd") == "'+cmd");
  CHECK(csv_field("-x") == "'-x");
  CHECK(csv_field("\tx") == "'\tx");
  CHECK(csv_field("\rx") == " x");  // CR becomes a space first (rows are single lines): no formula left
  CHECK(csv_field("-2") == "-2");
  CHECK(csv_field("+2") == "'+2");  // found by fuzz_csv_field: a spreadsheet reads "+2" as a formula
  CHECK(csv_field("-1.5e-3") == "-1.5e-3");
  CHECK(csv_field("-") == "-");
  CHECK(csv_field("a,b") == "\"a,b\"");
  CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csv_field("two\nlines") == "two lines");
  CHECK(csv_field("=HYPERLINK(\"x\",\"y\")") == "\"'=HYPERLINK(\"\"x\"\",\"\"y\"\")\"");
  const std::vector<std::string> fields = {"", "a,b", "\"", "=1", "-3", "x\r\ny", " @"};
  std::vector<std::string> expected;
  for (const auto& f : fields) expected.push_back(csv_text(f));
  CHECK(split_csv_line(csv_row(fields)) == expected);

  // End to end: a cases file with a BOM, a formula, quotes and commas; Python reads the rows back.
  const fs::path dir = fresh_dir("csv");
  const std::string cases = write_file(dir / "cases.csv", "\xEF\xBB\xBF" "len [mm],a.mode\n1,plain\n2,\"=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\"\n3,\"fancy\"\n");
  const fs::path out = dir / "rows.csv";
  const auto r = run_cli(sweep_of(scene()) + "--cases " + q(cases) + " --out " + q(out));
  CHECK_THAT(r.err, !Contains("\\ufeff") && !Contains("unknown node"));
  REQUIRE(r.exit_code == 0);
  const auto rows = python_csv(out);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0] == std::vector<std::string>{"case", "len [mm]", "a.mode", "s.sum [m]", "exit", "error"});
  for (const auto& row : rows) CHECK(row.size() == rows[0].size());
  CHECK(rows[2][2] == "'=HYPERLINK(\"http://x\",\"y\")");
  CHECK(rows[2][4] == "2");
  CHECK(rows[3][2] == "fancy");
  CHECK(rows[3][4] == "0");
  // The same rows through the project's reader.
  std::istringstream in(slurp(out));
  std::size_t i = 0;
  for (std::string line; std::getline(in, line); ++i) CHECK(split_csv_line(line) == rows[i]);
}

TEST_CASE("hostile reads: FIFOs, devices and folders are refused, long user text is cut in messages", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("reads");
  const std::string sweep = "timeout 20 '" + std::string(MECHGRAPH_CLI) + "' " + sweep_of(scene());
  REQUIRE(::mkfifo((dir / "cases.fifo").c_str(), 0644) == 0);
  auto r = run_command(sweep + "--cases " + q(dir / "cases.fifo"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("a FIFO"));
  r = run_command(sweep + "--cases /dev/zero");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("device"));
  r = run_command(sweep + "--cases " + q(dir));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("a folder"));
  // A manifest that is a FIFO: merge refuses it without waiting for a writer.
  write_file(dir / "rows.csv", "case,exit,error\n");
  REQUIRE(::mkfifo((dir / "rows.csv.json").c_str(), 0644) == 0);
  r = run_command("timeout 20 '" + std::string(MECHGRAPH_CLI) + "' merge " + q(dir / "rows.csv"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("a FIFO"));
  // Too large (sparse files: nothing is really written): refused from the size, not read.
  write_file(dir / "huge.csv", "len [mm]\n1\n");
  fs::resize_file(dir / "huge.csv", std::uintmax_t{300} << 20);
  r = run_command(sweep + "--cases " + q(dir / "huge.csv"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("huge.csv") && Contains("256 MiB"));
  fs::remove(dir / "rows.csv.json");
  write_file(dir / "rows.csv.json", "{}");
  fs::resize_file(dir / "rows.csv.json", std::uintmax_t{17} << 20);
  r = run_command("timeout 20 '" + std::string(MECHGRAPH_CLI) + "' merge " + q(dir / "rows.csv"));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("rows.csv.json") && Contains("65536 bytes"));
  // 10 000 characters of user text: the message quotes at most a few hundred.
  const std::string long_name(10000, 'k');
  r = run_cli(sweep_of(scene()) + "--vary '" + long_name + "=1mm:2mm:x'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.size() < 2000);
}

TEST_CASE("hostile disk: a full disk is exit 5 naming the file, and publishes nothing", "[hostile][sweep]") {
  const fs::path dir = fresh_dir("full");
  const fs::path small = dir / "small";
  fs::create_directories(small);
  if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=64k") != 0) {
    WARN("cannot mount a small tmpfs (not root?): the full-disk case is skipped");
    return;
  }
  const std::string sweep = sweep_of(scene()) + "--vary len=1mm:5000mm:5000 ";
  auto r = run_cli(sweep + "--out " + q(small / "rows.csv"));
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.err, Contains("rows.csv") && Contains("No space left"));
  CHECK_FALSE(fs::exists(small / "rows.csv"));
  fs::remove(small / "rows.csv.part");
  // merge --out onto the full disk: nothing published, no temporary left.
  REQUIRE(run_cli(sweep + "--out " + q(dir / "big.csv")).exit_code == 0);
  r = run_cli("merge " + q(dir / "big.csv") + " --out " + q(small / "merged.csv"));
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.err, Contains("merged.csv") && Contains("No space left"));
  CHECK_FALSE(fs::exists(small / "merged.csv"));
  for (const auto& e : fs::directory_iterator(small)) CHECK(e.path().filename().string().find("tmp") == std::string::npos);
  ::umount(small.c_str());
}
