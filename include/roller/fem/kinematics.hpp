#pragma once
// Element formulation choices (docs/model.md, Kinematics).
#include <string>

#include "roller/core/enum_names.hpp"

namespace roller {

// "small": linear strain, no geometric stiffness, the mesh is never updated (thesis INFINI).
// "finite": updated Lagrangian, Green-Lagrange strain of the increment, geometric stiffness,
// objective push-forward of the stress (thesis LARGE).
enum class Kinematics { Small, Finite };

// Q4 volumetric treatment. "bbar": the volumetric part of the strain is replaced by its
// element average (Hughes' B-bar, applied to the Green-Lagrange increment so that it stays
// exactly objective); locking-free for isochoric plastic flow. "standard": full 2x2
// integration, locks for nearly incompressible response. T3 has a constant strain and no option.
enum class Q4Formulation { Standard, BBar };

template <>
struct EnumNames<Kinematics> {
  static constexpr std::array<std::pair<Kinematics, const char*>, 2> names{
      {{Kinematics::Finite, "finite"}, {Kinematics::Small, "small"}}};
};
template <>
struct EnumNames<Q4Formulation> {
  static constexpr std::array<std::pair<Q4Formulation, const char*>, 2> names{
      {{Q4Formulation::BBar, "bbar"}, {Q4Formulation::Standard, "standard"}}};
};

struct ElementOptions {
  Kinematics kinematics = Kinematics::Finite;
  Q4Formulation q4 = Q4Formulation::BBar;
};

std::string to_string(Kinematics k);
std::string to_string(Q4Formulation f);

}  // namespace roller
