#include "roller/analysis/pressure_profile.hpp"

namespace roller {

std::vector<PressureSample> pressure_profile(const std::vector<NodeContactRecord>& contact, const RollerPose& pose) {
  std::vector<PressureSample> out;
  for (const auto& c : contact) {
    const bool loaded = c.contact.status != ContactStatus::Open;
    out.push_back({c.position.x() - pose.centre.x(), loaded ? c.contact.normal_force / c.tributary_length : 0.0});
  }
  return out;
}

}  // namespace roller
