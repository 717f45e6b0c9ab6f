#include "interruptible.hpp"

#include <pybind11/pybind11.h>

#include <chrono>
#include <future>
#include <memory>
#include <thread>

namespace mechgraph::python {

void run_interruptibly(std::function<void()> work, const std::function<void()>& on_interrupt, OnInterrupt mode) {
  namespace py = pybind11;
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> finished = done->get_future();
  std::thread worker([work = std::move(work), done]() {
    try {
      work();
      done->set_value();
    } catch (...) {
      done->set_exception(std::current_exception());
    }
  });
  for (;;) {
    std::future_status status;
    {
      py::gil_scoped_release released;
      status = finished.wait_for(std::chrono::milliseconds(20));
    }
    if (status == std::future_status::ready) break;
    if (PyErr_CheckSignals() != 0) {
      on_interrupt();
      if (mode == OnInterrupt::detach) {
        worker.detach();
      } else {
        py::gil_scoped_release released;
        worker.join();
      }
      throw py::error_already_set();
    }
  }
  worker.join();
  finished.get();
}

}  // namespace mechgraph::python
