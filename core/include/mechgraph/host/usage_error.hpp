#pragma once
// What a host refuses of a request before anything runs: an option out of range, a resumed file
// that is not this sweep's. Each host maps it to its own "usage" failure (the CLI: exit code 2 with
// the command's usage; Python: ValueError).
#include <stdexcept>

namespace mechgraph::host {

/// A request the user can correct (an option, a file being resumed); the message says what.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The most worker threads a host accepts (--threads, threads=); 0 means one per core.
constexpr unsigned max_threads = 1024;

}  // namespace mechgraph::host
