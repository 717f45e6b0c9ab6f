#pragma once
// Boost.Program_options glue shared by the subcommands: parse, print --help, map errors to usage.
#include "cli.hpp"

#include <boost/program_options.hpp>

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

/// The options of every command that reads a scene: --help and --set (SCENE is positional).
inline void add_scene_options(po::options_description& visible) {
  visible.add_options()("help,h", "this text")("set", po::value<std::vector<std::string>>()->composing(),
                                                "override a parameter: --set rpm=6000rpm, --set cam.max_lift=10mm");
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
  return load_graph(vm["scene"].as<std::string>(), sets, registry);
}

}  // namespace mechgraph::cli
