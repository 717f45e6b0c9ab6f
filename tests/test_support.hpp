#pragma once
// Helpers shared by the framework's tests: loading the test plugins, building graphs from inline
// YAML, running the `mechgraph` command.
#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>
#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/scene.hpp>
#include <mechgraph/testing/node_harness.hpp>
#include <mechgraph/detail/cxx_abi_key.hpp>

#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <map>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <chrono>
#include <thread>

namespace mechgraph::testing {

/// The host's handshake values, read through the public ABI header.
std::string build_fingerprint_for_tests();
std::uint32_t plugin_abi_version_for_tests();

/// An EvalContext for calling node types directly: effects by name, work summed, logs kept (the
/// SDK kit's own).
using RecordingContext = HarnessContext;

/// A node type's parameters with its defaults filled in, then `values` (SI) on top.
inline ParamSet defaults_of(const NodeInfo& info, const std::map<std::string, ParamValue>& values = {}) {
  ParamSet p;
  for (const ParamSpec& s : info.params)
    if (s.default_value) p.set(s.name, *s.default_value);
  for (const auto& [k, v] : values) p.set(k, v);
  return p;
}

/// Whether the libraries this project's compiler builds from the SDK's headers share their C++
/// layer, so that one's objects cross into another as themselves: with gcc; not with clang or
/// libc++, whose builds have no key (mechgraph/detail/cxx_abi_key.hpp).
inline constexpr bool shares_cxx_layer = mechgraph::detail::cxx_abi_key != nullptr;

inline std::filesystem::path test_plugin(const std::string& name) {
  return std::filesystem::path(MECHGRAPH_TEST_PLUGIN_ROOT) / name / ("mechgraph_" + name + ".so");
}

inline const PluginRegistry& arith_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.load_file(test_plugin("test_arith"));
    return r;
  }();
  return registry;
}

inline const PluginRegistry& project_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.load_directory(MECHGRAPH_PLUGIN_DIR);
    return r;
  }();
  return registry;
}

// The built-in plugins with every node type called through the C boundary, as a host of another
// compiler calls them (project_registry() calls them as themselves: one C++ layer, c/node_cxx.h);
// their objects still cross as C++ objects (c/object_cxx.h).
inline const PluginRegistry& project_registry_through_c() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.set_node_types_through_c(true);
    r.load_directory(MECHGRAPH_PLUGIN_DIR);
    return r;
  }();
  return registry;
}

// The built-in cams and valvetrain built on the SDK 1.x entry (test_plugins/builtin_sdk1), in place
// of the pre-1.0 ones: the same node types through the C boundary.
inline const PluginRegistry& builtin_sdk1_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    r.load_directory(std::filesystem::path(MECHGRAPH_TEST_PLUGIN_ROOT) / "builtin_sdk1");
    return r;
  }();
  return registry;
}

// The built-in plugins with cams and valvetrain on the pre-1.0 entry (test_plugins/builtin_pre10)
// in place of the shipped ones: C++ objects cross as they are, so a test can read valvetrain's
// private objects (a spring design) out of a run.
inline void load_builtin_pre10(PluginRegistry& r) {
  for (const auto& entry : std::filesystem::directory_iterator(MECHGRAPH_PLUGIN_DIR)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".so" && name != "mechgraph_cams.so" && name != "mechgraph_valvetrain.so") r.load_file(entry.path());
  }
  r.load_directory(std::filesystem::path(MECHGRAPH_TEST_PLUGIN_ROOT) / "builtin_pre10");
}
inline const PluginRegistry& builtin_pre10_registry() {
  static const PluginRegistry registry = [] {
    PluginRegistry r;
    load_builtin_pre10(r);
    return r;
  }();
  return registry;
}

// A file of this source tree as text ("bench/peers/stages123_study.yaml"); throws when it is
// missing or empty.
inline std::string source_file_text(const std::string& relative) {
  std::ifstream in(std::filesystem::path(MECHGRAPH_SOURCE_DIR) / relative);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.empty()) throw std::runtime_error("no text in " + relative + " of the source tree");
  return text;
}

inline Graph graph_from(const std::string& yaml, const PluginRegistry& registry = arith_registry(),
                        const std::vector<Override>& overrides = {}) {
  return build_graph(parse_scene(yaml, "scene.yaml"), registry, overrides);
}

/// Builds and evaluates an inline scene with a fresh memo cache.
inline RunResult run_yaml(const std::string& yaml, const PluginRegistry& registry, const std::vector<Override>& overrides = {}) {
  MemoCache cache;
  return evaluate(graph_from(yaml, registry, overrides), cache);
}

/// The value of one requested output of a run.
inline const Value& output(const RunResult& r, const std::string& label) {
  for (const OutputValue& o : r.outputs)
    if (o.label == label) return o.value;
  throw std::runtime_error("no output " + label);
}

/// The number at one requested scalar output of a run.
inline double scalar_output(const RunResult& r, const std::string& label) { return output(r, label).as_scalar(); }

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs a shell command, capturing stdout and stderr.
inline CommandResult run_command(const std::string& shell_command) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path();
  const auto out_file = dir / ("mechgraph_test_out_" + std::to_string(::getpid()) + "_" + std::to_string(counter));
  const auto err_file = dir / ("mechgraph_test_err_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const std::string command = shell_command + " >'" + out_file.string() + "' 2>'" + err_file.string() + "'";
  const int status = std::system(command.c_str());
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  CommandResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out_file), slurp(err_file)};
  std::filesystem::remove(out_file);
  std::filesystem::remove(err_file);
  return r;
}

/// Runs the mechgraph command with `args` (a shell fragment), capturing stdout and stderr.
inline CommandResult run_cli(const std::string& args) { return run_command(std::string("'") + MECHGRAPH_CLI + "' " + args); }

/// The command-line option that loads the arithmetic test plugin alone.
inline std::string arith_plugin_dir_option() {
  return "--only-plugin-dir '" + test_plugin("test_arith").parent_path().string() + "'";
}

/// Where `program` is on PATH (absolute entries only, an executable regular file), without a shell;
/// empty if nowhere. For tests that draw with an optional tool such as gnuplot.
inline std::filesystem::path find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::string rest = path;
  for (std::size_t start = 0; start <= rest.size();) {
    const std::size_t end = std::min(rest.find(':', start), rest.size());
    const std::filesystem::path dir = rest.substr(start, end - start);
    start = end + 1;
    if (!dir.is_absolute()) continue;
    const auto candidate = dir / program;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

/// A scratch folder `NAME_PID` under the temporary folder, made if missing.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

/// Starts the mechgraph command with `args` (a shell fragment of the test's own fixed text) in the
/// background and returns its process id; its exit status lands in `status_file` when it ends.
/// `pid_file` is scratch space.
inline pid_t start_cli_in_background(const std::string& args, const std::filesystem::path& status_file,
                                     const std::filesystem::path& pid_file) {
  std::filesystem::remove(pid_file);
  std::filesystem::remove(status_file);
  const std::string command = "( '" + std::string(MECHGRAPH_CLI) + "' " + args + " >/dev/null 2>&1 & echo $! > '" +
                              pid_file.string() + "'; wait $!; echo $? > '" + status_file.string() + "' ) >/dev/null 2>&1 &";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("cannot start: " + command);
  pid_t pid = 0;
  for (int i = 0; i < 500 && pid == 0; ++i) {
    std::ifstream(pid_file) >> pid;
    if (pid == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (pid <= 0) throw std::runtime_error("the command did not start: " + command);
  return pid;
}

}  // namespace mechgraph::testing
