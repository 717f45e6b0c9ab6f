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
/// work budget (--max-work, --max-output) checked before anything is evaluated.
inline void add_scene_options(po::options_description& visible) {
  const WorkBudget defaults;
  visible.add_options()("help,h", "this text")("set", po::value<std::vector<std::string>>()->composing(),
                                                "override a parameter: --set rpm=6000rpm, --set cam.max_lift=10mm")(
      "max-work", po::value<double>()->default_value(defaults.max_work, "1e9"),
      "refuse a scene estimated at more work items (curve points, samples, bins, records) than this (a sweep: all its cases, default 1e12)")(
      "max-output", po::value<double>()->default_value(defaults.max_bytes, "268435456"),
      "refuse a scene whose curves would write more bytes of files than this (256 MiB)");
}

/// The budget the command line sets; throws UsageError for one that is not a positive number.
inline WorkBudget work_budget(const po::variables_map& vm) {
  WorkBudget b;
  b.max_work = vm["max-work"].as<double>();
  b.max_bytes = vm["max-output"].as<double>();
  if (!(b.max_work > 0) || !(b.max_bytes > 0) || !std::isfinite(b.max_work) || !std::isfinite(b.max_bytes))
    throw UsageError("--max-work and --max-output take a positive number");
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

/// The scene named on the command line, loaded and checked with its --set overrides.
inline Graph load_scene_graph(const po::variables_map& vm, const PluginRegistry& registry) {
  const auto sets = vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{};
  Graph graph = load_graph(vm["scene"].as<std::string>(), sets, registry);
  check_work_budget(graph, estimate_work(graph), work_budget(vm), 1, vm.count("out") > 0);
  return graph;
}

}  // namespace mechgraph::cli
