// Chaos: scenes of test.chaos nodes that throw, throw what is not an exception, return NaN,
// sleep or ask for more memory than any machine has, mixed at random (seeded) and evaluated on
// every core (--threads 0). The host must report a misbehaving node by name with exit 3, finish
// with exit 0 when none misbehaves, and never crash or hang (ctest's timeout catches a hang).
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <fstream>
#include <random>

using namespace mechgraph::testing;
using Catch::Matchers::Contains;

TEST_CASE("chaos: misbehaving nodes under --threads 0 are reported by name, the host never crashes", "[cli][chaos]") {
  const std::string plugins = "--only-plugin-dir '" + test_plugin("test_arith").parent_path().string() + "' ";
  const auto dir = std::filesystem::temp_directory_path() / ("mechgraph_chaos_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const char* modes[] = {"ok", "ok", "ok", "sleep", "throw", "nan", "allocate", "throw_other"};
  std::mt19937 random(20261123);
  for (int round = 0; round < 24; ++round) {
    // Eight nodes: four sources, two that sum pairs of them, one that sums those, one alone.
    std::vector<std::string> mode(8);
    for (auto& m : mode) m = modes[random() % 8];
    std::string yaml = "nodes:\n";
    for (int i = 0; i < 4; ++i) yaml += "  s" + std::to_string(i) + ": { type: test.chaos, params: { mode: " + mode[i] + " } }\n";
    yaml += "  p0: { type: test.chaos, inputs: { in: [s0.out, s1.out] }, params: { mode: " + mode[4] + " } }\n";
    yaml += "  p1: { type: test.chaos, inputs: { in: [s2.out, s3.out] }, params: { mode: " + mode[5] + " } }\n";
    yaml += "  top: { type: test.chaos, inputs: { in: [p0.out, p1.out] }, params: { mode: " + mode[6] + " } }\n";
    yaml += "  alone: { type: test.chaos, params: { mode: " + mode[7] + " } }\n";
    yaml += "outputs: [top.out, alone.out]\n";
    const auto file = dir / ("chaos_" + std::to_string(round) + ".yaml");
    std::ofstream(file) << yaml;
    const auto r = run_cli(plugins + "run '" + file.string() + "' --threads 0 --json");
    INFO(yaml << "\nstderr: " << r.err);
    bool misbehaves = false;
    for (const auto& m : mode) misbehaves = misbehaves || (m != "ok" && m != "sleep");
    if (!misbehaves) {
      CHECK(r.exit_code == 0);
      continue;
    }
    CHECK(r.exit_code == 3);
    // The message names one of the misbehaving nodes and what it did.
    bool named = false;
    const char* names[] = {"s0", "s1", "s2", "s3", "p0", "p1", "top", "alone"};
    for (int i = 0; i < 8; ++i)
      if (mode[i] != "ok" && mode[i] != "sleep") named = named || r.err.find("node '" + std::string(names[i]) + "'") != std::string::npos;
    CHECK(named);
    CHECK((Contains("chaos: thrown on purpose").match(r.err) || Contains("NaN or infinite").match(r.err) ||
           Contains("ran out of memory").match(r.err) || Contains("not a std::exception").match(r.err)));
  }
  std::filesystem::remove_all(dir);
}
