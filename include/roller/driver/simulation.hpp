#pragma once
// The step loop (DESIGN: setup; for each step: predict, solve, cut back if needed, commit,
// write). Results of completed steps are on disk before the next step starts, so a failure or
// a kill loses nothing already done.
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>

#include "roller/assembly/strip_model.hpp"
#include "roller/driver/load_program.hpp"
#include "roller/io/scene.hpp"

namespace roller {

struct RunOptions {
  std::filesystem::path out_dir = "out";
  std::ostream* progress = nullptr;  // one line per step; nullptr = silent
};

struct RunSummary {
  bool converged = false;
  int steps_done = 0;
  int iterations_total = 0;
  int cuts_total = 0;
  double wall_s = 0.0;
  std::string message;
};

class Simulation {
 public:
  // Builds the mesh and the load program, validating the scene against the mesh (InputError).
  explicit Simulation(Scene scene);

  RunSummary run(const RunOptions& options);

  const Scene& scene() const { return scene_; }
  StripModel& model() { return *model_; }
  const StripModel& model() const { return *model_; }

 private:
  struct Increment;
  Increment solve_increment(Real s_from, Real s_to);

  Scene scene_;
  std::unique_ptr<StripModel> model_;
  LoadProgram loads_;
  VecX last_increment_;     // last converged increment (all dofs), for the predictor
  Real last_length_ = 0.0;  // its length in steps
};

}  // namespace roller
