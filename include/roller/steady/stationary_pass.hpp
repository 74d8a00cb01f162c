#pragma once
// One steady pass of the roller solved in its own frame (docs/model.md, "Stationary pass"):
// the displacement u (from the upstream configuration) for which the states swept along the
// streamlines carry the load. Each iteration is a correction, with the elastic stiffness
//   r(u) = f(sigma_upstream) - f(sigma(u)),   K_e du = r + f_c  (f_c: the load, with du)
// or with the steady Jacobian near the solution, and the fixed point
// u = u + du accelerated by Anderson's mixing of the last 40 corrections of one operator;
// converged when |r + f_c| <= tolerance |f_c|. The upstream term makes an unloaded strip keep its
// upstream state (r = 0 at u = 0).
#include <atomic>
#include <functional>
#include <iosfwd>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/assembly/stationary_strip.hpp"
#include "roller/solver/sparse_solver.hpp"
#include "roller/solver/termination.hpp"

namespace roller {

// The load's side of one iteration: from the iterate u (all dofs), its states and r (free dofs),
// the correction du (free dofs) and the load f_c (all dofs) it carries: a prescribed load
// (du = K_e^-1 (r + f_ext)), or the roller's contact solved with K_e.
class StationaryCorrection {
 public:
  virtual ~StationaryCorrection() = default;
  struct Result {
    VecX du;                    // free dofs
    VecX load;                  // all dofs
    std::string message;        // why there is none (du empty)
    bool new_operator = false;  // du comes from another operator than the last: Anderson starts again
  };
  virtual Result correct(const VecX& u, const std::vector<MaterialState>& states, const VecX& r) = 0;
  // The load when it does not depend on the iterate (all dofs), so that another operator's step
  // needs no call of correct; none otherwise.
  virtual const VecX* fixed_load() const { return nullptr; }
  // From now on the operator is `tangent` (the steady Jacobian: square, its first unknowns the free
  // dofs), or K_e again when null. A correction that finds its load with the operator (the
  // roller's contact, condensed with it) factorises it and returns true: its corrections are then
  // the tangent's steps. False: the load is found with K_e, and the caller steps with the tangent.
  virtual bool take_operator(const SparseMatrix* /*tangent*/, const LinearSolverOptions& /*options*/) { return false; }
};

// K_e^-1 (r + f_ext) with K_e factorised (over the free dofs) and a fixed load f_ext.
class PrescribedLoadCorrection : public StationaryCorrection {
 public:
  PrescribedLoadCorrection(const DofMap& dofs, SparseSolver& elastic, VecX external)
      : elastic_(elastic), external_(std::move(external)), external_free_(dofs.gather_free(external_)) {}
  Result correct(const VecX&, const std::vector<MaterialState>&, const VecX& r) override {
    return {elastic_.solve(r + external_free_), external_, {}};
  }
  const VecX* fixed_load() const override { return &external_; }

 private:
  SparseSolver& elastic_;
  VecX external_, external_free_;
};

// When the steady Jacobian takes over from K_e and when it is factorised again (measured on
// shakedown_p45 at 1.8e4 and 4.8e4 dofs: docs/benchmarks-log.md, "The steady Jacobian").
struct SteadyJacobianSettings {
  // From |r + f_ext| <= from |f_ext| on; further out Newton's steps from the Jacobian of a strip far
  // from its steady state overshoot (from the elastic field, the residual grows tenfold a step).
  // At 0.1 they still diverge at times on a perfectly plastic strip, and the retries below catch
  // it; 3e-2 was slower by a tenth at 4.8e4 dofs, 0.3 slower still (docs/benchmarks-log.md).
  Real from = 0.1;
  // J is factorised again at the iterate when the last step left more than this share of the
  // residual; otherwise the last J stays, and Anderson's mixing accelerates the chord iteration
  // (under the roller's contact 0.5 factorised J at most steps of pass 1: 39 times).
  Real contraction = 0.9;
  Real tolerance = 1e-8;  // the pass's: a converged iterate needs no new J
  // J's steps diverge when the residual grows to this multiple of the least they reached. The
  // iterate goes back to that least one, and K_e's correction, slower but safe, carries on from
  // there: until its residual is `retry` times that least one, where J takes over again (at most
  // `retries` times a pass), then for the rest of the pass.
  Real divergence = 10.0;
  Real retry = 0.3;
  int retries = 2;
  // MUMPS's options for J (the scene's [linear_solver]: out_of_core keeps its factors on disk).
  // Its "auto" ordering becomes AMD: J's pattern follows the yielding points, so most
  // factorisations analyse it anew, and AMD's analysis costs a third of METIS's there, its
  // factorisation half as much again (docs/benchmarks-log.md).
  LinearSolverOptions linear_solver;
};

// Why the steady Jacobian no longer corrects in a pass.
enum class JacobianDropped { No, Diverged, Singular };

// Newton's correction with the steady Jacobian (assembly/steady_jacobian.hpp) around another
// correction with K_e, which finds the load f_c (prescribed, or the roller's contact): K_e's
// while the iterate is far from the steady state, then the displacement's part of
// J^-1 [r + f_c; 0] with K_e's load (docs/model.md, "The steady Jacobian"). Should J be singular
// or its steps diverge, K_e's carries on alone for the rest of the pass.
class SteadyJacobianCorrection : public StationaryCorrection {
 public:
  SteadyJacobianCorrection(const StationaryStrip& strip, const DofMap& dofs, const SparseMatrix& elastic_free,
                           StationaryCorrection& elastic, std::vector<MaterialState> upstream,
                           const SteadyJacobianSettings& settings);
  Result correct(const VecX& u, const std::vector<MaterialState>& states, const VecX& r) override;
  int factorizations() const { return factorizations_; }  // of J
  JacobianDropped dropped() const {
    return stage_ == Stage::Diverged   ? JacobianDropped::Diverged
           : stage_ == Stage::Singular ? JacobianDropped::Singular
                                       : JacobianDropped::No;
  }
  int retried() const { return retried_; }

 private:
  const StationaryStrip& strip_;
  const DofMap& dofs_;
  const SparseMatrix& elastic_free_;
  StationaryCorrection& elastic_;
  std::vector<MaterialState> upstream_;
  SteadyJacobianSettings settings_;
  SparseSolver jacobian_{MumpsSolver::Symmetry::General};
  // Which correction the steps take: K_e's until the hand-over (and again after a divergence with
  // retries left), then J's; after a last divergence, or a singular J, K_e's for the rest of the pass.
  enum class Stage { Elastic, Jacobian, Diverged, Singular };
  Stage stage_ = Stage::Elastic;
  Index n_unknowns_ = 0;                                        // of the factorised J
  Real last_residual_ = 0.0;                                    // |r + f_c| / |f_c| at the last step with J
  Real best_residual_ = std::numeric_limits<Real>::infinity();  // the least since J took over
  VecX best_u_;                                                 // its iterate (all dofs)
  Real from_ = 0.0;  // the hand-over's residual: settings_.from, lowered after each divergence
  int retried_ = 0;  // divergences after which J took over again
  int factorizations_ = 0;
  bool load_on_jacobian_ = false;  // the load's correction steps with J itself (take_operator)
  // Back to K_e's correction: the load's correction too.
  void leave_jacobian(Stage next);
};

struct StationarySettings {
  Real tolerance = 1e-8;             // on |r + f_c|_inf / |f_c|_inf
  int max_iterations = 3000;         // then limit_reached
  int stagnation_window = 500;       // limit_reached when |r|/F has not halved in this many iterations
  std::ostream* progress = nullptr;  // a line every `report_every` iterations
  int report_every = 100;
  // Checked every iteration: when it holds a signal's number the solve ends as interrupted.
  const std::atomic<int>* stop = nullptr;
};

struct StationaryPassResult {
  Termination status = Termination::Failed;
  int iterations = 0;
  Real residual = 0.0;                // |r|_inf / F_ref at the end
  VecX displacement;                  // all dofs
  VecX load;                          // f_c of the last correction: the load the pass carries (all dofs)
  std::vector<MaterialState> states;  // at every point
  Index n_yielded = 0;                // points that yield on their way
  std::string message;
  bool converged() const { return status == Termination::Converged; }
};

// The state each streamline leaves the pass with (one per streamline), from the iterate u (all
// dofs), its states and the load it carried: the strip beyond the mesh's downstream end holds the
// mesh with it, as a long track's does.
using LeavingStates = std::function<std::vector<MaterialState>(const VecX& u, const std::vector<MaterialState>& states,
                                                               const VecX& load)>;

// `upstream`: one state per streamline. Constrained dofs stay at zero. Without `leaving` the strip
// beyond the downstream end holds the upstream states; with it, the leaving states of the last
// iterate (the load: the last correction's). `start`: the first iterate (all dofs), or empty: zero.
StationaryPassResult solve_stationary_pass(const StationaryStrip& strip, const DofMap& dofs,
                                           StationaryCorrection& correction, const std::vector<MaterialState>& upstream,
                                           const StationarySettings& settings, const LeavingStates& leaving = {},
                                           const VecX& start = VecX());

}  // namespace roller
