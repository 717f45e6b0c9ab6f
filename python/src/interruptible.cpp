#include "interruptible.hpp"

#include <pybind11/pybind11.h>

#include <chrono>
#include <future>
#include <memory>
#include <system_error>
#include <thread>

namespace mechgraph::python {

void run_interruptibly(std::function<void()> work, const std::function<void()>& on_interrupt, OnInterrupt mode,
                       const std::function<void()>& on_tick) {
  namespace py = pybind11;
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
  for (;;) {
    std::future_status status;
    {
      py::gil_scoped_release released;
      status = finished.wait_for(std::chrono::milliseconds(20));
    }
    if (status == std::future_status::ready) break;
    const auto stop_work = [&] {
      on_interrupt();
      if (mode == OnInterrupt::detach) {
        worker.detach();
      } else {
        py::gil_scoped_release released;
        worker.join();
      }
    };
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
