#pragma once
// The stationary pass's correction on the roller's exact contact (passes.stationary_contact =
// "roller", the default), the contact condensed under the roller with the strip's elastic
// stiffness (contact/condensed_contact.hpp).
#include <memory>

#include "roller/steady/stationary_passes.hpp"

namespace roller {

// The correction of the scene's strip (its mesh `mesh`) with the roller over x = centre_x under `force`.
std::unique_ptr<RollerCorrection> make_roller_contact_correction(const Scene& scene, const Mesh& mesh,
                                                                 const SteadyLoad& steady, Real centre_x, Real force);

}  // namespace roller
