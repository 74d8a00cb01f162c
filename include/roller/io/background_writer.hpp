#pragma once
// Output files written beside the computation: a step's VTU file and state files go to a
// background thread while the next step is solved (Hertz at 2.9e5 dofs: 0.8 s of VTU and 0.5 s
// of checkpoint a step, 2 s of solving). The job gets everything it writes by value; it must not
// read the model, which the next step changes.
//
// Jobs run one after another in the order submitted, so a file written later (the checkpoint)
// is never on disk before the files submitted before it (the step's VTU) that it vouches for; a
// job whose predecessor failed does not run and carries that error on. At most kMaxInFlight jobs
// are queued: a submit waits for the oldest beyond that, so memory stays bounded when writing is
// slower than solving. A job's exception (a full disk) is rethrown by the submit or finish() that
// collects it, so the run stops with that message as it did when it wrote in its own thread.
// finish() before reading what the jobs wrote (state_final.cbor, the summary) and before the
// process ends.
#include <deque>
#include <functional>
#include <future>

namespace roller {

class BackgroundWriter {
 public:
  static constexpr int kMaxInFlight = 2;
  // in_background = false: every job runs inside submit() (the low-memory mode: a job holds a
  // copy of a step's fields and state, 0.8 kB per dof, while the next step factorises).
  explicit BackgroundWriter(bool in_background = true) : in_background_(in_background) {}
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;
  // Waits for the jobs still running; their errors are lost here (call finish() to see them).
  ~BackgroundWriter() { drain(); }
  // The same wait, for an owner of data the jobs use that goes away first (its destructor).
  void drain() noexcept;

  void submit(std::function<void()> job);
  // Waits for every job; rethrows the first error among them.
  void finish();

 private:
  bool in_background_;
  std::deque<std::shared_future<void>> running_;  // oldest first; each waits for the one before
};

}  // namespace roller
