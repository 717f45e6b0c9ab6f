#pragma once
// Progress of a sweep on stderr: a bar redrawn in place when stderr is a terminal (cases done,
// failures, rate, time left), a log line every few seconds when it is not (a batch job's log).
#include <chrono>
#include <cstddef>

namespace mechgraph::cli {

class SweepProgress {
 public:
  /// `total` cases to run in this process; silent when `enabled` is false (-q).
  SweepProgress(std::size_t total, bool enabled);
  void update(std::size_t done, std::size_t failed);
  /// Ends the bar's line.
  void finish(std::size_t done, std::size_t failed);

 private:
  void draw(std::size_t done, std::size_t failed, bool final);
  std::size_t total_;
  bool enabled_, terminal_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace mechgraph::cli
