#pragma once
// Running a helper program (gnuplot) without a shell: the program is found on PATH by the host, and
// started with posix_spawn from an argument vector, so nothing in a file name, a folder or a title
// is ever read by a shell. Its standard input is /dev/null, its output goes to files the caller
// names, and it is killed when it runs past a time limit.
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mechgraph::cli {

/// The full path of `program` found in the folders of $PATH (an executable regular file), or
/// nullopt. Empty and relative PATH entries are skipped: never the current folder.
std::optional<std::filesystem::path> find_program(const std::string& program);

struct SpawnOutcome {
  bool started = false;     // false: could not be started (why: `error`)
  bool timed_out = false;   // killed after the time limit
  int exit_code = -1;       // when it exited
  int signal = 0;           // when a signal ended it
  std::string error;
  bool succeeded() const { return started && !timed_out && signal == 0 && exit_code == 0; }
  /// "exit code 1", "killed by signal 9", "did not finish within 120 s", "cannot start: ..."
  std::string describe() const;
};

/// Runs `program` (a path, from find_program) with `args` (argv[1..]) in the folder `cwd`, standard
/// input from /dev/null, standard output and error appended to `log` (created, never followed
/// through a symbolic link). Waits at most `limit`, then kills it (SIGKILL) and reports timed_out.
/// The child's environment is this process's with each NAME of `environment` set to its VALUE
/// (e.g. a HOME of its own for chromium).
SpawnOutcome run_program(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& cwd, const std::filesystem::path& log,
                         std::chrono::milliseconds limit,
                         const std::vector<std::pair<std::string, std::string>>& environment = {});

}  // namespace mechgraph::cli
