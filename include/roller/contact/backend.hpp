#pragma once
// Contact backends: solve one IncrementProblem. The non-virtual
// solve() validates, times and checks the result (no NaN leaves a backend); the private
// do_solve() is backend specific. Backends report failure; the driver decides to cut the step.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roller/contact/contact_options.hpp"
#include "roller/contact/increment_problem.hpp"
#include "roller/solver/inertia.hpp"
#include "roller/solver/newton.hpp"

namespace roller {

enum class ContactStatus { Open, Stick, Slip };

// How a contact solve ended; the driver cuts the step on anything but Converged.
enum class ContactTermination {
  Converged,
  LimitReached,  // an iteration, pass or stage budget ran out, or the method stalled: a smaller
                 // step (or a larger budget) may succeed
  Failed,        // no usable solution: the strip could not be evaluated, NaN, a solver error
};
const char* to_string(ContactStatus s);

// Result per contact candidate (same order as IncrementProblem::candidates()).
struct NodeContact {
  Real normal_force = 0.0;      // F_N >= 0 on the strip node [N per mm width]
  Real tangential_force = 0.0;  // F_T along the candidate's tangent [N per mm width]
  Real gap = 0.0;               // g at the solution [mm] (negative = penetration)
  Real slip = 0.0;              // tangential slip increment against the roller surface [mm]
  ContactStatus status = ContactStatus::Open;
};

// What a backend measured in one increment: named fields, not a string map (the idea of Drake's
// SolverDetails). A backend leaves the fields it does not measure at zero.
struct BackendStats {
  Real complementarity = 0.0;       // ipopt: max |F_N g| / F_ref
  Real constraint_violation = 0.0;  // ipopt: max penetration of the constrained candidates [mm]
  int fixed_point_iterations = 0;   // ipopt: friction passes (condensed: on the last linearisation)
  int nlp_solves = 0;               // ipopt: NLP solves of the increment (cold restarts included)
  int cold_restarts = 0;            // ipopt: warm-started NLPs that failed and were solved again cold
  int nlp_variables = 0;            // ipopt: size of the last NLP
  int nlp_constraints = 0;
  int linearisations = 0;           // ipopt, condensed formulation: linearisations of the strip
  int condensed_dofs = 0;           // ipopt, condensed formulation: contact dofs of the last one
  double ipopt_time_s = 0.0;        // ipopt: time inside Ipopt
  bool acceptable_level = false;    // ipopt: Ipopt stopped at its acceptable level
  bool condensed_fallback = false;  // ipopt: the full formulation solved what the condensed could not
  int active_set_passes = 0;        // penalty: passes of the frozen-status Newton
  int penalty_stages = 0;           // penalty: stages of the raised penalty
  std::string brief() const;        // the non-zero fields, for messages
  // The stats of several solves of one increment or step (a suspended or force-controlled roller
  // solves the contact several times, a cut step several sub-increments), `later` solved last: the
  // work (NLP solves, linearisations, time, restarts, passes, stages) summed, the rest `later`'s.
  void add(const BackendStats& later);
};

struct BackendResult {
  ContactTermination status = ContactTermination::Failed;
  std::string message;
  VecX x;                             // free-dof increment
  std::optional<Real> roller_offset;  // a suspended roller's offset w at the solution (IncrementProblem::free_roller)
  std::vector<NodeContact> contact;
  int iterations = 0;  // Newton or interior-point iterations (all passes)
  int factorizations = 0;
  Real residual = 0.0;         // relative equilibrium residual at the solution
  Real max_penetration = 0.0;  // max(0, -min gap) [mm]
  double wall_s = 0.0;
  BackendStats stats;
  bool converged() const { return status == ContactTermination::Converged; }
  std::string brief_report() const;
};

class ContactBackend {
 public:
  virtual ~ContactBackend() = default;
  BackendResult solve(IncrementProblem& problem, const VecX& x0);
  virtual std::string name() const = 0;
  // Whether solve() finds a suspended roller's position with the strip (IncrementProblem::free_roller);
  // a backend that does not is given problems whose roller is placed.
  virtual bool solves_roller_height() const { return false; }
  // The inertia of the strip tangent `k` when this backend still holds a factorisation of exactly
  // that matrix (a constant tangent kept over increments), nullopt otherwise: the run-time
  // monitor's check of the same matrix without a factorisation of its own.
  std::optional<Inertia> held_tangent_inertia(const SparseMatrix& k) { return do_held_tangent_inertia(k); }

 private:
  virtual BackendResult do_solve(IncrementProblem& problem, const VecX& x0) = 0;
  virtual std::optional<Inertia> do_held_tangent_inertia(const SparseMatrix& /*k*/) { return std::nullopt; }
};

}  // namespace roller
