#pragma once
// The contact pressure of a solved contact against x from the roller's centre.
#include <vector>

#include "roller/analysis/hertz.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/roller.hpp"

namespace roller {

// Nodal contact pressures against x measured from the roller centre; open nodes count as unloaded
// (an interior-point solution leaves barrier-size forces there).
std::vector<PressureSample> pressure_profile(const std::vector<NodeContactRecord>& contact, const RollerPose& pose);

}  // namespace roller
