#pragma once
// Pieces shared by the two formulations of the interior-point backend (ipopt_full.cpp,
// ipopt_condensed.cpp): Ipopt set-up, status messages, the increment's scales and the
// per-candidate report. Internal to src/contact (Ipopt stays out of the public headers).
#include <algorithm>
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
// Ipopt's warm start from a primal-dual point (warm_start_init_point and its push/frac options).
void set_warm_start(Ipopt::IpoptApplication& app, bool on);

// Scales of one increment (docs/model.md, "The interior-point backend's NLP in detail": Scaling).
struct Scales {
  Real force = 1.0;   // F_ref [N/mm]
  Real length = 1.0;  // l_step [mm]
};
Scales increment_scales(const IncrementProblem& problem, const VecX& x0, Real strip_force_scale);

// An Ipopt application with roller's settings (docs/model.md, the NLP in detail: Ipopt options) and the
// pass-through options applied; not yet initialised.
Ipopt::SmartPtr<Ipopt::IpoptApplication> make_application(const IpoptOptions& o, const Scales& scales);

// Ipopt's linear_solver for an NLP of n variables and m constraints (the "ma27" it is given is
// the dense solver of solver/dense_kkt_solver.hpp).
std::string kkt_linear_solver(KktSolver choice, int n, int m);

struct StatusText {
  Termination status;
  std::string message;
};
StatusText map_status(Ipopt::ApplicationReturnStatus s, int iterations, const IpoptOptions& o,
                      const std::string& evaluation_error);

// The status of a node at an interior-point solution, where the barrier leaves every force and
// gap slightly positive and a stick node's slip slightly non-zero (docs/model.md, "Stick, slip and
// open at an interior-point solution"). `length` is the increment's length scale (the largest
// motion of the roller or the strip), `bound` mu F_N of the last pass (0: no friction row).
// - open: apart and carrying at most `open_force` (open_force(): kOpenForceRatio of the largest
//   normal force, at least 1e-6 of the problem's force scale);
// - slip: it slips more than kSlipFraction of `length`, or more than kNoSlip of it with |F_T| on
//   the Coulomb bound to within kConeTolerance (without friction: more than kNoSlip of it);
// - stick: otherwise.
inline constexpr Real kOpenForceRatio = 1e-4;
inline constexpr Real kSlipFraction = 1e-3;
inline constexpr Real kNoSlip = 1e-6;
inline constexpr Real kConeTolerance = 1e-2;
inline Real open_force(Real fn_max, Real force_scale) { return std::max(kOpenForceRatio * fn_max, 1e-6 * force_scale); }
ContactStatus contact_status(const NodeContact& c, Real open_force, Real bound, Real length);

// Fills result->contact (forces, gaps, slips, open/stick/slip), residual (|grad Pi - contact
// forces| / F_ref at x), complementarity and constraint_violation from a solution x with forces
// F_N, F_T per candidate; `fbar` and `has_friction` are the last pass's friction set-up. Returns
// false (result->status = Failure, message set) when the strip cannot be evaluated at x.
bool report_increment(IncrementProblem& problem, const VecX& x, const std::vector<Real>& normal,
                      const std::vector<Real>& tangential, const std::vector<Real>& fbar,
                      const std::vector<bool>& has_friction, const Scales& scales, BackendResult* result);

}  // namespace roller::ipopt_detail
