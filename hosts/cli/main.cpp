// mechgraph: the command-line host. Subcommands live in one file each (cmd_*.cpp).
#include "cli.hpp"
#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/abi_version.hpp>
#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/errors.hpp>

#include <spdlog/spdlog.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>

#ifndef MECHGRAPH_VERSION
#define MECHGRAPH_VERSION "0"
#endif

namespace {

constexpr const char* usage = R"(mechgraph - calculation graphs for mechanism design

usage: mechgraph [--plugin-dir DIR | --only-plugin-dir DIR] [-v|-q] COMMAND [ARGS...]

commands:
  run SCENE [--set NAME=VALUE ...] [--json] [--out DIR]   evaluate the requested outputs
  validate SCENE [--set NAME=VALUE ...]                   load and check, evaluate nothing
  report SCENE [--set NAME=VALUE ...] [--out DIR]         one HTML page: report tables, every curve plotted, CSVs
  graph SCENE [--set NAME=VALUE ...]                      Graphviz DOT; culled nodes shown apart
  plugins [--json]                                        plugins, node types, ports, params
  describe TYPE [--json]                                  one node type in full
  bench SCENE [--node NAME] [--json] [--out DIR]          accuracy knobs: error (own converged reference) vs time
  sweep SCENE (--vary N=A:B:K | --cases F.csv | --sample N=A:B --n K) [--threads N] [--out F] [--shard I/N]
                                                          many designs: one row per case, on all cores
  merge FILE... [--out FILE]                              shards of one sweep back together, checked
  study SCENE [--samples N] [--method M] [--seed S] [--rows FILE] [--json] [--out DIR]
                                                          uncertainty: statistics, Cpk, events, Sobol' indices
  plugin-test (LIB.so | TYPE)... [--set TYPE.P=V] [--continuity TYPE=N] [--strict] [--threads N] [--json]
                                                          conformance suites against a plugin's node types

global options:
  --plugin-dir DIR   also load the plugins in DIR (repeatable; searched first), then those of
                     MECHGRAPH_PLUGIN_PATH (':'-separated), then the built-in ones (lib/mechgraph/plugins)
  --only-plugin-dir DIR
                     load the plugins in DIR only (repeatable): no MECHGRAPH_PLUGIN_PATH, no built-ins
  -v, --verbose      debug logging on stderr
  -q, --quiet        only errors on stderr
  --version          print the version and the plugin ABI version
  -h, --help         this text; `mechgraph COMMAND --help` for a command

exit codes: 0 success, 2 bad scene or usage, 3 evaluation error, 4 plugin load error,
            5 results could not be written, 6 a plugin-test check failed, 130 stopped by Ctrl-C/SIGTERM (rows so far kept)
)";

// An error message as printed: at most 4000 bytes (a 1 MB value must not become a 1 MB message);
// the log sink makes it valid UTF-8 without control sequences.
std::string bounded(std::string_view message) {
  constexpr std::size_t limit = 4000;
  std::string text(message.substr(0, std::min(message.size(), limit)));
  if (message.size() > limit) text += "... (message cut: " + std::to_string(message.size() - limit) + " more bytes)";
  return text;
}

// Standard output is a result file like any other: a write that failed (a full disk, a closed
// terminal) turns `code` 0 into exit 5, never a silent 0.
int stdout_written(int code) {
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    spdlog::error("cannot write the results to standard output (disk full, or the reader went away?)");
    if (code == mechgraph::cli::ok) code = mechgraph::cli::io_error;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mechgraph;
  // A file-size limit (ulimit -f) is a full disk to mechgraph: the write fails with EFBIG and is
  // refused like ENOSPC (exit 5, nothing published), instead of SIGXFSZ ending the process midway.
  std::signal(SIGXFSZ, SIG_IGN);
  // Every log message passes through terminal_text (a message may quote a label or a file name).
  cli::use_terminal_safe_logger("mechgraph");
  spdlog::set_pattern("%^[%l]%$ %v");
  spdlog::set_level(spdlog::level::info);

  cli::GlobalOptions global;
  std::vector<std::string> args(argv + 1, argv + argc);
  std::size_t i = 0;
  for (; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--version") {
      std::cout << "mechgraph " << MECHGRAPH_VERSION << " (plugin ABI " << MECHGRAPH_PLUGIN_ABI_VERSION << ")\n";
      return stdout_written(cli::ok);
    } else if (a == "-h" || a == "--help") {
      std::cout << usage;
      return stdout_written(cli::ok);
    } else if (a == "-v" || a == "--verbose") {
      spdlog::set_level(spdlog::level::debug);
    } else if (a == "-q" || a == "--quiet") {
      spdlog::set_level(spdlog::level::err);
    } else if (a == "--plugin-dir" || a == "--only-plugin-dir") {
      if (i + 1 >= args.size()) {
        std::cerr << "mechgraph: " << a << " needs a folder\n";
        return cli::usage_error;
      }
      global.plugin_dirs.push_back(args[++i]);
      if (a == "--only-plugin-dir") global.only_plugin_dirs = true;
    } else if (a.rfind("--plugin-dir=", 0) == 0) {
      global.plugin_dirs.push_back(a.substr(std::strlen("--plugin-dir=")));
    } else if (a.rfind("--only-plugin-dir=", 0) == 0) {
      global.plugin_dirs.push_back(a.substr(std::strlen("--only-plugin-dir=")));
      global.only_plugin_dirs = true;
    } else {
      break;
    }
  }
  if (i >= args.size()) {
    std::cerr << usage;
    return cli::usage_error;
  }
  const std::string command = args[i];
  std::vector<std::string> rest(args.begin() + static_cast<long>(i) + 1, args.end());
  // Subcommand flags -v/-q are accepted after the command too.
  for (auto it = rest.begin(); it != rest.end();) {
    if (*it == "-v" || *it == "--verbose") { spdlog::set_level(spdlog::level::debug); it = rest.erase(it); }
    else if (*it == "-q" || *it == "--quiet") { spdlog::set_level(spdlog::level::err); it = rest.erase(it); }
    else ++it;
  }

  const std::map<std::string, int (*)(const cli::GlobalOptions&, const std::vector<std::string>&)> commands{
      {"run", &cli::run_command},         {"validate", &cli::validate_command}, {"graph", &cli::graph_command},
      {"plugins", &cli::plugins_command}, {"describe", &cli::describe_command}, {"bench", &cli::bench_command},
      {"sweep", &cli::sweep_command},     {"merge", &cli::merge_command},       {"study", &cli::study_command},       {"plugin-test", &cli::plugin_test_command},
      {"report", &cli::report_command}};
  auto it = commands.find(command);
  if (it == commands.end()) {
    std::vector<std::string> names;
    for (const auto& [name, fn] : commands) names.push_back(name);
    spdlog::error("{}", unknown_name_message("command", command, names));
    return cli::usage_error;
  }
  int code = cli::ok;
  try {
    code = it->second(global, rest);
  } catch (const cli::UsageError& e) {
    spdlog::error("{}: {} (see 'mechgraph {} --help')", command, bounded(e.what()), command);
    code = cli::usage_error;
  } catch (const SceneError& e) {
    spdlog::error("{}", bounded(e.what()));
    code = cli::usage_error;
  } catch (const EvaluationError& e) {
    spdlog::error("{}", bounded(e.what()));
    code = cli::evaluation_error;
  } catch (const PluginError& e) {
    spdlog::error("{}", bounded(e.what()));
    code = cli::plugin_error;
  } catch (const IoError& e) {
    spdlog::error("{}", bounded(e.what()));
    code = cli::io_error;
  } catch (const std::exception& e) {
    spdlog::error("{}", bounded(e.what()));
    code = cli::evaluation_error;
  } catch (...) {
    spdlog::error("{}: failed with an exception that is not a std::exception (a defect; please report it)", command);
    code = cli::evaluation_error;
  }
  return stdout_written(code);
}
