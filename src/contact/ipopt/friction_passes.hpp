#pragma once
// Coulomb friction in the interior-point backend: a fixed point on the normal force around NLP
// solves with a given friction bound (Tresca passes), one loop for both formulations
// (docs/model.md, "Friction"). Pass 1 takes Fbar from the candidates' normal_force_guess, pass
// k+1 from pass k's F_N; FixedPointRule::Converge repeats until max|F_N - Fbar| <=
// max(fixed_point_tol * max F_N, F_tol), F_tol the resolution of a pass's multipliers (changes
// below it are the inner solves' noise, not the fixed point's: on Z1 refine 2, warm-started
// passes of 1-2 iterations moved an F_N of 1454 N by ~1e-2 N back and forth and the passes ran
// out); FixedPointRule::Single stops after one pass (the thesis's explicit variant).
#include <string>
#include <vector>

#include <IpIpoptApplication.hpp>

#include "contact_tnlp.hpp"
#include "roller/contact/backend.hpp"
#include "roller/solver/newton_options.hpp"

namespace roller::ipopt_detail {

// Fbar per candidate, updated from each pass's F_N: plain substitution while the change at least
// halves per pass; once it does not, relaxed, Fbar += w (F_N - Fbar), with Aitken's dynamic
// weight w (docs/model.md, Friction fixed point). The map can be expansive at the contact edge:
// in rolling, a node carrying 1e-3 of the peak force answered an increase of Fbar by a three
// times larger decrease of F_N, so plain substitution and any fixed w >= 1/2 cycled until the
// passes ran out; Aitken's secant estimate of the slope finds w ~ 1/4 there.
class NormalForceFixedPoint {
 public:
  NormalForceFixedPoint(const IncrementProblem& problem, const IpoptOptions& o, Real force_scale);
  const std::vector<Real>& fbar() const { return fbar_; }
  // F_tol: the resolution of a pass's multipliers, 1e-6 max(F_ref, max Fbar).
  Real force_tol() const;
  // Takes a pass's normal forces (per candidate); true when the fixed point has converged (or is
  // not iterated: mu = 0 or FixedPointRule::Single).
  bool update(const std::vector<Real>& normal);
  bool iterated() const { return mu_ > 0.0 && o_.fixed_point == FixedPointRule::Converge; }
  // Restart the halving test (a new linearisation of the strip starts a new sequence).
  void restart() {
    previous_change_ = 1e300;
    relaxation_ = 1.0;
    relaxed_ = false;
  }
  // The message of a fixed point that ran out of passes.
  std::string failure_message(int passes) const;

 private:
  const IpoptOptions& o_;
  Real mu_;
  Real force_scale_;
  std::vector<Real> fbar_;
  Real last_change_ = 0.0, last_max_ = 0.0;
  Real previous_change_ = 1e300, relaxation_ = 1.0;
  bool relaxed_ = false;                 // the change stopped halving: Aitken's weight from now on
  std::vector<Real> previous_residual_;  // F_N - Fbar of the previous pass
};

// What the passes of one fixed point produced.
struct FrictionPasses {
  Termination status = Termination::Converged;  // not Converged: a pass's NLP failed (message)
  std::string message;
  int passes = 0;         // passes run, the failed one included
  int nlp_solves = 0;     // NLPs solved: the passes and their cold restarts
  int cold_restarts = 0;  // warm-started passes that failed and were solved again from a cold start
  int iterations = 0;     // interior-point iterations of all passes
  double ipopt_time_s = 0.0;
  bool acceptable_level = false;
  bool fixed_point_converged = false;
  int nlp_variables = 0, nlp_constraints = 0;  // of the last pass
  NlpSolution last;                            // of the last pass that Ipopt finalised
  FrictionTerms friction;                      // of the last solved pass
  // Of the last solved pass, per candidate (0 / false for candidates without a row):
  std::vector<Real> normal, tangential, fbar;
  std::vector<bool> has_friction;
};

// Runs up to max_passes NLP solves of objective + contact rows (rows fixed over the passes, the
// friction terms from the fixed point's Fbar), each pass warm-started from the previous one (pass
// 1 only with warm_first). Stops at the first failed NLP.
FrictionPasses solve_friction_passes(Ipopt::IpoptApplication& app, NlpObjective& objective,
                                     const IncrementProblem& problem, const std::vector<RowMap>& rows,
                                     NormalForceFixedPoint& fixed_point, NlpStart start, int max_passes,
                                     bool warm_first, const IpoptOptions& o);

}  // namespace roller::ipopt_detail
