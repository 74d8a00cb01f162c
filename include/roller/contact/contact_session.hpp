#pragma once
// The one door to a contact solve (docs/architecture.md): one increment of a strip against the
// roller, with the roller coupled as asked (docs/model.md, Roller couplings): placed (its motion
// prescribed), on its suspension (the deflection converged with the contact) or under prescribed
// forces (the centre's offset that carries them). It takes typed values only (the strip's
// increment energy, the roller's motion and forces, the friction history, the backend) and knows
// no scene and no run; it is pure in the caller's state: the caller commits what it returns. The
// transient step and shakedown-limit's elastic press solve their contact through it; a strip of
// constant tangent condensed under the roller has the contact floor's other door
// (condensed_contact.hpp).
#include <memory>
#include <vector>

#include "roller/assembly/increment_energy.hpp"
#include "roller/contact/backend.hpp"
#include "roller/contact/contact_options.hpp"
#include "roller/contact/elastic_roller.hpp"
#include "roller/contact/increment_types.hpp"

namespace roller {

// What a session needs besides the increment (io/contact_settings.hpp makes it of a scene).
struct ContactSessionSettings {
  bool roller = true;  // false: the strip alone, one solve without contact candidates
  // The strip's surface, which the roller touches: the penalty's scale.
  Real surface_youngs_modulus = 0.0;
  Real surface_poisson_ratio = 0.0;
  // E* of the line contact, about its stiffness per unit length: force control's first slope.
  Real contact_modulus = 0.0;
  // The roller's height solved with the strip where the backend can (contact.roller_coupling).
  RollerCoupling roller_coupling = RollerCoupling::Joint;
  // The body's largest dimension [mm]: offsets and deflections beyond 1e3 of it carry nothing.
  Real body_size = 0.0;
  // The largest force the roller's path prescribes per axis (|fx|, fy) [N per mm]: the scale of
  // force control's tolerances.
  Vec2 largest_force = Vec2::Zero();
  // An elastic roller's rim, condensed (contact/elastic_roller.hpp); null: the roller is rigid.
  std::shared_ptr<const RimStiffness> rim;
};

class ContactSession {
 public:
  // `backend` solves the increments (backend_factory.hpp: the strip's own without a roller);
  // `candidate_nodes` (empty without a roller) may touch the roller. The backend outlives the session.
  ContactSession(ContactSessionSettings settings, ContactBackend& backend, std::vector<Index> candidate_nodes);

  // Solves the increment of `energy` from `predictor` (all dofs): the solution when report.converged.
  // `start.motion` ends where the couplings put the roller.
  IncrementSolution solve(IncrementEnergy& energy, const VecX& prescribed, const VecX& predictor, IncrementStart& start,
                          IncrementReport& report);

  const std::vector<Index>& candidate_nodes() const { return candidate_nodes_; }

 private:
  // The strip without a roller: one solve of a problem without contact candidates.
  IncrementSolution solve_strip(IncrementEnergy& energy, const VecX& predictor, const IncrementStart& start,
                                IncrementReport& report);
  ContactSessionSettings settings_;
  ContactBackend& backend_;
  std::vector<Index> candidate_nodes_;
};

}  // namespace roller
