// `mechgraph report` regenerates its own folder: a second report into the same --out replaces the
// first without --force; results another command wrote, or a folder mechgraph did not write, still
// need --force or are refused. With --pdf it says where the PDF is.
#include "hostile/hostile_support.hpp"

#include <catch2/catch.hpp>

using namespace mechgraph::hostile;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

TEST_CASE("report regenerates its own folder without --force, other folders keep their rules", "[cli][report]") {
  const Scratch scratch("report_again");
  const std::string scene = source_file("scenes/tolerance_stack.yaml");
  const fs::path out = scratch.dir / "r";
  const Outcome first = run_mechgraph({"report", scene, "--out", out.string()});
  REQUIRE(first.exit_code == 0);
  CHECK_THAT(first.out, Contains((out / "report.html").string()));
  const auto written = fs::last_write_time(out / "report.html");
  const Outcome again = run_mechgraph({"report", scene, "--out", out.string()});
  INFO(again.err);
  CHECK(again.exit_code == 0);
  CHECK(fs::exists(out / "report.html"));
  CHECK(fs::last_write_time(out / "report.html") >= written);

  // Results of `run --out` are not a report: --force is still needed to replace them.
  const fs::path run_out = scratch.dir / "run";
  REQUIRE(run_mechgraph({"run", scene, "--out", run_out.string()}).exit_code == 0);
  const Outcome over_run = run_mechgraph({"report", scene, "--out", run_out.string()});
  CHECK(over_run.exit_code == 2);
  CHECK_THAT(over_run.err, Contains("--force"));
  CHECK(run_mechgraph({"report", scene, "--out", run_out.string(), "--force"}).exit_code == 0);

  // A folder of someone else's with a report.html in it is never replaced.
  const fs::path theirs = scratch.dir / "theirs";
  fs::create_directories(theirs);
  scratch.write("theirs/report.html", "<p>mine</p>");
  CHECK(run_mechgraph({"report", scene, "--out", theirs.string()}).exit_code == 2);
  CHECK(slurp(theirs / "report.html") == "<p>mine</p>");
}
