#pragma once
// Contact backends: solve one IncrementProblem. The non-virtual
// solve() validates, times and checks the result (no NaN leaves a backend); the private
// do_solve() is backend specific. Backends report failure; the driver decides to cut the step.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roller/contact/backend_details.hpp"
#include "roller/contact/contact_options.hpp"
#include "roller/contact/increment_problem.hpp"
#include "roller/solver/inertia.hpp"
#include "roller/solver/newton.hpp"
#include "roller/solver/solve_counters.hpp"
#include "roller/solver/termination.hpp"

namespace roller {

enum class ContactStatus { Open, Stick, Slip };

const char* to_string(ContactStatus s);

// Result per contact candidate (same order as IncrementProblem::candidates()).
struct NodeContact {
  Real normal_force = 0.0;      // F_N >= 0 on the strip node [N per mm width]
  Real tangential_force = 0.0;  // F_T along the candidate's tangent [N per mm width]
  Real gap = 0.0;               // g at the solution [mm] (negative = penetration)
  Real slip = 0.0;              // tangential slip increment against the roller surface [mm]
  ContactStatus status = ContactStatus::Open;
};

struct BackendResult {
  Termination status = Termination::Failed;
  std::string message;
  VecX x;                             // free-dof increment
  std::optional<Real> roller_offset;  // a suspended roller's offset w at the solution (IncrementProblem::free_roller)
  VecX rim;                           // an elastic roller's rim displacements at the solution (empty: rigid)
  std::vector<NodeContact> contact;
  SolveCounters counters;      // Newton or interior-point iterations (all passes), factorisations
  Real residual = 0.0;         // relative equilibrium residual at the solution
  Real max_penetration = 0.0;  // max(0, -min gap) [mm]
  double wall_s = 0.0;
  BackendDetails details;  // the backend's own measurements (backend_details.hpp)
  bool converged() const { return status == Termination::Converged; }
  std::string brief_report() const;
  // A Newton solve's outcome, work and last iterate `x` (no contact: the caller adds it).
  static BackendResult of(const NewtonReport& newton, VecX x);
};

class ContactBackend {
 public:
  virtual ~ContactBackend() = default;
  BackendResult solve(IncrementProblem& problem, const VecX& x0);
  virtual std::string name() const = 0;
  // Whether solve() finds a suspended roller's position with the strip (IncrementProblem::free_roller);
  // a backend that does not is given problems whose roller is placed.
  virtual bool solves_roller_height() const { return false; }
  // Whether the backend minimises the increment energy (and so needs a potential: a law with
  // Armstrong-Frederick recovery is then solved with the recovery frozen and iterated), or
  // solves the equilibrium equations with the exact, unsymmetric tangent.
  virtual bool minimises_energy() const { return true; }
  // The inertia of the strip tangent `k` when this backend still holds a factorisation of exactly
  // that matrix (a constant tangent kept over increments), nullopt otherwise: the run-time
  // monitor's check of the same matrix without a factorisation of its own.
  std::optional<Inertia> held_tangent_inertia(const SparseMatrix& k) { return do_held_tangent_inertia(k); }

 private:
  virtual BackendResult do_solve(IncrementProblem& problem, const VecX& x0) = 0;
  BackendResult solve_settling_recovery(IncrementProblem& problem, const VecX& x0);
  // The frozen recovery is settled when the back-stresses are within this fraction of sigma_y0 of
  // the exact update's. 1e-6 by default: Ipopt's own accuracy leaves them noisy a little below
  // that (Z1: 1.7e-11 against 3e-9).
  virtual Real recovery_tolerance() const { return 1e-6; }
  virtual std::optional<Inertia> do_held_tangent_inertia(const SparseMatrix& /*k*/) { return std::nullopt; }
};

}  // namespace roller
