#pragma once
// Running `mechgraph` the way a hostile-input test needs: arguments as a vector (a quote or a
// newline in an argument reaches the program as it is, no shell in between), stdout and stderr
// captured to files, stdin from /dev/null, a time limit so a hang is a failure and not a stuck
// suite. Also a scratch folder per test.
#include "file_support.hpp"

#include <chrono>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <signal.h>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace mechgraph::hostile {

struct Outcome {
  int exit_code = -1;   // -1: killed (signal) or timed out
  bool timed_out = false;
  std::string out, err;
};

using mechgraph::testing::slurp;

/// A fresh, empty folder under the system's temporary folder, removed when the object goes.
struct Scratch {
  std::filesystem::path dir;
  explicit Scratch(const std::string& name) {
    dir = std::filesystem::temp_directory_path() / ("mechgraph_hostile_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  }
};

/// Runs `program` with `args` in `cwd`; stdout goes to `stdout_path` when given (e.g. /dev/full).
inline Outcome run_argv(const std::string& program, const std::vector<std::string>& args,
                        const std::filesystem::path& cwd = std::filesystem::temp_directory_path(),
                        const std::string& stdout_path = {}, std::chrono::seconds limit = std::chrono::seconds(120)) {
  static int counter = 0;
  const auto base = std::filesystem::temp_directory_path() / ("mechgraph_hostile_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const std::string out_file = stdout_path.empty() ? base.string() + ".out" : stdout_path;
  const std::string err_file = base.string() + ".err";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  std::vector<std::string> text{program};
  text.insert(text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : text) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t child = 0;
  Outcome o;
  if (::posix_spawn(&child, program.c_str(), &actions, nullptr, argv.data(), environ) != 0) {
    posix_spawn_file_actions_destroy(&actions);
    return o;
  }
  posix_spawn_file_actions_destroy(&actions);
  const auto deadline = std::chrono::steady_clock::now() + limit;
  int status = 0;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      o.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!o.timed_out && WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  if (stdout_path.empty()) {
    o.out = slurp(out_file);
    std::filesystem::remove(out_file);
  }
  o.err = slurp(err_file);
  std::filesystem::remove(err_file);
  return o;
}

/// The mechgraph command with `args`.
inline Outcome run_mechgraph(const std::vector<std::string>& args, const std::filesystem::path& cwd = std::filesystem::temp_directory_path(),
                         const std::string& stdout_path = {}) {
  return run_argv(MECHGRAPH_CLI, args, cwd, stdout_path);
}

/// A scene file path inside the source tree.
inline std::string source_file(const std::string& relative) { return std::string(MECHGRAPH_SOURCE_DIR) + "/" + relative; }

}  // namespace mechgraph::hostile
