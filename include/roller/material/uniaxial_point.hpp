#pragma once
// A material point in uniaxial stress (S_yy = S_zz = S_xy = 0), driven by an axial strain
// increment or to an axial stress: Newton on the free strain components with the consistent
// tangent, so that each converged step is the return mapping's answer to round-off. What a
// calibrated law is checked on (its uniaxial loops: docs/validation.md, Hardening laws; rollerpy
// material-loops).
#include <vector>

#include "roller/material/j2_plasticity.hpp"

namespace roller {

struct UniaxialStep {
  MaterialUpdate update;
  Vec4 strain_increment = Vec4::Zero();  // [xx, yy, zz, 2xy] that gives it
};

// One increment of axial strain; the lateral (yy, zz) increments make S_yy = S_zz = 0. Throws
// NumericalError when the lateral Newton does not converge.
UniaxialStep uniaxial_strain_step(const MaterialParams& p, Real d_axial, const MaterialState& state);

// One increment to the axial stress `target`, Newton on (xx, yy, zz) from an elastic guess.
UniaxialStep uniaxial_stress_step(const MaterialParams& p, Real target, const MaterialState& state);

// A point of a uniaxial path: axial strain and stress, the axial plastic strain (strain - stress/E)
// and the equivalent plastic strain.
struct UniaxialSample {
  Real strain = 0.0;
  Real stress = 0.0;
  Real plastic_strain = 0.0;
  Real eq_plastic_strain = 0.0;
};

// Strain control from the virgin state through the axial strains `turning_points`, each branch in
// `steps_per_branch` equal increments; the samples start at zero and end at every step.
std::vector<UniaxialSample> uniaxial_strain_path(const MaterialParams& p, const std::vector<Real>& turning_points,
                                                 int steps_per_branch);

// Stress control from the virgin state through the axial stresses `turning_points`.
std::vector<UniaxialSample> uniaxial_stress_path(const MaterialParams& p, const std::vector<Real>& turning_points,
                                                 int steps_per_branch);

}  // namespace roller
