#include "roller/assembly/strip_model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

StripModel::StripModel(Mesh mesh, MaterialParams material, ElementOptions options)
    : mesh_(std::move(mesh)),
      material_(material),
      options_(options),
      n_points_(n_integration_points(mesh_.element_type)),
      reference_(mesh_.nodes),
      total_displacement_(VecX::Zero(mesh_.n_dofs())) {
  std::string why;
  if (!material_.is_valid(&why)) throw InputError(why);
  committed_.assign(mesh_.n_elements() * n_points_, initial_state(material_));
  trial_ = committed_;
  geometry_ = geometry_for(reference_);
  set_dof_map(DofMap(std::vector<bool>(mesh_.n_dofs(), false)));
}

std::vector<std::vector<PointGeometry>> StripModel::geometry_for(const std::vector<Vec2>& coordinates) const {
  std::vector<std::vector<PointGeometry>> geometry(mesh_.n_elements());
  std::vector<Vec2> xe;
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    xe.clear();
    for (Index a : mesh_.elements[e]) xe.push_back(coordinates[a]);
    geometry[e] = element_geometry(mesh_.element_type, xe, e);
  }
  return geometry;
}

void StripModel::set_dof_map(DofMap dofs) {
  dofs_ = std::move(dofs);
  std::vector<Triplet> triplets;
  for (const auto& element : mesh_.elements)
    for (Index a : element)
      for (Index c : element)
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) {
            const Index r = dofs_.free_index(2 * a + i), k = dofs_.free_index(2 * c + j);
            if (r >= 0 && k >= 0) triplets.emplace_back(static_cast<int>(r), static_cast<int>(k), 0.0);
          }
  pattern_.resize(dofs_.n_free(), dofs_.n_free());
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();

  // Value slot of each element-matrix entry, found once so assembly is a plain scatter.
  scatter_.assign(mesh_.n_elements(), {});
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    const auto& element = mesh_.elements[e];
    const Index n = 2 * static_cast<Index>(element.size());
    auto& slots = scatter_[e];
    slots.assign(n * n, -1);
    for (Index p = 0; p < n; ++p)
      for (Index q = 0; q < n; ++q) {
        const Index r = dofs_.free_index(2 * element[p / 2] + p % 2);
        const Index k = dofs_.free_index(2 * element[q / 2] + q % 2);
        if (r < 0 || k < 0) continue;
        const int* begin = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[k];
        const int* end = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[k + 1];
        const int* it = std::lower_bound(begin, end, static_cast<int>(r));
        slots[p * n + q] = static_cast<int>(it - pattern_.innerIndexPtr());
      }
  }
}

ElementVector StripModel::element_values(Index e, const VecX& u) const {
  const auto& element = mesh_.elements[e];
  ElementVector ue(2 * element.size());
  for (std::size_t a = 0; a < element.size(); ++a) {
    ue(2 * a) = u(2 * element[a]);
    ue(2 * a + 1) = u(2 * element[a] + 1);
  }
  return ue;
}

Real StripModel::evaluate(const VecX& u, VecX* gradient, SparseMatrix* hessian_free) {
  if (!u.allFinite())
    throw NumericalError("the displacement increment contains NaN or Inf: the solver diverged; "
                         "use smaller steps");
  if (gradient) gradient->setZero(n_dofs());
  if (hessian_free) {
    *hessian_free = pattern_;
    std::fill_n(hessian_free->valuePtr(), hessian_free->nonZeros(), 0.0);
  }
  Real energy = 0.0;
  n_yielded_ = 0;
  ElementInput in;
  in.type = mesh_.element_type;
  ElementOutput out;
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    const auto& element = mesh_.elements[e];
    in.geometry = &geometry_[e];
    in.committed = &committed_[e * n_points_];
    in.displacement = element_values(e, u);
    evaluate_element(options_, material_, in, gradient != nullptr, hessian_free != nullptr, out);
    energy += out.energy;
    for (int q = 0; q < n_points_; ++q) {
      trial_[e * n_points_ + q] = out.points[q].trial;
      n_yielded_ += out.points[q].yielded ? 1 : 0;
    }
    if (gradient)
      for (std::size_t a = 0; a < element.size(); ++a) {
        (*gradient)(2 * element[a]) += out.residual(2 * a);
        (*gradient)(2 * element[a] + 1) += out.residual(2 * a + 1);
      }
    if (hessian_free) {
      const auto& slots = scatter_[e];
      const Index n = out.tangent.rows();
      Real* values = hessian_free->valuePtr();
      for (Index p = 0; p < n; ++p)
        for (Index q = 0; q < n; ++q)
          if (slots[p * n + q] >= 0) values[slots[p * n + q]] += out.tangent(p, q);
    }
  }
  if (!std::isfinite(energy))
    throw NumericalError("the strain energy is not finite: the increment is too large; use smaller steps");
  return energy;
}

void StripModel::commit(const VecX& u) {
  evaluate(u, nullptr, nullptr);  // the trial states at exactly this u
  const bool finite = options_.kinematics == Kinematics::Finite;
  // Everything that can fail (an element inverted in the new configuration) is computed before
  // any member changes, so a throw leaves the committed state as it was.
  std::vector<Vec2> reference = reference_;
  std::vector<std::vector<PointGeometry>> geometry;
  if (finite) {
    for (Index a = 0; a < mesh_.n_nodes(); ++a) reference[a] += Vec2(u(2 * a), u(2 * a + 1));
    geometry = geometry_for(reference);
    for (Index e = 0; e < mesh_.n_elements(); ++e) {
      const auto f = deformation_gradients(geometry_[e], element_values(e, u));
      for (int q = 0; q < n_points_; ++q) {
        MaterialState& s = trial_[e * n_points_ + q];
        s.stress = push_forward(f[q], s.stress);
      }
    }
  }
  committed_ = trial_;
  total_displacement_ += u;
  if (finite) {
    reference_ = std::move(reference);
    geometry_ = std::move(geometry);
  }
}

void StripModel::restore(std::vector<Vec2> reference, VecX total_displacement, std::vector<MaterialState> states) {
  if (static_cast<Index>(reference.size()) != mesh_.n_nodes() || total_displacement.size() != n_dofs() ||
      states.size() != committed_.size())
    throw InputError(fmt::format("the saved state does not fit this mesh: it has {} nodes and {} integration "
                                 "points, the mesh {} and {} (same [mesh] and refine needed)",
                                 reference.size(), states.size(), mesh_.n_nodes(), committed_.size()));
  auto geometry = geometry_for(reference);
  reference_ = std::move(reference);
  geometry_ = std::move(geometry);
  total_displacement_ = std::move(total_displacement);
  committed_ = std::move(states);
  trial_ = committed_;
}

std::vector<Vec2> StripModel::current_coordinates() const {
  std::vector<Vec2> x(mesh_.nodes);
  for (Index a = 0; a < mesh_.n_nodes(); ++a)
    x[a] += Vec2(total_displacement_(2 * a), total_displacement_(2 * a + 1));
  return x;
}

std::vector<Vec4> StripModel::total_strain(Index e) const {
  std::vector<Vec2> x0;
  for (Index a : mesh_.elements[e]) x0.push_back(mesh_.nodes[a]);
  const auto g0 = element_geometry(mesh_.element_type, x0, e);
  const auto f = deformation_gradients(g0, element_values(e, total_displacement_));
  std::vector<Vec4> out;
  for (const Mat2& fq : f) {
    const Mat2 h = fq - Mat2::Identity();
    Mat2 strain = 0.5 * (h + h.transpose());
    if (options_.kinematics == Kinematics::Finite) strain += 0.5 * h.transpose() * h;
    out.emplace_back(strain(0, 0), strain(1, 1), 0.0, 2.0 * strain(0, 1));
  }
  return out;
}

SparseMatrix StripModel::mass_matrix(bool lumped) const {
  std::vector<Triplet> triplets;
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    const auto& element = mesh_.elements[e];
    const ElementMatrix me = element_mass(mesh_.element_type, geometry_[e], material_.density, lumped);
    for (Index p = 0; p < me.rows(); ++p)
      for (Index q = 0; q < me.cols(); ++q)
        if (me(p, q) != 0.0)
          triplets.emplace_back(static_cast<int>(2 * element[p / 2] + p % 2),
                                static_cast<int>(2 * element[q / 2] + q % 2), me(p, q));
  }
  SparseMatrix m(n_dofs(), n_dofs());
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

Real StripModel::volume() const {
  Real v = 0.0;
  for (const auto& g : geometry_)
    for (const auto& p : g) v += p.weight;
  return v;
}

}  // namespace roller
