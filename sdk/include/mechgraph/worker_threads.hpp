#pragma once
// Threads that may not start. A process limit (a container's pids.max, RLIMIT_NPROC), an
// address-space limit (RLIMIT_AS: each thread needs its stack mapped) or many nested pools make
// std::thread's constructor throw; a pool that lets that escape while other threads run ends the
// process with std::terminate. Here a thread that cannot start is simply not started: the work is
// shared among those that did (each takes its tasks from a shared counter or queue), and the caller
// always works too, so the work gets done on one thread at worst. Header-only: plugins compile it in.
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace mechgraph {

/// Up to `extra` threads running `work(w)`, w = 1..extra, started at construction; the first that
/// cannot start ends the starting (its `work` never runs). Joined by join() or the destructor.
class WorkerThreads {
 public:
  template <class Work>
  WorkerThreads(unsigned extra, const Work& work) {
    try {
      threads_.reserve(extra);
    } catch (...) {
      return;  // no memory for the handles: no extra threads
    }
    for (unsigned w = 1; w <= extra; ++w) {
      try {
        threads_.emplace_back(work, w);
      } catch (const std::system_error&) {
        break;
      }
    }
  }
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;
  ~WorkerThreads() { join(); }

  /// How many threads started (0..extra).
  unsigned started() const { return static_cast<unsigned>(threads_.size()); }
  /// Whether all that were asked for started.
  bool complete(unsigned extra) const { return started() == extra; }

  void join() {
    for (std::thread& t : threads_)
      if (t.joinable()) t.join();
  }

 private:
  std::vector<std::thread> threads_;
};

/// Runs `work(w)` on the calling thread (w = 0) and on up to `count - 1` more (w = 1..count-1), as
/// many as can start, and returns when all have returned. `work` must take its tasks from shared
/// state, so that fewer workers still do all of it; it must not throw (catch and hand the
/// exception over). Returns the number of workers that ran (1..count).
template <class Work>
unsigned run_on_workers(unsigned count, const Work& work) {
  WorkerThreads more(count > 1 ? count - 1 : 0, work);
  work(0u);
  more.join();
  return more.started() + 1;
}

}  // namespace mechgraph
