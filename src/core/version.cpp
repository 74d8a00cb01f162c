#include "roller/core/version.hpp"

#include <dmumps_c.h>

#include "build_info.hpp"

namespace roller {

BuildInfo build_info() { return {ROLLER_VERSION, ROLLER_GIT_COMMIT, ROLLER_IPOPT_VERSION, MUMPS_VERSION}; }

}  // namespace roller
