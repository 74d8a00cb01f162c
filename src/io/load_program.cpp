#include "roller/io/load_program.hpp"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "roller/core/error.hpp"
#include "roller/io/scene_loader.hpp"

namespace roller {

LoadProgram::LoadProgram(const Scene& scene, const Mesh& mesh) : n_dofs_(mesh.n_dofs()) {
  std::map<Index, std::pair<Ramp, std::string>> seen;
  auto add_prescribed = [&](Index dof, const Ramp& r, const std::string& context) {
    auto it = seen.find(dof);
    if (it != seen.end()) {
      const Ramp& o = it->second.first;
      if (o != r)
        throw InputError(fmt::format("{}: node {} {} is already prescribed differently by {}", context, dof / 2 + 1,
                                     dof % 2 ? "y" : "x", it->second.second));
      return;
    }
    seen.emplace(dof, std::make_pair(r, context));
    prescribed_.push_back({dof, r});
  };
  for (std::size_t i = 0; i < scene.displacements.size(); ++i) {
    const auto& bc = scene.displacements[i];
    const std::string ctx = fmt::format("displacement[{}]", i);
    for (Index node : resolve_nodes(bc.nodes, mesh, ctx + ".nodes")) {
      if (bc.x) add_prescribed(2 * node, *bc.x, ctx + ".x");
      if (bc.y) add_prescribed(2 * node + 1, *bc.y, ctx + ".y");
    }
  }
  if (mesh.period > 0.0) {
    masters_ = node_masters(mesh);
    for (Index d = 0; d < n_dofs_; ++d) {
      const Index m = 2 * masters_[d / 2] + d % 2;
      if (m == d) continue;
      const auto mine = seen.find(d), master = seen.find(m);
      if (mine != seen.end() && (master == seen.end() || master->second.first != mine->second.first))
        throw InputError(fmt::format(
            "{}: node {} lies on the right edge of a periodic strip ([mesh] periodic = true), where it is node {} of "
            "the left edge; prescribe {} there{}",
            mine->second.second, d / 2 + 1, m / 2 + 1, d % 2 ? "y" : "x",
            master == seen.end() ? "" : fmt::format(" (it is prescribed differently by {})", master->second.second)));
      if (master != seen.end() && mine == seen.end()) add_prescribed(d, master->second.first, master->second.second);
    }
  }
  for (std::size_t i = 0; i < scene.loads.size(); ++i) {
    const auto& load = scene.loads[i];
    for (Index node : resolve_nodes(load.nodes, mesh, fmt::format("load[{}].nodes", i))) {
      if (load.fx) forces_.push_back({2 * node, *load.fx});
      if (load.fy) forces_.push_back({2 * node + 1, *load.fy});
    }
  }
}

DofMap LoadProgram::dof_map() const {
  std::vector<bool> constrained(n_dofs_, false);
  for (const auto& e : prescribed_) constrained[e.dof] = true;
  return masters_.empty() ? DofMap(constrained) : DofMap(constrained, masters_);
}

Real LoadProgram::ramp_value(const Ramp& r, Real s) {
  // Linear interpolation between the step-end values, which Ramp defines for integer steps.
  const int lo = static_cast<int>(std::floor(s));
  const Real frac = s - lo;
  const Real v_lo = lo <= 0 ? 0.0 : r.at_step(lo);
  return frac == 0.0 ? v_lo : v_lo + frac * (r.at_step(lo + 1) - v_lo);
}

VecX LoadProgram::prescribed_displacement(Real s) const {
  VecX u = VecX::Zero(n_dofs_);
  for (const auto& e : prescribed_) u(e.dof) = ramp_value(e.ramp, s);
  return u;
}

VecX LoadProgram::external_force(Real s) const {
  VecX f = VecX::Zero(n_dofs_);
  for (const auto& e : forces_) f(e.dof) += ramp_value(e.ramp, s);
  return f;
}

}  // namespace roller
