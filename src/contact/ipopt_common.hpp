#pragma once
// Pieces shared by the two formulations of the interior-point backend (ipopt_backend.cpp =
// "full", ipopt_condensed.cpp = "condensed"): Ipopt set-up, status messages, the increment's
// scales, the friction fixed point on the normal force and the per-candidate report. Internal to
// src/contact (Ipopt stays out of the public headers).
#include <string>
#include <vector>

#include <IpIpoptApplication.hpp>

#include "roller/contact/backend.hpp"

namespace roller::ipopt_detail {

using IIndex = Ipopt::Index;
using Ipopt::Number;

void set(Ipopt::IpoptApplication& app, const std::string& name, const std::string& value);
void set(Ipopt::IpoptApplication& app, const std::string& name, Real value);
void set(Ipopt::IpoptApplication& app, const std::string& name, int value);
// [contact.ipopt.options]: pass-through options, after ours so that they override them.
void apply_raw_options(Ipopt::IpoptApplication& app, const std::vector<RawIpoptOption>& raw);
// Ipopt's warm start from a primal-dual point (notes/ipopt-on-debian.md, item 9).
void set_warm_start(Ipopt::IpoptApplication& app, bool on);

// Scales of one increment (ipopt_backend.cpp, header comment "Scaling").
struct Scales {
  Real force = 1.0;   // F_ref [N/mm]
  Real length = 1.0;  // l_step [mm]
};
Scales increment_scales(IncrementProblem& problem, const VecX& x0);

// An Ipopt application with roller's settings (ipopt_backend.cpp, header comment "Ipopt
// options") and the pass-through options applied; not yet initialised.
Ipopt::SmartPtr<Ipopt::IpoptApplication> make_application(const IpoptOptions& o, const Scales& scales);

struct StatusText {
  NewtonStatus status;
  std::string message;
};
StatusText map_status(Ipopt::ApplicationReturnStatus s, int iterations, const IpoptOptions& o,
                      const std::string& evaluation_error);

// Coulomb's fixed point on the normal force (ipopt_backend.cpp, header comment "Coulomb"):
// Fbar per candidate, updated from each pass's F_N; plain substitution while the change at least
// halves per pass, averaged (Krasnoselskii-Mann, weight 1/2) once it does not (the map can cycle,
// e.g. with nodes at the contact edge switching between passes: Cattaneo at refine 5 repeated a
// 3-pass cycle until the passes ran out).
class NormalForceFixedPoint {
 public:
  NormalForceFixedPoint(const IncrementProblem& problem, const IpoptOptions& o, Real force_scale);
  const std::vector<Real>& fbar() const { return fbar_; }
  // F_tol: the resolution of a pass's multipliers, 1e-6 max(F_ref, max Fbar).
  Real force_tol() const;
  // Takes a pass's normal forces; true when the fixed point has converged (or is not iterated).
  bool update(const std::vector<Real>& normal);
  Real last_change() const { return last_change_; }
  Real last_max() const { return last_max_; }
  // Restart the halving test (a new linearisation of the strip starts a new sequence).
  void restart() { previous_change_ = 1e300; relaxation_ = 1.0; }

 private:
  const IpoptOptions& o_;
  Real mu_;
  Real force_scale_;
  std::vector<Real> fbar_;
  Real last_change_ = 0.0, last_max_ = 0.0;
  Real previous_change_ = 1e300, relaxation_ = 1.0;
  int pass_ = 0;
};

// The message of a fixed point that ran out of passes.
std::string fixed_point_message(int passes, const NormalForceFixedPoint& fixed_point, const IpoptOptions& o);

// Fills result->contact (forces, gaps, slips, open/stick/slip), residual (|grad Pi - contact
// forces| / F_ref at x), complementarity and constraint_violation from a solution x with forces
// F_N, F_T per candidate; `fbar` and `has_friction` are the last pass's friction set-up. Returns
// false (result->status = Failure, message set) when the strip cannot be evaluated at x.
bool report_increment(IncrementProblem& problem, const VecX& x, const std::vector<Real>& normal,
                      const std::vector<Real>& tangential, const std::vector<Real>& fbar,
                      const std::vector<bool>& has_friction, const Scales& scales, BackendResult* result);

}  // namespace roller::ipopt_detail
