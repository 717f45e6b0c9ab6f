#pragma once
// Boost.Program_options glue shared by the subcommands: parse, print --help, map errors to usage.
#include "cli.hpp"

#include <mechgraph/work_estimate.hpp>

#include <boost/program_options.hpp>

#include <cmath>

#include <iostream>

namespace mechgraph::cli {

namespace po = boost::program_options;

/// Parses `args`; returns false (after printing help) when --help was given.
inline bool parse_options(const std::vector<std::string>& args, const po::options_description& visible,
                          const po::options_description& all, const po::positional_options_description& positional,
                          po::variables_map& vm, const char* synopsis) {
  try {
    po::store(po::command_line_parser(args).options(all).positional(positional).run(), vm);
    if (vm.count("help")) {
      std::cout << "usage: " << synopsis << "\n\n" << visible << "\n";
      return false;
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw UsageError(e.what());
  }
  return true;
}

/// The options of every command that reads a scene: --help, --set (SCENE is positional) and the
/// work budget (--max-work, --max-output, --max-memory) checked before anything is evaluated.
inline void add_scene_options(po::options_description& visible) {
  const WorkBudget defaults;
  visible.add_options()("help,h", "this text")("set", po::value<std::vector<std::string>>()->composing(),
                                                "override a parameter: --set rpm=6000rpm, --set part.length=10mm")(
      "max-work", po::value<double>()->default_value(defaults.max_work, "1e9"),
      "refuse a scene estimated at more work items (each node's forecast, or its curve points, samples, bins, records) than this (a sweep: all its cases, default 1e12)")(
      "max-output", po::value<double>()->default_value(defaults.max_bytes, "268435456"),
      "refuse a scene whose curves would write more bytes than this, to files (--out) or to standard output (run --json) (256 MiB)")(
      "max-memory", po::value<double>()->default_value(defaults.max_memory, "4294967296"),
      "refuse a scene estimated to hold more bytes of memory than this (4 GiB; a sweep: its threads together)");
}

/// The budget the command line sets; throws UsageError for one that is not a positive number.
inline WorkBudget work_budget(const po::variables_map& vm) {
  WorkBudget b;
  b.max_work = vm["max-work"].as<double>();
  b.max_bytes = vm["max-output"].as<double>();
  b.max_memory = vm["max-memory"].as<double>();
  for (const double v : {b.max_work, b.max_bytes, b.max_memory})
    if (!(v > 0) || !std::isfinite(v)) throw UsageError("--max-work, --max-output and --max-memory take a positive number");
  return b;
}

/// Parses a scene command (SCENE plus `visible`); returns false after printing --help.
inline bool parse_scene_command(const std::vector<std::string>& args, const po::options_description& visible,
                                po::variables_map& vm, const char* synopsis) {
  po::options_description all;
  all.add(visible).add_options()("scene", po::value<std::string>()->required(), "scene file");
  po::positional_options_description positional;
  positional.add("scene", 1);
  return parse_options(args, visible, all, positional, vm, synopsis);
}

/// The scene read from the command line (before its plugins: plugins_for_scene), made into a graph
/// with its --set overrides. Its curves count against --max-output when they are written: to files
/// (--out) or, `prints_curves`, to standard output (run --json).
inline Graph load_scene_graph(const po::variables_map& vm, const SceneSpec& scene, const PluginRegistry& registry,
                              bool prints_curves = false) {
  const auto sets = vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{};
  Graph graph = load_graph(scene, sets, registry);
  check_work_budget(graph, estimate_work(graph), work_budget(vm), 1, vm.count("out") > 0 || prints_curves);
  return graph;
}

/// The plugins a command that runs `scene` loads: those the probe cache knows provide the scene's
/// node types and required plugins, or all of them when it cannot tell (host::scene_plugin_needs).
inline PluginRegistry plugins_for_scene(const GlobalOptions& g, const SceneSpec& scene) {
  const std::optional<PluginNeeds> needs = host::scene_plugin_needs(scene);
  return load_plugins(g, {}, needs ? &*needs : nullptr);
}

}  // namespace mechgraph::cli
