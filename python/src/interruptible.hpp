#pragma once
// Ctrl-C for work done in C++: the work runs on its own thread with the GIL released while the
// calling (Python) thread waits in slices of 20 ms and asks Python for pending signals between
// them. On Ctrl-C, `on_interrupt` runs (a sweep sets its stop flag: no new case starts) and the
// KeyboardInterrupt is raised: after the work has ended (`wait`), or at once, the work left to end
// on its own thread (`detach`: it must own everything it touches; a single evaluation cannot be cut
// short, the session it holds is busy until it ends).
#include <functional>

namespace mechgraph::python {

enum class OnInterrupt { wait, detach };

/// Runs `work`; rethrows its exception; throws pybind11::error_already_set on a signal whose
/// Python handler raised. Call with the GIL held. `on_tick` (if any) runs with the GIL after each
/// slice while the work goes on (a progress bar), and once more when the work has ended without an
/// error; what it throws while the work goes on is handled as Ctrl-C is.
void run_interruptibly(std::function<void()> work, const std::function<void()>& on_interrupt, OnInterrupt mode,
                       const std::function<void()>& on_tick = {});

}  // namespace mechgraph::python
