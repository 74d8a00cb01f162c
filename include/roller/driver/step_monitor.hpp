#pragma once
// The run-time monotonicity monitor (docs/model.md, Run-time monitor): after each step, operator
// A at the integration points and the definiteness of the assembled effective tangent (contact
// terms excluded) at the new state, with warnings a user can act on. Switched off
// (output.monitor = false) it checks nothing and its solver.csv columns read -1.
//
// Cost. The assembled check is one assembly and one LDL^T factorisation (MUMPS) of K_eff per
// step. Where the tangent cannot change from step to step (a linear elastic strip with small
// kinematics: K and the pointwise operator do not depend on the state), the first step's verdict
// holds for every later step with the same free dofs and is reused, not recomputed; and the
// first step's inertia comes from the contact backend when it still holds the factors of that
// very matrix (ContactBackend::held_tangent_inertia), so the monitor factorises nothing.
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roller/analysis/monotonicity.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/contact/backend.hpp"
#include "roller/solver/mumps_factorization.hpp"

namespace roller {

struct MonitorReport {
  bool checked = false;
  bool reused = false;              // the verdict of an earlier step with the same constant tangent
  bool from_contact_solve = false;  // the inertia of the contact backend's factors of the same K
  StripMonotonicity pointwise;      // operator A at the integration points
  SparseDefiniteness assembled;     // the effective tangent K (+ 2M/dt^2 with strip inertia)
  Vec2 worst_place = Vec2::Zero();  // centroid of the element with the worst point [mm]
  // The warnings this check gave (each kind once a run): summary.json lists them.
  std::vector<std::string> warnings;
  bool pointwise_loss_first = false;  // warnings holds the run's one warning of operator A's pointwise loss
};

class StepMonitor {
 public:
  // `mass_free` is the strip's mass over the free dofs (nullptr: quasistatic strip); `backend`
  // the run's contact backend, asked for the inertia of factors it holds (nullptr: none);
  // `progress` receives the warnings (nullptr: silent); `stationary`: the steps are stationary
  // passes, which solve the steady Jacobian, not the tangent checked here (the advice differs).
  StepMonitor(bool enabled, Real dt, const SparseMatrix* mass_free, ContactBackend* backend, std::ostream* progress,
              bool stationary = false)
      : enabled_(enabled),
        dt_(dt),
        mass_free_(mass_free),
        backend_(backend),
        progress_(progress),
        stationary_(stationary) {}

  // `pointwise_loss_reported`: the run (its steps before, a resumed run's included) gave the
  // warning of operator A's pointwise loss already, which is given once a run (RunState holds it).
  MonitorReport check(int step, StripModel& model, bool pointwise_loss_reported = false);

 private:
  bool enabled_;
  Real dt_;
  const SparseMatrix* mass_free_;
  ContactBackend* backend_;
  std::ostream* progress_;
  bool stationary_;
  // The LDL^T of the assembled check: one MUMPS instance for the run, so that its analysis is
  // reused while the pattern stays, with the factors discarded as they are computed (only the
  // inertia is wanted: no factor memory beside the contact solve's).
  std::unique_ptr<MumpsSolver> ldlt_;
  // The verdict of a state-independent tangent and the free dofs it was computed on.
  std::optional<MonitorReport> constant_report_;
  std::vector<Index> constant_free_dofs_;
};

}  // namespace roller
