#include "roller/assembly/strip_model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "roller/core/error.hpp"

namespace roller {

namespace {

// Green-Lagrange strain [xx, yy, zz, 2xy] of a deformation gradient; linearised for small
// kinematics.
Vec4 green_lagrange(const Mat2& f, bool finite) {
  const Mat2 h = f - Mat2::Identity();
  Mat2 strain = 0.5 * (h + h.transpose());
  if (finite) strain += 0.5 * h.transpose() * h;
  return Vec4(strain(0, 0), strain(1, 1), 0.0, 2.0 * strain(0, 1));
}

}  // namespace

StripModel::StripModel(Mesh mesh, MaterialParams material, ElementOptions options)
    : StripModel(std::move(mesh), uniform_materials(material, 0), options) {}

StripModel::StripModel(Mesh mesh, ElementMaterials materials, ElementOptions options)
    : mesh_(std::move(mesh)),
      materials_(std::move(materials)),
      options_(options),
      n_points_(n_integration_points(mesh_.element_type)),
      reference_(mesh_.nodes),
      total_displacement_(VecX::Zero(mesh_.n_dofs())) {
  // The homogeneous constructor leaves the index to fill here, where the mesh is known.
  if (materials_.index.empty() && materials_.table.size() == 1)
    materials_.index.assign(static_cast<std::size_t>(mesh_.n_elements()), 0);
  ROLLER_ASSERT(static_cast<Index>(materials_.index.size()) == mesh_.n_elements() &&
                    materials_.layer.size() == materials_.table.size(),
                "one material index per element, one layer per material");
  std::string why;
  for (const MaterialParams& m : materials_.table)
    if (!m.is_valid(&why)) throw InputError(why);
  committed_.resize(mesh_.n_elements() * n_points_);
  for (Index e = 0; e < mesh_.n_elements(); ++e)
    std::fill_n(committed_.begin() + e * n_points_, n_points_, initial_state(materials_.of(e)));
  check_not_inverted(reference_);
  set_dof_map(DofMap(std::vector<bool>(mesh_.n_dofs(), false)));
}

void StripModel::point_geometry(Index e, const std::vector<Vec2>& coordinates, std::vector<Vec2>& xe,
                                std::vector<PointGeometry>& out) const {
  const auto& element = mesh_.elements[e];
  xe.resize(element.size());
  for (std::size_t a = 0; a < element.size(); ++a) xe[a] = coordinates[element[a]];
  element_geometry(mesh_.element_type, xe, e, out);
}

std::vector<PointGeometry> StripModel::point_geometry(Index e, const std::vector<Vec2>& coordinates) const {
  std::vector<Vec2> xe;
  std::vector<PointGeometry> out;
  point_geometry(e, coordinates, xe, out);
  return out;
}

void StripModel::check_not_inverted(const std::vector<Vec2>& coordinates) const {
  for (Index e = 0; e < mesh_.n_elements(); ++e) point_geometry(e, coordinates);
}

// Nodes sharing an element with each node (itself included), sorted, every node counted as its
// master (a periodic strip's right edge as its left edge): offsets `start` (n_nodes + 1) into
// `adjacent`. Built by counting then filling, so the memory is one Index per node-node coupling,
// not the 16 bytes per element-matrix entry a triplet list would need.
static void node_adjacency(const Mesh& mesh, const std::vector<Index>& masters, std::vector<Index>& start,
                           std::vector<Index>& adjacent) {
  const Index n = mesh.n_nodes();
  std::vector<Index> bound(n + 1, 0);
  for (const auto& element : mesh.elements)
    for (Index a : element) bound[masters[a] + 1] += static_cast<Index>(element.size());
  for (Index a = 0; a < n; ++a) bound[a + 1] += bound[a];
  adjacent.assign(bound[n], 0);
  std::vector<Index> fill(bound.begin(), bound.end() - 1);
  for (const auto& element : mesh.elements)
    for (Index a : element)
      for (Index c : element) adjacent[fill[masters[a]]++] = masters[c];
  start.assign(n + 1, 0);
  Index kept = 0;
  for (Index a = 0; a < n; ++a) {
    Index* first = adjacent.data() + bound[a];
    std::sort(first, adjacent.data() + bound[a + 1]);
    Index* last = std::unique(first, adjacent.data() + bound[a + 1]);
    kept = static_cast<Index>(std::copy(first, last, adjacent.data() + kept) - adjacent.data());
    start[a + 1] = kept;
  }
  adjacent.resize(kept);
  adjacent.shrink_to_fit();
}

void StripModel::set_dof_map(DofMap dofs) {
  dofs_ = std::move(dofs);
  std::vector<Index> masters(static_cast<std::size_t>(mesh_.n_nodes()));
  for (Index a = 0; a < mesh_.n_nodes(); ++a) masters[a] = a;
  if (dofs_.has_masters()) masters = node_masters(mesh_);
  std::vector<Index> start, adjacent;
  node_adjacency(mesh_, masters, start, adjacent);

  // Compressed columns over the free dofs. Free indices grow with the dof number and the
  // neighbours of a node are sorted, so each column's rows come out sorted.
  const Index n_free = dofs_.n_free();
  outer_.assign(n_free + 1, 0);
  inner_.clear();
  for (Index k = 0; k < n_free; ++k) {
    const Index c = dofs_.free_dofs()[k] / 2;
    for (Index s = start[c]; s < start[c + 1]; ++s)
      for (int i = 0; i < 2; ++i) {
        const Index r = dofs_.free_index(2 * adjacent[s] + i);
        if (r >= 0) inner_.push_back(static_cast<int>(r));
      }
    outer_[k + 1] = static_cast<int>(inner_.size());
  }
  inner_.shrink_to_fit();

  // Value slots, found once so assembly is a plain scatter. Rows 2a and 2a+1 of a node are
  // adjacent in every column, so one slot per (node a, node c, column dof j) of an element
  // locates its 2x2 block: the first free row of node a in column 2c+j (-1: column
  // constrained or node a fully constrained). Half the memory of one slot per matrix entry.
  const Index m = nodes_per_element(mesh_.element_type);
  scatter_.assign(static_cast<std::size_t>(mesh_.n_elements() * m * m * 2), -1);
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    const auto& element = mesh_.elements[e];
    int* slots = scatter_.data() + e * m * m * 2;
    for (Index pa = 0; pa < m; ++pa)
      for (Index pc = 0; pc < m; ++pc)
        for (int j = 0; j < 2; ++j) {
          const Index k = dofs_.free_index(2 * element[pc] + j);
          Index r = dofs_.free_index(2 * element[pa]);
          if (r < 0) r = dofs_.free_index(2 * element[pa] + 1);
          if (k < 0 || r < 0) continue;
          const int* begin = inner_.data() + outer_[k];
          const int* end = inner_.data() + outer_[k + 1];
          const int* it = std::lower_bound(begin, end, static_cast<int>(r));
          slots[(pa * m + pc) * 2 + j] = static_cast<int>(it - inner_.data());
        }
  }
}

void StripModel::zero_hessian(SparseMatrix& h) const {
  const Index n = dofs_.n_free();
  const bool same = h.rows() == n && h.cols() == n && h.isCompressed() &&
                    h.nonZeros() == static_cast<Index>(inner_.size()) &&
                    std::equal(outer_.begin(), outer_.end(), h.outerIndexPtr()) &&
                    std::equal(inner_.begin(), inner_.end(), h.innerIndexPtr());
  if (!same) {
    h = SparseMatrix(n, n);
    h.resizeNonZeros(static_cast<Index>(inner_.size()));
    std::copy(outer_.begin(), outer_.end(), h.outerIndexPtr());
    std::copy(inner_.begin(), inner_.end(), h.innerIndexPtr());
  }
  std::fill_n(h.valuePtr(), h.nonZeros(), 0.0);
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

StripEvaluation StripModel::evaluate(const VecX& u, VecX* gradient, SparseMatrix* hessian_free) {
  return evaluate_states(u, gradient, hessian_free, nullptr);
}

StripEvaluation StripModel::evaluate_states(const VecX& u, VecX* gradient, SparseMatrix* hessian_free,
                                            std::vector<MaterialState>* trial) {
  ROLLER_ASSERT(u.size() == n_dofs(), "the strip is evaluated at an increment of all its dofs");
  if (!u.allFinite())
    throw NumericalError(
        "the displacement increment contains NaN or Inf: the solver diverged; "
        "use smaller steps (a larger steps.count, or steps.max_cuts)");
  if (gradient) gradient->setZero(n_dofs());
  if (hessian_free) zero_hessian(*hessian_free);
  Real energy = 0.0;
  Index n_yielded = 0;
  ElementInput in;
  in.type = mesh_.element_type;
  ElementOutput out;
  if (trial) trial->resize(committed_.size());
  std::vector<Vec2> xe;  // buffers reused by every element
  std::vector<PointGeometry> geometry;
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    const auto& element = mesh_.elements[e];
    point_geometry(e, reference_, xe, geometry);
    in.geometry = &geometry;
    in.committed = &committed_[e * n_points_];
    in.frozen_recovery = frozen_recovery_.empty() ? nullptr : &frozen_recovery_[e * n_points_];
    in.displacement = element_values(e, u);
    evaluate_element(options_, materials_.of(e), in, gradient != nullptr, hessian_free != nullptr, out);
    energy += out.energy;
    for (int q = 0; q < n_points_; ++q) {
      if (trial) (*trial)[e * n_points_ + q] = out.points[q].trial;
      n_yielded += out.points[q].yielded ? 1 : 0;
    }
    if (gradient)
      for (std::size_t a = 0; a < element.size(); ++a) {
        (*gradient)(2 * element[a]) += out.residual(2 * a);
        (*gradient)(2 * element[a] + 1) += out.residual(2 * a + 1);
      }
    if (hessian_free) {
      const Index m = static_cast<Index>(element.size());
      const int* slots = scatter_.data() + e * m * m * 2;
      Real* values = hessian_free->valuePtr();
      for (Index pa = 0; pa < m; ++pa) {
        const bool x_free = !dofs_.is_constrained(2 * element[pa]);
        const bool y_free = !dofs_.is_constrained(2 * element[pa] + 1);
        for (Index pc = 0; pc < m; ++pc)
          for (int j = 0; j < 2; ++j) {
            const int slot = slots[(pa * m + pc) * 2 + j];
            if (slot < 0) continue;
            if (x_free) values[slot] += out.tangent(2 * pa, 2 * pc + j);
            if (y_free) values[slot + (x_free ? 1 : 0)] += out.tangent(2 * pa + 1, 2 * pc + j);
          }
      }
    }
  }
  if (dead_load_.size() > 0) {
    energy -= dead_load_.dot(u);
    if (gradient) *gradient -= dead_load_;
  }
  if (!std::isfinite(energy))
    throw NumericalError(
        "the strain energy is not finite: the increment is too large; use smaller steps (a larger steps.count, or "
        "steps.max_cuts)");
  return {energy, n_yielded};
}

void StripModel::freeze_recovery(std::vector<Real> multipliers) {
  ROLLER_ASSERT(multipliers.empty() || multipliers.size() == committed_.size(),
                "one frozen multiplier per integration point");
  frozen_recovery_ = std::move(multipliers);
}

std::vector<Real> StripModel::plastic_multipliers(const VecX& u) {
  std::vector<MaterialState> trial;
  evaluate_states(u, nullptr, nullptr, &trial);
  std::vector<Real> d(trial.size());
  for (std::size_t k = 0; k < trial.size(); ++k) d[k] = trial[k].eq_plastic_strain - committed_[k].eq_plastic_strain;
  return d;
}

Index StripModel::commit(const VecX& u) {
  ROLLER_ASSERT(frozen_recovery_.empty(), "a commit takes the exact update, with no recovery frozen");
  std::vector<MaterialState> trial;
  const Index n_yielded = evaluate_states(u, nullptr, nullptr, &trial).n_yielded;  // trial states at exactly this u
  const bool finite = options_.kinematics == Kinematics::Finite;
  // Everything that can fail (an element inverted in the new configuration) is computed before
  // any member changes, so a throw leaves the committed state as it was.
  std::vector<Vec2> reference = reference_;
  if (finite) {
    for (Index a = 0; a < mesh_.n_nodes(); ++a) reference[a] += Vec2(u(2 * a), u(2 * a + 1));
    check_not_inverted(reference);
    for (Index e = 0; e < mesh_.n_elements(); ++e) {
      const auto f = deformation_gradients(point_geometry(e, reference_), element_values(e, u));
      const int n_back = materials_.of(e).n_back_stresses();
      for (int q = 0; q < n_points_; ++q) {
        MaterialState& s = trial[e * n_points_ + q];
        s.stress = push_forward(f[q], s.stress);
        // Back-stresses rotate as the stress does; the deviator is taken again so that the flow
        // stays volume-preserving (docs/model.md, Hardening laws).
        for (int i = 0; i < n_back; ++i) {
          Vec4& alpha = s.back_stress[static_cast<std::size_t>(i)];
          alpha = push_forward(f[q], alpha);
          alpha.head<3>().array() -= alpha.head<3>().sum() / 3.0;
        }
      }
    }
  }
  ROLLER_ASSERT(trial.size() == committed_.size(), "one committed state per integration point");
  committed_ = std::move(trial);
  total_displacement_ += u;
  if (finite) reference_ = std::move(reference);
  ROLLER_ASSERT(total_displacement_.allFinite(), "a committed displacement is finite");
  return n_yielded;
}

void StripModel::restore(std::vector<Vec2> reference, VecX total_displacement, std::vector<MaterialState> states) {
  if (static_cast<Index>(reference.size()) != mesh_.n_nodes() || total_displacement.size() != n_dofs() ||
      states.size() != committed_.size())
    throw InputError(
        fmt::format("the saved state does not fit this mesh: it has {} nodes and {} integration "
                    "points, the mesh {} and {} (same [mesh] and refine needed)",
                    reference.size(), states.size(), mesh_.n_nodes(), committed_.size()));
  check_not_inverted(reference);
  reference_ = std::move(reference);
  total_displacement_ = std::move(total_displacement);
  committed_ = std::move(states);
}

std::vector<Vec2> StripModel::current_coordinates() const {
  std::vector<Vec2> x(mesh_.nodes);
  for (Index a = 0; a < mesh_.n_nodes(); ++a) x[a] += Vec2(total_displacement_(2 * a), total_displacement_(2 * a + 1));
  return x;
}

std::vector<Vec4> StripModel::total_strain(Index e) const {
  std::vector<Vec2> x0;
  for (Index a : mesh_.elements[e]) x0.push_back(mesh_.nodes[a]);
  const auto g0 = element_geometry(mesh_.element_type, x0, e);
  std::vector<Vec4> out;
  for (const Mat2& f : deformation_gradients(g0, element_values(e, total_displacement_)))
    out.push_back(green_lagrange(f, options_.kinematics == Kinematics::Finite));
  return out;
}

std::vector<Vec4> StripModel::increment_strain(Index e, const VecX& du) const {
  const bool finite = options_.kinematics == Kinematics::Finite;
  std::vector<Vec2> xs;
  for (Index a : mesh_.elements[e])
    xs.push_back(finite ? Vec2(reference_[a] - Vec2(du(2 * a), du(2 * a + 1))) : mesh_.nodes[a]);
  const auto g = element_geometry(mesh_.element_type, xs, e);
  std::vector<Vec4> out;
  for (const Mat2& f : deformation_gradients(g, element_values(e, du))) out.push_back(green_lagrange(f, finite));
  return out;
}

SparseMatrix StripModel::mass_matrix(bool lumped) const {
  std::vector<Triplet> triplets;
  for (Index e = 0; e < mesh_.n_elements(); ++e) {
    const auto& element = mesh_.elements[e];
    const ElementMatrix me =
        element_mass(mesh_.element_type, point_geometry(e, reference_), materials_.of(e).density, lumped);
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
  for (Index e = 0; e < mesh_.n_elements(); ++e)
    for (const auto& p : point_geometry(e, reference_)) v += p.weight;
  return v;
}

}  // namespace roller
