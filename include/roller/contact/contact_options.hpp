#pragma once
// Options of the contact model and of the two backends (scene tables [contact],
// [contact.penalty], [contact.ipopt]; docs/scenes.md).
#include <string>
#include <vector>

#include "roller/core/enum_names.hpp"
#include "roller/core/types.hpp"
#include "roller/solver/newton_options.hpp"

namespace roller {

enum class ContactBackendKind { Ipopt, Penalty };
// Condensed: per linearisation of the strip, one MUMPS factorisation of K_eff condensed onto the
// contact dofs, Ipopt on the small dense NLP (contact/ipopt/ipopt_condensed.cpp; the default).
// Full: Ipopt on the whole strip's nonlinear energy, every free dof an NLP variable.
enum class IpoptFormulation { Condensed, Full };
enum class MuStrategy { Adaptive, Monotone };  // Ipopt's barrier update
// Split: v_T = s+ - s-, exact; Regularized: sqrt(v_T^2 + eps^2).
enum class IpoptFriction { Split, Regularized };
// Converge: Coulomb (the normal-force fixed point iterated); Single: one pass with the previous
// increment's F_N (the thesis's explicit variant).
enum class FixedPointRule { Converge, Single };
// Ipopt's linear solver for the KKT systems of its interior-point iterations. Dense: LAPACK's
// Bunch-Kaufman LDL^T (contact/dense_kkt_solver.hpp), no fixed cost per call, O(n^3); Mumps: the
// sparse multifrontal solver, about 0.1 ms a call whatever the size; Auto: dense for small NLPs
// (contact/ipopt/ipopt_common.cpp, kDenseKktMax).
enum class KktSolver { Auto, Dense, Mumps };
// Start of each increment: the previous increment scaled, or then the thesis's arc rule (4.25)
// (docs/model.md, Arc predictor), or the previous increment carried along with the roller
// (contact/rolling_predictor.hpp).
enum class IncrementPredictor { Extrapolate, Arc, Rolling };
// The height of a roller that is not prescribed (hanging on its suspension, or carrying a
// prescribed vertical force) in each increment: Joint: an unknown of the contact solve itself
// (backends that support it: ipopt, condensed), Passes: found by the driver's coupling loop, one
// contact solve per pass with the roller placed (dynamics/suspension.hpp, contact/force_control.hpp;
// every backend).
enum class RollerCoupling { Joint, Passes };

template <>
struct EnumNames<ContactBackendKind> {
  static constexpr std::array<std::pair<ContactBackendKind, const char*>, 2> names{
      {{ContactBackendKind::Ipopt, "ipopt"}, {ContactBackendKind::Penalty, "penalty"}}};
};
template <>
struct EnumNames<IpoptFormulation> {
  static constexpr std::array<std::pair<IpoptFormulation, const char*>, 2> names{
      {{IpoptFormulation::Condensed, "condensed"}, {IpoptFormulation::Full, "full"}}};
};
template <>
struct EnumNames<MuStrategy> {
  static constexpr std::array<std::pair<MuStrategy, const char*>, 2> names{
      {{MuStrategy::Adaptive, "adaptive"}, {MuStrategy::Monotone, "monotone"}}};
};
template <>
struct EnumNames<IpoptFriction> {
  static constexpr std::array<std::pair<IpoptFriction, const char*>, 2> names{
      {{IpoptFriction::Split, "split"}, {IpoptFriction::Regularized, "regularized"}}};
};
template <>
struct EnumNames<KktSolver> {
  static constexpr std::array<std::pair<KktSolver, const char*>, 3> names{
      {{KktSolver::Auto, "auto"}, {KktSolver::Dense, "dense"}, {KktSolver::Mumps, "mumps"}}};
};
template <>
struct EnumNames<FixedPointRule> {
  static constexpr std::array<std::pair<FixedPointRule, const char*>, 2> names{
      {{FixedPointRule::Converge, "converge"}, {FixedPointRule::Single, "single"}}};
};
template <>
struct EnumNames<RollerCoupling> {
  static constexpr std::array<std::pair<RollerCoupling, const char*>, 2> names{
      {{RollerCoupling::Joint, "joint"}, {RollerCoupling::Passes, "passes"}}};
};
template <>
struct EnumNames<IncrementPredictor> {
  static constexpr std::array<std::pair<IncrementPredictor, const char*>, 3> names{
      {{IncrementPredictor::Extrapolate, "extrapolate"},
       {IncrementPredictor::Arc, "arc"},
       {IncrementPredictor::Rolling, "rolling"}}};
};

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
  IpoptFormulation formulation = IpoptFormulation::Condensed;
  Real tol = 1e-9;  // Ipopt's tol on the scaled NLP
  int max_iter = 500;
  MuStrategy mu_strategy = MuStrategy::Adaptive;
  int print_level = 0;
  // Warm-start the first Ipopt pass of each linearisation from the last forces (the increment's
  // first from the previous increment's); later friction passes always do.
  // A warm-started pass that fails is repeated cold (src/contact/ipopt/friction_passes.cpp).
  bool warm_start = true;
  IpoptFriction friction = IpoptFriction::Split;
  Real regularization = 1e-8;  // epsilon of sqrt(v_T^2 + eps^2) [mm], "regularized" only
  FixedPointRule fixed_point = FixedPointRule::Converge;
  Real fixed_point_tol = 1e-6;  // relative change of F_N that ends the fixed point (changes
                                // below a pass's multiplier resolution end it too)
  int fixed_point_max = 30;
  KktSolver kkt_solver = KktSolver::Auto;
  std::vector<RawIpoptOption> raw;  // applied after roller's own settings (override them)
  bool is_valid(std::string* why) const;
};

struct ContactOptions {
  ContactBackendKind backend = ContactBackendKind::Ipopt;  // ipopt: the main method
  Real friction = 0.0;                                     // Coulomb mu
  std::string candidates = "contact";                      // node set of contact candidates
  IncrementPredictor predictor = IncrementPredictor::Extrapolate;
  RollerCoupling roller_coupling = RollerCoupling::Joint;
  PenaltyOptions penalty;
  IpoptOptions ipopt;
  bool is_valid(std::string* why) const;
};

}  // namespace roller
