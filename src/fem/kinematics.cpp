#include "roller/fem/kinematics.hpp"

namespace roller {

std::string to_string(Kinematics k) { return k == Kinematics::Small ? "small" : "finite"; }
std::string to_string(Q4Formulation f) { return f == Q4Formulation::BBar ? "bbar" : "standard"; }

}  // namespace roller
