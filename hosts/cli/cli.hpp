#pragma once
// Shared pieces of the `mechgraph` subcommands: global options, plugin loading, exit codes
// (0 ok, 2 usage or scene, 3 evaluation, 4 plugin load, 5 writing, 6 a plugin-test check, 130 stopped).
#include <mechgraph/graph.hpp>
#include <mechgraph/host/exit_codes.hpp>
#include <mechgraph/host/plugin_search.hpp>
#include <mechgraph/host/scene_loading.hpp>
#include <mechgraph/host/usage_error.hpp>
#include <mechgraph/plugin_registry.hpp>
#include <mechgraph/shown_number.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mechgraph::cli {

/// The host rules every host shares (core/include/mechgraph/host/): the CLI's names for them.
/// A bad command line is a host::UsageError; main() prints it with the subcommand's usage and exits 2.
using namespace host;
using GlobalOptions = host::PluginSearch;

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
