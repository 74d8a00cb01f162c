#pragma once
// The strip's material by depth (docs/model.md, Layered strips and hardness profiles): bands
// ([[layer]]) from the top surface, each a full MaterialParams, over the [material] below them,
// and an optional depth profile of the initial yield stress. Depth is measured from the strip's
// top surface in the initial mesh.
#include <string>
#include <utility>
#include <vector>

#include "roller/material/material_params.hpp"

namespace roller {

// Initial yield stress against depth: points (depth [mm], sigma_y [MPa]) with strictly
// increasing depths, linear in between, constant beyond the first and the last point.
struct YieldProfile {
  std::vector<std::pair<Real, Real>> points;

  bool empty() const { return points.empty(); }
  Real at(Real depth) const;
  // True when the points are admissible; otherwise false and *why names the first bad point
  // ("yield_profile[2]: ...").
  bool is_valid(std::string* why) const;
};

// One band from the top: its thickness and its material (a copy of [material] with the layer's
// own keys over it). `follows_profile`: the yield profile sets its initial yield stress (the
// layer gave no yield_stress of its own).
struct MaterialLayer {
  Real thickness = 1.0;  // [mm], > 0
  MaterialParams material;
  bool follows_profile = true;
};

// What an element at a given depth is made of.
struct MaterialAtDepth {
  MaterialParams material;
  int layer = 0;  // index of the [[layer]] block, layers.size() for the [material] below them
};

struct LayeredMaterial {
  MaterialParams base;  // [material]: below the layers, and where there are none
  std::vector<MaterialLayer> layers;
  YieldProfile yield_profile;  // applies to `base` and to the layers that follow it

  // A homogeneous strip of `m`.
  static LayeredMaterial uniform(const MaterialParams& m) { return LayeredMaterial{m, {}, {}}; }

  MaterialAtDepth at_depth(Real depth) const;
  // Depths of the boundaries between consecutive bands (the layers' bottoms), from the top.
  std::vector<Real> boundaries() const;
  // The material of the top surface (the first layer, else [material]) with the profile's
  // surface value: what the contact sees.
  MaterialParams surface() const { return at_depth(0.0).material; }
  bool any_plastic() const;
  // The largest Poisson's ratio of any band (the strip's worst conditioning).
  Real max_poisson_ratio() const;
  bool is_homogeneous() const { return layers.empty() && yield_profile.empty(); }
};

}  // namespace roller
