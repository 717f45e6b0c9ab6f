// Plugin folders survive bad files: a truncated library, a file that is no library at all, a library
// that crashes while it loads, a file
// or folder others can write. Each is refused with its path and reason before the dynamic loader
// maps it; load_directory skips it and loads the rest.
#include "file_support.hpp"
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sys/stat.h>
#include <unistd.h>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A fresh folder (mode 755) holding a copy of the good test plugin.
fs::path folder_with_good_plugin(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("mg_safety_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::permissions(dir, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                           fs::perms::others_exec);
  fs::copy_file(test_plugin("test_arith"), dir / "mechgraph_test_arith.so");
  return dir;
}

void write_truncated_copy(const fs::path& to, std::size_t keep) {
  std::ifstream in(test_plugin("test_arith"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  REQUIRE(bytes.size() > keep);
  std::ofstream(to, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(keep));
}

}  // namespace

TEST_CASE("a truncated library is refused before it is mapped, and the rest of its folder loads", "[plugins][safety]") {
  const fs::path dir = folder_with_good_plugin("truncated");
  const auto full = fs::file_size(dir / "mechgraph_test_arith.so");
  for (std::size_t keep : {std::size_t{40}, std::size_t{64}, std::size_t{4096}, static_cast<std::size_t>(full / 2),
                           static_cast<std::size_t>(full - 1)}) {
    INFO("kept " << keep << " of " << full << " bytes");
    write_truncated_copy(dir / "mechgraph_broken.so", keep);
    PluginRegistry r;
    r.load_directory(dir);  // must not die with SIGBUS
    REQUIRE(r.plugins().size() == 1);
    CHECK(r.plugins()[0].id == "test_arith");
    REQUIRE(r.skipped().size() == 1);
    CHECK(r.skipped()[0].path == dir / "mechgraph_broken.so");
    CHECK_THAT(r.skipped()[0].reason, Contains("mechgraph_broken.so") &&
                                          (Contains("truncated") || Contains("not an ELF") || Contains("cannot be loaded")));
  }
  fs::remove_all(dir);
}

TEST_CASE("a plugin file or folder that others can write is refused, saying how to fix it", "[plugins][safety]") {
  const fs::path dir = folder_with_good_plugin("writable");
  fs::permissions(dir / "mechgraph_test_arith.so", fs::perms::others_write, fs::perm_options::add);
  PluginRegistry file_check;
  CHECK_THROWS_WITH(file_check.load_file(dir / "mechgraph_test_arith.so"),
                    Contains("writable by group or others") && Contains("chmod go-w"));
  fs::permissions(dir / "mechgraph_test_arith.so", fs::perms::others_write, fs::perm_options::remove);
  fs::permissions(dir, fs::perms::group_write, fs::perm_options::add);
  PluginRegistry folder_check;
  CHECK_THROWS_WITH(folder_check.load_directory(dir), Contains("folder is writable by group or others"));
  fs::remove_all(dir);
}

TEST_CASE("the command line: skipped files are shown, and named when the scene needs a type they may hold", "[plugins][safety][cli]") {
  const fs::path dir = folder_with_good_plugin("cli");
  std::ofstream(dir / "mechgraph_notes.so") << "these are not machine instructions";
  const std::string plugins = "--only-plugin-dir '" + dir.string() + "' ";
  const auto listing = run_cli(plugins + "plugins");
  CHECK(listing.exit_code == 0);
  CHECK_THAT(listing.out, Contains("test_arith") && Contains("skipped") && Contains("mechgraph_notes.so") &&
                              Contains("not an ELF"));
  std::ofstream(dir / "scene.yaml") << "nodes: { a: { type: test.constant, params: { value: 1 mm } } }\noutputs: [a.out]\n";
  CHECK(run_cli(plugins + "-q run '" + (dir / "scene.yaml").string() + "'").exit_code == 0);
  std::ofstream(dir / "missing.yaml") << "nodes: { a: { type: other.thing } }\noutputs: [a.out]\n";
  const auto missing = run_cli(plugins + "-q run '" + (dir / "missing.yaml").string() + "'");
  CHECK(missing.exit_code == 4);
  CHECK_THAT(missing.err, Contains("unknown node type 'other.thing'") && Contains("mechgraph_notes.so"));
  fs::remove_all(dir);
}

TEST_CASE("a library that crashes in its static constructors is refused, the host and the rest survive", "[plugins][safety]") {
  // The probe loads each file in a child process first: the crash takes the child down only.
  const fs::path dir = folder_with_good_plugin("crash");
  fs::copy_file(test_plugin("test_crash_ctor"), dir / "mechgraph_test_crash_ctor.so");
  PluginRegistry r;
  r.load_directory(dir);
  CHECK(r.find("test.add"));
  REQUIRE(r.skipped().size() == 1);
  CHECK_THAT(r.skipped()[0].reason, Contains("mechgraph_test_crash_ctor.so") && Contains("crashed") &&
                                        Contains("static constructors"));
  // Loading it alone is a PluginError naming it, not the end of this process.
  CHECK_THROWS_WITH(PluginRegistry().load_file(dir / "mechgraph_test_crash_ctor.so"), Contains("crashed"));
  fs::remove_all(dir);
}

namespace {

// The process ids a marker library wrote when its constructors ran (empty: its code never ran).
std::vector<long> marks(const fs::path& marker) {
  std::vector<long> pids;
  std::ifstream in(marker);
  for (long pid = 0; in >> pid;) pids.push_back(pid);
  return pids;
}

// Sets MECHGRAPH_TEST_MARKER for the scope and removes the file it names.
struct MarkerFile {
  fs::path path;
  explicit MarkerFile(const std::string& name)
      : path(fs::temp_directory_path() / ("mg_marker_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove(path);
    ::setenv("MECHGRAPH_TEST_MARKER", path.c_str(), 1);
  }
  ~MarkerFile() {
    ::unsetenv("MECHGRAPH_TEST_MARKER");
    std::error_code ec;
    fs::remove(path, ec);
  }
};

}  // namespace

// The trust model (README, "Plugins are code"): the probe protects against crashes and broken files,
// not against malice; but no code of a file that does not declare itself a plugin ever runs, and a
// file the probe refused is never loaded in the host.
TEST_CASE("a library without the plugin entry never runs, not even in the probe's child", "[plugins][safety][trust]") {
  const MarkerFile marker("no_entry");
  const fs::path dir = folder_with_good_plugin("no_entry_marker");
  fs::copy_file(test_plugin("test_marker_no_entry"), dir / "mechgraph_marker.so");
  PluginRegistry r;
  r.load_directory(dir);
  CHECK(r.find("test.add"));
  REQUIRE(r.skipped().size() == 1);
  CHECK_THAT(r.skipped()[0].reason, Contains("has no entry 'mechgraph_plugin_entry'") && Contains("not a mechgraph plugin"));
  CHECK(marks(marker.path).empty());
  CHECK_THROWS_WITH(PluginRegistry().load_file(dir / "mechgraph_marker.so"), Contains("has no entry"));
  CHECK(marks(marker.path).empty());
  fs::remove_all(dir);
}

TEST_CASE("a library the probe refuses is not loaded in the host: its constructors ran only in the child",
          "[plugins][safety][trust]") {
  const MarkerFile marker("foreign_abi");
  for (int attempt = 0; attempt < 2; ++attempt) {  // the second time: a refusal is never cached as good
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_marker_foreign_abi")),
                      Contains("built for plugin ABI version " + std::to_string(plugin_abi_version_for_tests() + 1)));
    const std::vector<long> pids = marks(marker.path);
    REQUIRE(pids.size() == static_cast<std::size_t>(attempt + 1));  // one probe each time
    for (long pid : pids) CHECK(pid != static_cast<long>(::getpid()));
  }
}

TEST_CASE("a symbolic link in a plugin folder is followed only within the folder", "[plugins][safety][trust]") {
  const MarkerFile marker("symlink");
  const fs::path dir = folder_with_good_plugin("symlink");
  // Outside: a plugin elsewhere, and a library that is no plugin (as a link to a system library is).
  fs::create_symlink(test_plugin("test_marker_foreign_abi"), dir / "mechgraph_elsewhere.so");
  fs::create_symlink(test_plugin("test_marker_no_entry"), dir / "mechgraph_system_lib.so");
  // Inside: a versioned name, as installs make them.
  fs::copy_file(test_plugin("test_bad_version"), dir / "mechgraph_versioned.so.1");
  fs::create_symlink("mechgraph_versioned.so.1", dir / "mechgraph_versioned.so");
  PluginRegistry r;
  r.load_directory(dir);
  CHECK(r.find("test.add"));
  std::map<std::string, std::string> reasons;
  for (const SkippedPlugin& s : r.skipped()) reasons[s.path.filename().string()] = s.reason;
  REQUIRE(reasons.size() == 3);
  CHECK_THAT(reasons["mechgraph_elsewhere.so"], Contains("symbolic link") && Contains("outside its plugin folder"));
  CHECK_THAT(reasons["mechgraph_system_lib.so"], Contains("symbolic link") && Contains("outside its plugin folder"));
  // The link within the folder was followed: its target was loaded and judged on its own merits.
  CHECK_THAT(reasons["mechgraph_versioned.so"], Contains("is not a semantic version"));
  CHECK(marks(marker.path).empty());
  fs::remove_all(dir);
}

TEST_CASE("the ELF symbol reader finds the entry of every built-in plugin and of no system library",
          "[plugins][safety][trust]") {
  // A second method: the dynamic loader itself (dlsym) on the same files.
  const fs::path builtin = MECHGRAPH_PLUGIN_DIR;
  int seen = 0;
  for (const auto& entry : fs::directory_iterator(builtin)) {
    if (entry.path().extension() != ".so") continue;
    ++seen;
    INFO(entry.path());
    PluginRegistry r;
    CHECK_NOTHROW(r.load_file(entry.path()));
  }
  CHECK(seen >= 5);
  for (const char* system : {"/lib/x86_64-linux-gnu/libm.so.6", "/lib/x86_64-linux-gnu/libz.so.1"}) {
    if (!fs::exists(system)) continue;
    INFO(system);
    CHECK_THROWS_WITH(PluginRegistry().load_file(system), Contains("has no entry") || Contains("owned by"));
  }
}

namespace {

// Sets an environment variable for the scope, and unsets it after.
struct ScopedVariable {
  std::string name;
  ScopedVariable(std::string n, const std::string& value) : name(std::move(n)) { ::setenv(name.c_str(), value.c_str(), 1); }
  ~ScopedVariable() { ::unsetenv(name.c_str()); }
};

}  // namespace

// The probe cache saves a process start one probe child per plugin: a file it names, unchanged,
// is loaded without one. It is read once per registry and looked up as whole lines, so a start
// costs the same with a cache of thousands of lines (one per file any build tree on the machine
// loaded) and a line that merely contains the file's key does not count.
TEST_CASE("a plugin the probe cache names is loaded without a probe, only its whole line counts",
          "[plugins][safety][probe]") {
  const MarkerFile marker("probe_cache");
  const fs::path dir = fresh_dir(fs::temp_directory_path(), "mg_probe_cache_" + std::to_string(::getpid()));
  fs::create_directories(dir / "plugins");
  fs::permissions(dir / "plugins", fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                       fs::perms::others_read | fs::perms::others_exec);
  const fs::path plugin = dir / "plugins" / "mechgraph_marker_good.so";
  fs::copy_file(test_plugin("test_marker_good"), plugin);
  const ScopedVariable cache_home("XDG_CACHE_HOME", (dir / "cache").string());
  const fs::path probes = dir / "cache" / "mechgraph" / "plugin-probes";
  // How many processes ran the plugin's constructors in one start of the command: 2 when it was
  // probed (the probe's child, then the host), 1 when the cache had it.
  const auto processes_that_loaded_it = [&] {
    fs::remove(marker.path);
    const CommandResult r = run_cli("-q --only-plugin-dir '" + (dir / "plugins").string() + "' plugins");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return marks(marker.path).size();
  };
  // The key the cache remembers a file by: its path, size, change time and inode.
  struct stat st {};
  REQUIRE(::stat(plugin.c_str(), &st) == 0);
  const std::string key = fs::canonical(plugin).string() + " " + std::to_string(st.st_size) + " " +
                          std::to_string(st.st_ctim.tv_sec) + "." + std::to_string(st.st_ctim.tv_nsec) + " " +
                          std::to_string(st.st_ino);
  std::string others;  // a cache shared by many build trees
  for (int i = 0; i < 2000; ++i)
    others += "/elsewhere/build" + std::to_string(i) + "/mechgraph_marker_good.so 4096 1795902881.259305667 " + std::to_string(i) + "\n";

  SECTION("the first start probes and remembers it; the next ones load it without a probe") {
    CHECK(processes_that_loaded_it() == 2);
    CHECK(slurp(probes).find(key + "\n") != std::string::npos);
    CHECK(processes_that_loaded_it() == 1);
    write_file(probes, others + key + "\n" + others);
    CHECK(processes_that_loaded_it() == 1);
  }
  SECTION("a line that only contains the key is not the key") {
    fs::create_directories(probes.parent_path());
    write_file(probes, others + "x" + key + "\n" + key + " 1\n" + others);
    CHECK(processes_that_loaded_it() == 2);
  }
  fs::remove_all(dir);
}

// Every build, upgrade or removed build tree leaves the keys of its plugin files in the cache, and
// each start reads the whole file. Past 32 KiB, the next line written first drops the lines of
// files that changed or are gone, and repeated lines; the lines of files still there are kept.
TEST_CASE("the probe cache drops the lines of changed and removed files when it grows",
          "[plugins][safety][probe]") {
  const MarkerFile marker("probe_prune");
  const fs::path dir = fresh_dir(fs::temp_directory_path(), "mg_probe_prune_" + std::to_string(::getpid()));
  const fs::path plugins = dir / "plugins with a space";
  fs::create_directories(plugins);
  fs::permissions(plugins, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                               fs::perms::others_exec);
  const fs::path first = plugins / "mechgraph_marker_good.so";
  fs::copy_file(test_plugin("test_marker_good"), first);
  const ScopedVariable cache_home("XDG_CACHE_HOME", (dir / "cache").string());
  const fs::path probes = dir / "cache" / "mechgraph" / "plugin-probes";
  const auto processes_that_loaded = [&] {
    fs::remove(marker.path);
    const CommandResult r = run_cli("-q --only-plugin-dir '" + plugins.string() + "' plugins");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return marks(marker.path).size();
  };
  const auto key_of = [](const fs::path& file) {
    struct stat st {};
    REQUIRE(::stat(file.c_str(), &st) == 0);
    return fs::canonical(file).string() + " " + std::to_string(st.st_size) + " " + std::to_string(st.st_ctim.tv_sec) + "." +
           std::to_string(st.st_ctim.tv_nsec) + " " + std::to_string(st.st_ino);
  };
  CHECK(processes_that_loaded() == 2);  // probed, then remembered with what it provides
  const std::string first_key = key_of(first);
  const std::string first_lines = slurp(probes);
  REQUIRE(first_lines.find(first_key + "\n") != std::string::npos);
  REQUIRE(first_lines.find(first_key + "\tprovides marker_good\n") != std::string::npos);
  // Stale lines: files that are gone (one in a folder with spaces), and the first file as it was
  // before a rebuild (another change time); the current lines twice.
  std::string stale;
  for (int i = 0; i < 600; ++i) {
    const std::string gone = "/gone/build " + std::to_string(i) + "/mechgraph_marker_good.so 4096 1795902881.259305667 " + std::to_string(i);
    stale += gone + "\n" + gone + "\tprovides marker_good\n";
  }
  const std::string rebuilt = fs::canonical(first).string() + " 4096 1.5 7";
  stale += rebuilt + "\n" + rebuilt + "\tprovides marker_good\n";
  const std::string grown = stale + first_lines + first_lines;
  write_file(probes, grown);
  REQUIRE(grown.size() > (32u << 10));
  CHECK(processes_that_loaded() == 1);  // known: loaded without a probe
  CHECK(slurp(probes) == grown);        // nothing written, nothing dropped
  // A new file is probed and its lines written: the stale lines go first.
  const fs::path second = plugins / "mechgraph_test_arith.so";
  fs::copy_file(test_plugin("test_arith"), second);
  CHECK(processes_that_loaded() == 1);  // the marker plugin still from the cache
  const std::string after = slurp(probes);
  INFO(after);
  CHECK(after.find("/gone/") == std::string::npos);
  CHECK(after.find(rebuilt) == std::string::npos);
  const std::string second_key = key_of(second);
  for (const std::string& line : {first_key + "\n", first_key + "\tprovides marker_good\n", second_key + "\n"}) {
    const std::size_t at = after.find(line);
    CHECK(at != std::string::npos);
    CHECK(after.find(line, at + 1) == std::string::npos);  // once
  }
  CHECK(after.find(second_key + "\tprovides test_arith ") != std::string::npos);
  CHECK(after.size() < 2048);
  // What is kept still counts: neither file is probed again, so nothing more is written.
  CHECK(processes_that_loaded() == 1);
  CHECK(slurp(probes) == after);
  fs::remove_all(dir);
}
