#pragma once
// The stationary pass's correction on the roller's exact contact (passes.stationary_contact =
// "roller"), solved by an elastic twin of the strip that is a Simulation of its own: kept apart
// from stationary_passes.hpp, which the Simulation holds.
#include <memory>

#include "stationary_passes.hpp"

namespace roller {

// A RollerCorrectionMaker (stationary_passes.hpp).
std::unique_ptr<RollerCorrection> make_roller_contact_correction(const Scene& scene, Real centre_x, Real force);

}  // namespace roller
