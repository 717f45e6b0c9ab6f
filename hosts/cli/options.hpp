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

}  // namespace mechgraph::cli
