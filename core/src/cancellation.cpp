#include <mechgraph/cancellation.hpp>

#include <atomic>

namespace mechgraph {
namespace {
std::atomic<bool> cancelled{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");
}  // namespace

void request_cancellation() noexcept { cancelled.store(true, std::memory_order_relaxed); }
void clear_cancellation() noexcept { cancelled.store(false, std::memory_order_relaxed); }
bool cancellation_requested() noexcept { return cancelled.load(std::memory_order_relaxed); }

}  // namespace mechgraph
