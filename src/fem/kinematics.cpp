#include "roller/fem/kinematics.hpp"

namespace roller {

std::string to_string(Kinematics k) { return enum_name(k); }
std::string to_string(Q4Formulation f) { return enum_name(f); }

}  // namespace roller
