#pragma once
// Shared pieces of the `mechgraph` subcommands: global options, plugin loading, exit codes
// (0 ok, 2 usage or scene, 3 evaluation, 4 plugin load, 5 writing, 6 a plugin-test check, 130 stopped).
#include <mechgraph/graph.hpp>
#include <mechgraph/plugin_registry.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mechgraph::cli {

/// Exit codes (README): 0 success, 2 bad scene or usage, 3 evaluation error, 4 plugin load error,
/// 5 results could not be written, 130 stopped by Ctrl-C or SIGTERM (a sweep: its rows so far kept).
enum ExitCode : int { ok = 0, usage_error = 2, evaluation_error = 3, plugin_error = 4, io_error = 5, conformance_failed = 6,
                     interrupted = 130 };

/// Thrown for a bad command line; main() prints it with the subcommand's usage and exits 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The most worker threads a command accepts (--threads); 0 means one per core.
constexpr unsigned max_threads = 1024;

struct GlobalOptions {
  std::vector<std::string> plugin_dirs;  // --plugin-dir / --only-plugin-dir, in the order given
  bool only_plugin_dirs = false;          // --only-plugin-dir: no MECHGRAPH_PLUGIN_PATH, no built-ins
};

/// Loads the plugins from the search path (--plugin-dir, MECHGRAPH_PLUGIN_PATH, the built-in folder).
/// `first` are plugin files loaded before the search path (plugin-test LIB.so): a copy of the same
/// plugin found later (an installed one) is then the one skipped. A refused `first` file throws.
PluginRegistry load_plugins(const GlobalOptions& options, const std::vector<std::filesystem::path>& first = {});

/// Loads the scene, applies --set overrides and builds the graph against the loaded plugins.
Graph load_graph(const std::string& scene_file, const std::vector<std::string>& sets, const PluginRegistry& registry);

/// The graph a sweep runs: `outputs` ("a.b,c.d", --outputs) replace the scene's outputs and report;
/// without them, tables and handles (not one number per case) are left out of the scene's own
/// outputs with a note. Updates `scene.outputs` to what the graph requests. Throws UsageError for
/// a chosen output that is not a scalar or a series.
Graph build_sweep_graph(SceneSpec& scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                        const std::optional<std::string>& outputs);

/// "12.5 mm" from an SI value, in `unit` when given (else SI), 6 significant digits.
std::string format_value(double si, Dimension dimension, const std::string& unit);

int run_command(const GlobalOptions& g, const std::vector<std::string>& args);
int validate_command(const GlobalOptions& g, const std::vector<std::string>& args);
int graph_command(const GlobalOptions& g, const std::vector<std::string>& args);
int plugins_command(const GlobalOptions& g, const std::vector<std::string>& args);
int describe_command(const GlobalOptions& g, const std::vector<std::string>& args);
int sweep_command(const GlobalOptions& g, const std::vector<std::string>& args);
int merge_command(const GlobalOptions& g, const std::vector<std::string>& args);
int bench_command(const GlobalOptions& g, const std::vector<std::string>& args);
int plugin_test_command(const GlobalOptions& g, const std::vector<std::string>& args);
int report_command(const GlobalOptions& g, const std::vector<std::string>& args);
int study_command(const GlobalOptions& g, const std::vector<std::string>& args);

}  // namespace mechgraph::cli
