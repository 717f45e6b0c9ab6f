#include "interruptible.hpp"

#include <pybind11/pybind11.h>

#include <csignal>

#include <chrono>
#include <future>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

namespace mechgraph::python {
namespace {

// While work runs, SIGINT does what Python's own C handler does: it marks SIGINT for
// PyErr_CheckSignals (async-signal-safe, from whichever thread the signal lands on). A library may
// have put a handler of its own in Python's place: OpenTURNS' Python module throws a C++ exception
// from its handler, on any thread, which ends the process in std::terminate. The handler found is
// put back when the last work running ends; a default or ignored SIGINT is left as it is.
class PythonSigint {
 public:
  PythonSigint() {
    std::lock_guard lock(mutex());
    if (users()++ > 0) return;
    struct sigaction found {};
    const bool read = ::sigaction(SIGINT, nullptr, &found) == 0;
    const bool plain = (found.sa_flags & SA_SIGINFO) == 0;
    if (!read || (plain && (found.sa_handler == SIG_DFL || found.sa_handler == SIG_IGN))) {
      installed() = false;
      return;
    }
    struct sigaction mark {};
    mark.sa_handler = &PythonSigint::mark;
    sigemptyset(&mark.sa_mask);
    installed() = ::sigaction(SIGINT, &mark, &previous()) == 0;
  }
  ~PythonSigint() {
    std::lock_guard lock(mutex());
    if (--users() > 0 || !installed()) return;
    ::sigaction(SIGINT, &previous(), nullptr);
    installed() = false;
  }
  PythonSigint(const PythonSigint&) = delete;
  PythonSigint& operator=(const PythonSigint&) = delete;

 private:
  static void mark(int) { PyErr_SetInterruptEx(SIGINT); }
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static int& users() {
    static int n = 0;
    return n;
  }
  static bool& installed() {
    static bool b = false;
    return b;
  }
  static struct sigaction& previous() {
    static struct sigaction a {};
    return a;
  }
};

}  // namespace

void run_interruptibly(std::function<void()> work, const std::function<void()>& on_interrupt, OnInterrupt mode,
                       const std::function<void()>& on_tick) {
  namespace py = pybind11;
  const PythonSigint sigint;  // before the worker starts; after it is joined or detached, put back
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> finished = done->get_future();
  auto body = [work, done]() {
    try {
      work();
      done->set_value();
    } catch (...) {
      done->set_exception(std::current_exception());
    }
  };
  std::thread worker;
  try {
    worker = std::thread(body);
  } catch (const std::system_error&) {
    // No thread to be had (a process or memory limit): the work runs here, without the GIL, and
    // Ctrl-C is seen when it returns. Slower to interrupt, never an abort.
    {
      py::gil_scoped_release released;
      body();
    }
    finished.get();
    if (on_tick) on_tick();
    return;
  }
  const auto stop_work = [&] {
    on_interrupt();
    if (mode == OnInterrupt::detach) {
      worker.detach();
    } else {
      py::gil_scoped_release released;
      worker.join();
    }
  };
  for (;;) {
    std::future_status status = std::future_status::timeout;
    bool thrown_at_signal = false;
    {
      py::gil_scoped_release released;
      try {
        status = finished.wait_for(std::chrono::milliseconds(20));
      } catch (...) {
        // The wait throws nothing itself: this came from a signal handler. OpenTURNS' Python module
        // installs one for SIGINT that throws a C++ exception where Python's sets a flag. Taken as
        // the Ctrl-C it stands for: the work is stopped (a thread left running and joinable here
        // would end the process in std::terminate) and KeyboardInterrupt raised.
        thrown_at_signal = true;
      }
    }
    if (thrown_at_signal) {
      stop_work();
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
    if (status == std::future_status::ready) break;
    if (PyErr_CheckSignals() != 0) {
      stop_work();
      throw py::error_already_set();
    }
    if (on_tick) {
      try {
        on_tick();
      } catch (...) {
        stop_work();  // the work may hold references to the caller's frame: it ends before this does
        throw;
      }
    }
  }
  worker.join();
  finished.get();
  if (on_tick) on_tick();  // the final count: a sweep shorter than one slice reports too
}

}  // namespace mechgraph::python
