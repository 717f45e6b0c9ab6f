// A start loads only the plugins its scene uses (PluginRegistry::load_directories with needs): the
// probe cache writes down what each file provided when it was last loaded, and a file that
// provides none of the scene's node types and required plugins stays unloaded. Whenever the cache
// cannot tell (a new or changed file, two files claiming one type, a need nobody claims) every file
// is loaded, so a scene finds the same types and the same errors either way.
#include "file_support.hpp"
#include "test_support.hpp"

#include <mechgraph/host/plugin_search.hpp>
#include <mechgraph/host/study_run.hpp>
#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/scene.hpp>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

struct ScopedEnvironment {
  std::string name;
  ScopedEnvironment(std::string n, const std::string& value) : name(std::move(n)) { ::setenv(name.c_str(), value.c_str(), 1); }
  ~ScopedEnvironment() { ::unsetenv(name.c_str()); }
};

// A scratch folder with plugins/ (mode 755) holding test_arith and the marker plugin (no node
// types; each process that loads it appends its pid to MECHGRAPH_TEST_MARKER), and cache/ for the
// probe cache.
struct Folder {
  fs::path dir = fresh_dir(fs::temp_directory_path(), "mg_plugin_needs_" + std::to_string(::getpid()));
  fs::path plugins = dir / "plugins";
  fs::path marker = dir / "marks";
  Folder() {
    fs::create_directories(plugins);
    fs::permissions(plugins, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                 fs::perms::others_read | fs::perms::others_exec);
    fs::copy_file(test_plugin("test_arith"), plugins / "mechgraph_test_arith.so");
    fs::copy_file(test_plugin("test_marker_good"), plugins / "mechgraph_marker_good.so");
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::size_t marks() const {
    std::ifstream in(marker);
    std::size_t n = 0;
    for (long pid = 0; in >> pid;) ++n;
    return n;
  }
};

// Appends a note to the probe cache for `file` as a process writes it: KEY<tab>provides WORDS.
void append_note(const fs::path& dir, const fs::path& file, const std::string& words) {
  struct stat st {};
  REQUIRE(::stat(file.c_str(), &st) == 0);
  const std::string key = fs::canonical(file).string() + " " + std::to_string(st.st_size) + " " +
                          std::to_string(st.st_ctim.tv_sec) + "." + std::to_string(st.st_ctim.tv_nsec) + " " +
                          std::to_string(st.st_ino);
  std::ofstream(dir / "cache" / "mechgraph" / "plugin-probes", std::ios::app) << key << "\tprovides " << words << "\n";
}

std::vector<std::string> ids(const PluginRegistry& r) {
  std::vector<std::string> out;
  for (const PluginInfo& p : r.plugins()) out.push_back(p.id);
  return out;
}

}  // namespace

TEST_CASE("a registry given needs loads only the files the probe cache knows provide them", "[plugins][probe][needs]") {
  const Folder f;
  const ScopedEnvironment cache_home("XDG_CACHE_HOME", (f.dir / "cache").string());
  const auto load = [&](const PluginNeeds* needs) {
    PluginRegistry r;
    r.load_directories({f.plugins}, needs);
    return r;
  };
  const PluginNeeds add{{"test.add"}, {}};
  // Nothing written down yet: every file loads, and what each provides is written down.
  const PluginRegistry first = load(&add);
  CHECK(ids(first) == std::vector<std::string>{"marker_good", "test_arith"});
  CHECK(first.deferred() == 0);
  const std::string cache = slurp(f.dir / "cache" / "mechgraph" / "plugin-probes");
  CHECK_THAT(cache, Contains("\tprovides test_arith test.constant test.add test.box"));
  CHECK_THAT(cache, Contains("mechgraph_marker_good.so") && Contains("\tprovides marker_good\n"));

  SECTION("known now: the file that provides none of the needs stays unloaded") {
    const PluginRegistry r = load(&add);
    CHECK(ids(r) == std::vector<std::string>{"test_arith"});
    CHECK(r.deferred() == 1);
    CHECK(r.find("test.add"));
    // What is written down is not written again.
    CHECK(slurp(f.dir / "cache" / "mechgraph" / "plugin-probes") == cache);
  }
  SECTION("a plugin the scene requires by id is loaded") {
    const PluginNeeds with_marker{{"test.add"}, {"marker_good"}};
    CHECK(ids(load(&with_marker)) == std::vector<std::string>{"marker_good", "test_arith"});
  }
  SECTION("a need no file claims loads every file, so the error can list every type") {
    const PluginNeeds unknown{{"test.nothing"}, {}};
    const PluginRegistry r = load(&unknown);
    CHECK(r.plugins().size() == 2);
    CHECK(r.deferred() == 0);
  }
  SECTION("a file changed since (another key) loads every file") {
    fs::remove(f.plugins / "mechgraph_marker_good.so");
    fs::copy_file(test_plugin("test_marker_good"), f.plugins / "mechgraph_marker_good.so");
    CHECK(load(&add).plugins().size() == 2);
    CHECK(load(&add).plugins().size() == 1);  // and is known again after that
  }
  SECTION("a file the cache says nothing of (refused: no note is written) loads every file") {
    fs::copy_file(test_plugin("test_arith"), f.plugins / "mechgraph_z_arith_again.so");
    for (int start = 0; start < 2; ++start) {
      const PluginRegistry r = load(&add);
      CHECK(r.plugins().size() == 2);
      REQUIRE(r.skipped().size() == 1);
      CHECK_THAT(r.skipped()[0].reason, Contains("already loaded"));
    }
  }
  SECTION("two files claiming one type load every file") {
    // A note for a third file (as another process could have written it) that claims test.add
    // too: the cache cannot say which one loads first wins, so every file loads.
    fs::copy_file(test_plugin("test_arith"), f.plugins / "mechgraph_z_arith_again.so");
    append_note(f.dir, f.plugins / "mechgraph_z_arith_again.so", "other_arith test.add");
    const PluginRegistry r = load(&add);
    CHECK(ids(r) == std::vector<std::string>{"marker_good", "test_arith"});
    CHECK(r.deferred() == 0);
  }
  SECTION("a note that promised more than its file gave: the rest are loaded too") {
    append_note(f.dir, f.plugins / "mechgraph_marker_good.so", "marker_good test.ghost");
    const PluginNeeds ghost{{"test.ghost"}, {}};
    const PluginRegistry r = load(&ghost);
    CHECK(r.plugins().size() == 2);
    CHECK(r.deferred() == 0);
    CHECK_FALSE(r.find("test.ghost"));
  }
  SECTION("a newer note without an id is no note: every file loads") {
    append_note(f.dir, f.plugins / "mechgraph_marker_good.so", "");
    CHECK(load(&add).plugins().size() == 2);
  }
  SECTION("lines that name no file change nothing") {
    std::ofstream(f.dir / "cache" / "mechgraph" / "plugin-probes", std::ios::app) << "\tprovides test_arith\n\t\n\tprovides\nx";
    CHECK(ids(load(&add)) == std::vector<std::string>{"test_arith"});
  }
  SECTION("without needs every file loads") {
    CHECK(load(nullptr).plugins().size() == 2);
  }
}

TEST_CASE("mechgraph run, sweep, validate and graph load only the plugins their scene uses", "[plugins][probe][needs][cli]") {
  const Folder f;
  const ScopedEnvironment cache_home("XDG_CACHE_HOME", (f.dir / "cache").string());
  const ScopedEnvironment marker("MECHGRAPH_TEST_MARKER", f.marker.string());
  const fs::path scene = f.dir / "add.yaml";
  std::ofstream(scene) << "title: needs\nparams: { len: 2 mm }\nnodes:\n  a: { type: test.constant, params: { value: $len } }\n"
                          "  s: { type: test.add, inputs: { a: a.out, b: a.out } }\noutputs: [ s.sum ]\n";
  const std::string folder = "-q --only-plugin-dir '" + f.plugins.string() + "' ";
  const auto run = [&](const std::string& command) {
    const CommandResult r = run_cli(folder + command);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return r.out;
  };
  // The first start loads both (probe child and host for the marker plugin), the next only what
  // the scene uses: the same numbers, and the marker plugin's code never runs.
  const std::string first = run("run '" + scene.string() + "'");
  CHECK(f.marks() == 2);
  CHECK(run("run '" + scene.string() + "'") == first);
  CHECK(f.marks() == 2);
  CHECK_THAT(run("sweep '" + scene.string() + "' --vary len=1mm,3mm"), Contains("s.sum"));
  CHECK_THAT(run("validate '" + scene.string() + "'"), Contains("valid"));
  CHECK_THAT(run("graph '" + scene.string() + "'"), Contains("digraph"));
  CHECK(f.marks() == 2);
  // A scene that requires the marker plugin loads it (in the host only: the probe cache has it).
  std::ofstream(scene, std::ios::app) << "requires: { marker_good: \">=1\" }\n";
  CHECK(run("run '" + scene.string() + "'") == first);
  CHECK(f.marks() == 3);
  // A type nobody provides is told with every loaded type to choose from, as before.
  std::ofstream(f.dir / "typo.yaml") << "nodes:\n  s: { type: test.ad }\noutputs: [ s.sum ]\n";
  const CommandResult typo = run_cli(folder + "run '" + (f.dir / "typo.yaml").string() + "'");
  CHECK(typo.exit_code != 0);
  CHECK_THAT(typo.err, Contains("did you mean 'test.add'"));
  CHECK(f.marks() == 4);
}

TEST_CASE("mechgraph study finds the ISO 286 limits of a plugin no node of its scene names", "[plugins][probe][needs][cli]") {
  const Folder f;
  fs::copy_file(fs::path(MECHGRAPH_PLUGIN_DIR) / "mechgraph_fits.so", f.plugins / "mechgraph_fits.so");
  const ScopedEnvironment cache_home("XDG_CACHE_HOME", (f.dir / "cache").string());
  const fs::path scene = f.dir / "bore.yaml";
  std::ofstream(scene) << "params: { bore: 20 mm }\nnodes:\n  a: { type: test.constant, params: { value: $bore } }\n"
                          "outputs: [ a.out ]\nuncertainty:\n  samples: 16\n  parameters:\n"
                          "    bore: { iso286: { size: 20 mm, class: H7, distribution: uniform } }\n";
  // The first start loads every plugin and notes what each provides; the second loads by the
  // notes, and fits must be among them.
  for (int start = 0; start < 2; ++start) {
    const CommandResult r = run_cli("-q --only-plugin-dir '" + f.plugins.string() + "' study '" + scene.string() + "' --json");
    INFO(r.err);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("a.out"));
  }
}

TEST_CASE("a scene needs its node types and required plugins and with effects or no nodes every plugin",
          "[plugins][needs]") {
  const SceneSpec scene = parse_scene(
      "nodes:\n  a: { type: test.constant }\n  b: { type: test.constant }\n  s: { type: test.add }\n"
      "requires: { test_arith: \">=1\" }\n",
      "needs.yaml");
  const std::optional<PluginNeeds> needs = host::scene_plugin_needs(scene);
  REQUIRE(needs);
  CHECK(needs->node_types == std::vector<std::string>{"test.constant", "test.add"});
  CHECK(needs->plugin_ids == std::vector<std::string>{"test_arith"});
  // A study's iso286: parameters need the type that answers ISO 286 limits, which no node names.
  const SceneSpec study = parse_scene("nodes:\n  s: { type: test.add }\nuncertainty: { parameters: {} }\n", "study.yaml");
  const std::optional<PluginNeeds> study_needs = host::scene_plugin_needs(study);
  REQUIRE(study_needs);
  CHECK(study_needs->node_types == std::vector<std::string>{"test.add", host::iso286_node_type});
  CHECK_FALSE(host::scene_plugin_needs(parse_scene("nodes:\n  a: { type: test.effectful }\neffects: [ heat ]\n", "e.yaml")));
  CHECK_FALSE(host::scene_plugin_needs(SceneSpec{}));
}
