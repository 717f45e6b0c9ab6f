#include <mechgraph/sweep/sweep_runner.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/block_plan.hpp>
#include <mechgraph/text_escape.hpp>
#include <mechgraph/worker_threads.hpp>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <span>
#include <thread>

#include <spdlog/spdlog.h>

namespace mechgraph {

SweepSummary run_sweep(const Graph& base, const CaseBinder& binder, const CaseTable& table, MemoCache& cache,
                       const SweepOptions& options, const std::function<void(CaseResult&&)>& emit) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = options.cases.size();
  const unsigned threads = static_cast<unsigned>(std::clamp<std::size_t>(options.threads, 1, std::max<std::size_t>(n, 1)));
  // Fewer cases than threads: the rest go to independent nodes inside each case.
  const unsigned node_threads = std::max(1u, options.threads / threads);
  // Blocks of cases when every node on the path offers them (sweep/block_plan.hpp); a case the
  // block path cannot do is redone alone below, so the rows do not depend on it.
  std::optional<BlockPlan> plan;
  if (options.block_size > 1 && n > 1) {
    plan.emplace(base, binder);
    if (!plan->usable()) {
      spdlog::debug("sweep: every case alone ({})", plan->why_not());
      plan.reset();
    }
  }
  const std::size_t chunk = plan ? options.block_size : 1;
  // Blocks in flight: two per thread at least, whatever window was asked for.
  std::size_t window = options.window ? options.window : 64 * static_cast<std::size_t>(threads);
  if (plan) window = std::max(window, 2 * chunk * static_cast<std::size_t>(threads));
  std::atomic<std::size_t> in_blocks{0};

  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::condition_variable emitted_more;
  std::vector<std::optional<CaseResult>> ring(window);
  std::size_t next_to_emit = 0;
  std::exception_ptr emit_failure;
  std::atomic<bool> abort{false};
  SweepSummary summary;

  auto stopping = [&] { return abort.load() || (options.stop && options.stop->load()); };

  // A failed case's message is text for people, shown in its row (on stdout, in a DataFrame): one
  // line with nothing a terminal acts on, whatever a plugin or a scene put in it.
  auto worker = [&] {
    Graph graph = base;
    binder.mark_unmemoised(graph);
    std::optional<CaseBinder::Slots> slots;  // the varied parameters of this worker's graph
    if (!binder.rebuilds()) slots = binder.bind(graph);
    BlockPlan::WorkerState block_state;
    std::vector<CaseValue> row;  // a case's values, where the table keeps numbers only
    // One case alone: the per-case path, with its messages.
    auto run_alone = [&](CaseResult& result) {
      try {
        if (slots) binder.apply(*slots, graph, table.row(result.index, row));
        else binder.apply(graph, table.row(result.index, row));
        if (binder.rebuilds()) binder.mark_unmemoised(graph);
        RunValues run = evaluate_values(graph, cache, node_threads);
        result.outputs = std::move(run.values);
        result.evaluated = run.evaluated;
        result.reused = run.reused;
      } catch (const SceneError& e) {
        result.failure = CaseFailure::scene;
        result.error = terminal_text(e.what(), TerminalLines::one);
        if (binder.rebuilds()) graph = base;
      } catch (const std::exception& e) {
        result.failure = CaseFailure::evaluation;
        result.error = terminal_text(e.what(), TerminalLines::one);
      }
    };
    while (!stopping()) {
      const std::size_t first = next.fetch_add(chunk);
      if (first >= n) break;
      const std::size_t end = std::min(n, first + chunk);
      {
        std::unique_lock lock(mutex);
        emitted_more.wait(lock, [&] { return end - 1 < next_to_emit + window; });
      }
      std::vector<CaseResult> results(end - first);
      std::vector<BlockPlan::CaseOutcome> outcomes;
      if (plan) {
        // Whatever stops a block (no memory for its columns) leaves its cases to the per-case path.
        try {
          outcomes = plan->run(graph, table, std::span<const std::size_t>(options.cases).subspan(first, end - first), block_state);
        } catch (...) {
          outcomes.assign(end - first, {});
        }
      }
      for (std::size_t k = first; k < end; ++k) {
        CaseResult& result = results[k - first];
        result.index = options.cases[k];
        if (plan && outcomes[k - first].outputs) {
          result.outputs = std::move(*outcomes[k - first].outputs);
          in_blocks.fetch_add(1, std::memory_order_relaxed);
        } else {
          run_alone(result);
        }
      }
      std::unique_lock lock(mutex);
      for (std::size_t k = first; k < end; ++k) ring[k % window] = std::move(results[k - first]);
      // Whoever completes the oldest case hands every finished one in order to `emit`.
      while (ring[next_to_emit % window]) {
        CaseResult ready = std::move(*ring[next_to_emit % window]);
        ring[next_to_emit % window].reset();
        ++next_to_emit;
        if (ready.failure != CaseFailure::none) ++summary.failed;
        ++summary.run;
        if (!emit_failure) {
          try {
            emit(std::move(ready));
          } catch (...) {
            emit_failure = std::current_exception();
            abort = true;
          }
        }
      }
      emitted_more.notify_all();
    }
  };

  // The calling thread works too; a thread that cannot start (a process or memory limit) leaves its
  // cases to the others. Whatever escapes a case's own handling (no memory for a worker's graph)
  // stops the sweep and is rethrown here, never std::terminate.
  run_on_workers(threads, [&](unsigned) {
    try {
      worker();
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!emit_failure) emit_failure = std::current_exception();
      abort = true;
      emitted_more.notify_all();
    }
  });
  if (emit_failure) std::rethrow_exception(emit_failure);
  summary.stopped = summary.run < n;
  summary.in_blocks = in_blocks.load();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace mechgraph
