#pragma once
// What `roller --version` prints: roller's version and commit, and the versions of the solver
// libraries it was built against (the numbers a bug report needs).
#include <string>

namespace roller {

struct BuildInfo {
  std::string version;        // roller (CMake project version)
  std::string commit;         // git describe of the source tree at build time ("unknown" outside git)
  std::string ipopt_version;  // from pkg-config at configure time
  std::string mumps_version;  // MUMPS_VERSION of dmumps_c.h
};

BuildInfo build_info();

}  // namespace roller
