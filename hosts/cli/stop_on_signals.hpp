#pragma once
// Ctrl-C and SIGTERM (Slurm's, at a job's time limit) as a request to stop: while a StopOnSignals
// lives, either sets stop_on_signals_flag() and puts the default handler back, so a second one
// ends the process at once. The work polls the flag (a sweep lets its started cases finish and
// their rows land; a study reports nothing), and the command exits 130.
#include <atomic>

namespace mechgraph::cli {

/// The flag the handlers set: cleared when a StopOnSignals is made.
const std::atomic<bool>& stop_on_signals_flag();

class StopOnSignals {
 public:
  StopOnSignals();
  ~StopOnSignals();  // the handlers before it put back, whether the work returned or threw
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  void (*previous_int_)(int) = nullptr;
  void (*previous_term_)(int) = nullptr;
};

}  // namespace mechgraph::cli
