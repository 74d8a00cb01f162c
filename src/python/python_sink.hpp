#pragma once
// The in-memory outputs of a run started from Python, which also answer Python between steps:
// after each step's solver row the progress callback is called with that row, and Ctrl-C (a
// pending KeyboardInterrupt) or an exception of the callback stops the run after that step, as
// SIGINT stops `roller run`. The run itself holds no GIL; these calls take it.
#include <atomic>
#include <csignal>

#include <pybind11/pybind11.h>

#include "roller/driver/output_sink.hpp"

namespace roller::python {

class PythonSink : public MemoryOutputs {
 public:
  PythonSink(pybind11::object progress, int total_steps) : progress_(std::move(progress)), total_steps_(total_steps) {}
  void add_row(OutputTable table, const Row& row) override;

  // Set (to SIGINT) when the run is to stop after the step under way: RunOptions::stop_signal.
  const std::atomic<int>& stop() const { return stop_; }
  // The Python exception that stopped the run (KeyboardInterrupt or the callback's), if any:
  // raised again once the run has returned.
  pybind11::error_already_set* pending_error() { return error_ ? &*error_ : nullptr; }

 private:
  pybind11::object progress_;
  int total_steps_;
  std::atomic<int> stop_{0};
  std::optional<pybind11::error_already_set> error_;
};

// A row as a dict of its columns' values.
pybind11::dict row_dict(const Row& row);

}  // namespace roller::python
