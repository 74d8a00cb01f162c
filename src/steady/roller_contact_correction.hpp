#pragma once
// The stationary pass's correction on the roller's exact contact (passes.stationary_contact =
// "roller", the default), the contact condensed under the roller with the strip's elastic
// stiffness, and with the steady Jacobian once it takes over (contact/condensed_contact.hpp).
#include <memory>

#include "roller/steady/stationary_passes.hpp"

namespace roller {

// Where the rollers stand: over x = centre_x on the strip, and with phases k/P of an element
// further along copy k, which moved back as far (shift, assembly/phased_strip.hpp).
struct RollerPlaces {
  Real centre_x = 0.0;
  int phases = 1;
  Real shift = 0.0;
};

// The correction of the scene's strip (its mesh `mesh`) and its copies, each roller under `force`.
std::unique_ptr<RollerCorrection> make_roller_contact_correction(const Scene& scene, const Mesh& mesh,
                                                                 const SteadyLoad& steady, const RollerPlaces& places,
                                                                 Real force);

}  // namespace roller
