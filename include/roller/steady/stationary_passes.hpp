#pragma once
// The stationary method's passes for the step loop (docs/model.md, Stationary pass): one step is
// one pass, solved as the steady state in the roller's frame under the Hertz pressure of the
// travel segment's force (and q = mu p when it slides). Built once a run: the streamlines, the
// elastic stiffness factorised once for every pass, the load, and the load's elastic field, which
// unloads the state leaving a pass (the roller lifted). Near each pass's solution the steady
// Jacobian corrects instead (SteadyJacobianCorrection), factorised once or twice a pass. With
// passes.stationary_phases = P the pass is solved on P copies of the strip at once, the roller
// k/P of an element further along copy k (assembly/phased_strip.hpp); what it leaves, the
// residual strip and the contact, is the first copy's.
//
// The strip between passes is the residual strip: every point holds the residual state of its
// streamline as it leaves the pass, a long track's (material/long_track_state.hpp), read at the
// extraction column (downstream, half-way between the contact and the strip's end, with the
// roller's elastic field subtracted); the strip beyond the mesh's downstream end holds it with
// that state while the pass is solved. The displacement is the sum of the passes' long-track
// displacements (uniform along x: the plastic shear and the yy strain integrated from the base). So the next pass's
// upstream state, the pass metrics (measure_pass) and the state files are the transient method's.
#include <iosfwd>
#include <memory>
#include <optional>
#include <vector>

#include "roller/analysis/fatigue.hpp"
#include "roller/analysis/hertz.hpp"
#include "roller/assembly/phased_strip.hpp"
#include "roller/assembly/stationary_strip.hpp"
#include "roller/assembly/strip_model.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/io/scene.hpp"
#include "roller/material/long_track_state.hpp"
#include "roller/steady/stationary_pass.hpp"
#include "roller/steady/steady_load.hpp"

namespace roller {

// The correction on the roller's exact contact (passes.stationary_contact = "roller"): it
// corrects the iterate with the roller's contact and keeps that contact and the roller's pose.
class RollerCorrection : public StationaryCorrection {
 public:
  virtual const std::vector<NodeContactRecord>& contact() const = 0;
  virtual RollerPose pose() const = 0;
  // The roller's creep (1 - omega R / V): the travel's, or the one that carries its horizontal force.
  virtual Real creep() const = 0;
  // The next pass starts afresh, as a new correction would: no contact, zones or roller height
  // carried over from the pass before (no state file holds them), the factorisations kept.
  virtual void restart() = 0;
};
class StationaryPasses {
 public:
  // Throws InputError when the scene's travel segment prescribes no force (fy) or its mesh has no
  // straight rows of points. `steady`: the scene's travel and its load (steady_load.hpp).
  StationaryPasses(const Scene& scene, const StripModel& model, const SteadyLoad& steady);
  ~StationaryPasses();

  struct Pass {
    StationaryPassResult solve;
    std::vector<MaterialState> residual;  // the residual strip's states (every point)
    VecX permanent_displacement;          // the long track's displacement of the pass (all dofs)
    int factorizations = 0;               // of the steady Jacobian
    VecX next_start;                      // the next pass's first iterate (all dofs), or empty: zero
  };
  // The pass from the residual strip `strip` (or the initial state before the first pass), its
  // iteration started from `start` (all dofs; empty: zero): the last pass's next_start. A
  // signal's number in `stop` ends the iteration as interrupted (checked every iteration).
  Pass run(const StripModel& strip, const VecX& start, std::ostream* progress, const std::atomic<int>* stop);

  // A pass's stress cycles by depth (its states): along each row of elements of the strip (the
  // first copy), the element means from upstream to downstream, the path every point of the row
  // takes through the steady pass. `strip_height`: the depth's origin.
  std::vector<DepthCycle> cycles(const std::vector<MaterialState>& states, Real strip_height) const;
  const HertzSolution& hertz() const { return hertz_; }
  Real centre_x() const { return centre_x_; }
  Real extraction_x() const { return extraction_x_; }
  // The load as contact records of the top nodes (contact.csv), and the roller's pose over it
  // (the last pass's, with the roller's contact).
  const std::vector<NodeContactRecord>& contact() const { return contact_; }
  // The last pass's roller creep on the roller's contact (absent with the Hertz load).
  std::optional<Real> creep() const { return creep_; }
  RollerPose roller_pose() const;

 private:
  std::vector<MaterialState> upstream_of(const StripModel& strip) const;
  // The elastic displacement of a load (all dofs), which the lift takes off; kept for the load
  // last asked for (the Hertz load's is solved once).
  const VecX& elastic_displacement(const DofMap& dofs, const VecX& load);
  // The long track's state each streamline leaves with, and its strain of the pass, from the
  // iterate (u, its states) and the elastic displacement of the load it carried.
  std::vector<LongTrackState> leaving(const VecX& u, const std::vector<MaterialState>& states,
                                      const VecX& elastic) const;

  Real roller_y_ = 0.0;  // the centre's height at the start (the pose written beside the load)
  HertzSolution hertz_;
  Real centre_x_ = 0.0, extraction_x_ = 0.0, travel_ = 1.0;
  PhasedStrip phased_;  // the strip's copies, one per phase (one copy: the strip itself)
  StationaryStrip strip_;
  ElementMaterials elastic_materials_;
  LinearSolverOptions linear_solver_;  // the scene's, for the steady Jacobian
  SparseSolver solver_{MumpsSolver::Symmetry::Symmetric};
  SparseMatrix elastic_free_;  // K_e over the free dofs, which solver_ holds factorised
  VecX hertz_load_;            // the Hertz pressure and its traction (all dofs)
  // The correction on the roller's contact (passes.stationary_contact = "roller"), restarted at
  // every pass; null with the Hertz load.
  std::unique_ptr<RollerCorrection> roller_correction_;
  std::optional<RollerPose> pose_;  // the roller's, with the roller's contact
  std::optional<Real> creep_;       // the roller's, with the roller's contact
  Index base_points_ = 0;           // the strip's points (the first copy's)
  std::vector<Index> extraction_;   // per streamline: its point at the extraction column (of the first copy)
  std::vector<NodeContactRecord> contact_;
  VecX elastic_load_, elastic_displacement_;  // elastic_displacement()'s last load, and its displacement
};

}  // namespace roller
