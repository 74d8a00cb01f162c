#pragma once
// The time-dependent state of a run: the strip's Houbolt history and mass (when it has inertia)
// and the roller's suspension (when it hangs on one). Two levels of history: the step-level
// histories advance once per scene step; the working ones follow the increments and are
// resampled when a step is cut into sub-increments (houbolt.hpp, docs/model.md, Houbolt).
//   begin_increment -> (solve) -> commit_increment ... -> finish_step
// A quasistatic run without suspension has an empty DynamicsState that does nothing.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "roller/assembly/increment_energy.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/dynamics/houbolt.hpp"
#include "roller/dynamics/suspension.hpp"

namespace roller {

class DynamicsState {
 public:
  DynamicsState() = default;
  // The strip (with inertia: mass matrix built once, rho0 dV0 is constant) and the suspension
  // start at rest in the model's current configuration (a restarted strip included).
  DynamicsState(const StripModel& model, bool strip_inertia, bool lumped_mass,
                const std::optional<SuspensionSpec>& suspension, Real dt);

  bool strip_inertia() const { return strip_inertia_; }

  // Start of an increment of length h [s]: the working histories resampled to h, and the strip's
  // inertia term for the increment energy (none for a quasistatic strip).
  std::optional<InertiaTerm> begin_increment(Real h);
  // The working suspension of the increment (nullptr without one).
  Suspension* suspension() { return suspension_ ? &*suspension_ : nullptr; }
  const Suspension* suspension() const { return suspension_ ? &*suspension_ : nullptr; }
  // A converged increment: the working histories advance to the new displacement and deflection.
  void commit_increment(const VecX& total_displacement, Real deflection);
  // End of a scene step: velocities and accelerations by Houbolt's formulas on the step-level
  // histories, which then advance by one step; the working histories return to them.
  void finish_step(const VecX& total_displacement);

  // At the end of the last step: nodal velocity and acceleration of all dofs (empty when
  // quasistatic), kinetic energy 1/2 v.M v [N mm per mm], the suspension's deflection rates.
  const VecX& velocity() const { return velocity_; }
  const VecX& acceleration() const { return acceleration_; }
  Real kinetic_energy() const;
  Real suspension_velocity() const { return suspension_velocity_; }
  Real suspension_acceleration() const { return suspension_acceleration_; }
  // M over the free dofs (free numbering), for the effective tangent K + 2M/dt^2.
  const SparseMatrix& mass_free() const { return mass_free_; }

  // State files: the step-level histories and rates into `j`, and back. load() throws
  // InputError naming `file` when the saved dynamics (strip inertia, suspension) differ.
  void save(nlohmann::json& j) const;
  void load(const nlohmann::json& j, const std::string& file);

 private:
  bool strip_inertia_ = false;
  SparseMatrix mass_, mass_free_;
  HouboltHistory strip_step_history_, strip_history_;
  std::optional<Suspension> suspension_step_, suspension_;
  VecX velocity_, acceleration_;
  Real suspension_velocity_ = 0.0, suspension_acceleration_ = 0.0;
};

}  // namespace roller
