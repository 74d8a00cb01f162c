#pragma once
// Options of the contact model and of the two backends (scene tables [contact],
// [contact.penalty], [contact.ipopt]; docs/scenes.md).
#include <string>
#include <vector>

#include "roller/core/types.hpp"
#include "roller/solver/newton_options.hpp"

namespace roller {

struct PenaltyOptions {
  Real factor = 1e3;             // kappa_N = factor * E* * l_i / h_i  (per candidate)
  Real tangential_factor = 1.0;  // kappa_T = tangential_factor * kappa_N
  bool is_valid(std::string* why) const;
};

// An Ipopt option passed through unchanged ([contact.ipopt.options]): kind says which of
// Ipopt's setters takes it.
struct RawIpoptOption {
  enum class Kind { String, Integer, Number };
  std::string name;
  Kind kind = Kind::String;
  std::string text;  // the value as written (numbers: full precision)
};

struct IpoptOptions {
  // "condensed": per linearisation of the strip, one MUMPS factorisation of K_eff condensed onto
  // the contact dofs, Ipopt on the small dense NLP (contact/ipopt_condensed.cpp; the default).
  // "full": Ipopt on the whole strip's nonlinear energy, every free dof an NLP variable.
  std::string formulation = "condensed";
  Real tol = 1e-9;               // Ipopt's tol on the scaled NLP
  int max_iter = 500;
  std::string mu_strategy = "adaptive";  // "adaptive" | "monotone"
  int print_level = 0;
  bool warm_start = false;
  std::string friction = "split";        // "split" (v_T = s+ - s-, exact) | "regularized"
  Real regularization = 1e-8;            // epsilon of sqrt(v_T^2 + eps^2) [mm], "regularized" only
  std::string fixed_point = "converge";  // "converge" (Coulomb) | "single" (thesis's explicit variant)
  Real fixed_point_tol = 1e-6;           // relative change of F_N that ends the fixed point (changes
                                         // below a pass's multiplier resolution end it too)
  int fixed_point_max = 30;
  std::vector<RawIpoptOption> raw;       // applied after roller's own settings (override them)
  bool is_valid(std::string* why) const;
};

struct ContactOptions {
  std::string backend = "ipopt";  // "ipopt" (the main method) | "penalty"
  Real friction = 0.0;              // Coulomb mu
  std::string candidates = "contact";  // node set of contact candidates
  std::string predictor = "extrapolate";  // start of each increment: "extrapolate" (the previous
                                          // increment scaled) | "arc" (then the thesis's arc rule (4.25))
  PenaltyOptions penalty;
  IpoptOptions ipopt;
  bool is_valid(std::string* why) const;
};

}  // namespace roller
