#pragma once
// Numbered chunks of work shared among worker threads (mechgraph/worker_threads.hpp): each worker
// makes its own state once (a copy of a graph, buffers), then takes chunks from a shared counter
// until none is left. A chunk's result goes to its own slot, so what the chunks make does not
// depend on how many workers took them. The first exception any worker throws stops the others
// taking more and is rethrown to the caller once all have returned.
#include <mechgraph/worker_threads.hpp>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>

namespace mechgraph {

/// Runs body(state, chunk) for chunk = 0 .. chunks - 1 (each once, in no set order) on up to
/// `threads` workers (at least one; never more than there are chunks), each worker's `state` made
/// by make_state() before its first chunk.
template <class MakeState, class Body>
void run_chunks(std::size_t chunks, unsigned threads, const MakeState& make_state, const Body& body) {
  std::atomic<std::size_t> next{0};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  const unsigned workers = static_cast<unsigned>(std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(chunks, 1)));
  run_on_workers(workers, [&](unsigned) {
    try {
      auto state = make_state();
      for (std::size_t chunk; (chunk = next.fetch_add(1)) < chunks;) body(state, chunk);
    } catch (...) {
      std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = chunks;
    }
  });
  if (failure) std::rethrow_exception(failure);
}

}  // namespace mechgraph
