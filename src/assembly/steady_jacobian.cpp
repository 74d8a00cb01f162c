#include "roller/assembly/steady_jacobian.hpp"

#include <algorithm>

#include "roller/core/error.hpp"

namespace roller {

namespace {

using Triplets = std::vector<Eigen::Triplet<Real, int>>;

// The lane state's unknowns: stress (as tau), equivalent plastic strain, the back-stresses.
int state_size(const MaterialParams& m) { return 5 + 4 * m.n_back_stresses(); }

Real& component(MaterialState& s, int i) {
  if (i < 4) return s.stress[i];
  if (i == 4) return s.eq_plastic_strain;
  return s.back_stress[static_cast<std::size_t>((i - 5) / 4)][(i - 5) % 4];
}

VecX packed(MaterialState s, int d) {
  VecX z(d);
  for (int i = 0; i < d; ++i) z[i] = component(s, i);
  return z;
}

// The derivatives of a yielding step's end state (packed) with respect to the state before it
// (packed: `a`, d x d) and to the step's strain (`g`, d x 4), by forward differences of lane_step.
struct StepDerivatives {
  MatX a, g;
};

StepDerivatives step_derivatives(const MaterialParams& m, const Vec4& step, const MaterialState& before,
                                 const MaterialState& after, int d, int parts) {
  // Steps of a ten-millionth of the yield stress and strain: far above rounding (1e-16 of the
  // values), far below the walk's curvature.
  const Real stress_scale = std::max(m.yield_stress, 1e-12 * m.youngs_modulus);
  const Real strain_scale = stress_scale / m.youngs_modulus;
  constexpr Real kRelativeStep = 1e-7;
  const VecX base = packed(after, d);
  StepDerivatives out{MatX(d, d), MatX(d, 4)};
  for (int j = 0; j < d; ++j) {
    MaterialState shifted = before;
    const Real h = kRelativeStep * (j == 4 ? strain_scale : stress_scale);
    component(shifted, j) += h;
    out.a.col(j) = (packed(lane_step(m, step, shifted, parts).trial, d) - base) / h;
  }
  for (int j = 0; j < 4; ++j) {
    Vec4 shifted = step;
    const Real h = kRelativeStep * strain_scale;
    shifted[j] += h;
    out.g.col(j) = (packed(lane_step(m, shifted, before, parts).trial, d) - base) / h;
  }
  return out;
}

// Adds rows' += coefficient * (point p's strain rows of B) over the free dofs: a d x 4 block
// times B_p, into the rows starting at `row`.
void add_times_strain_rows(const StationaryStrip& strip, const DofMap& dofs, Index p, const MatX& block, int row,
                           Triplets& out) {
  const StationaryStrip::StrainOperator& b = strip.strain_operator();
  for (int c = 0; c < 4; ++c)
    for (StationaryStrip::StrainOperator::InnerIterator it(b, static_cast<int>(4 * p + c)); it; ++it) {
      const Index column = dofs.free_index(it.col());
      if (column < 0) continue;
      for (int i = 0; i < block.rows(); ++i)
        if (block(i, c) != 0.0) out.emplace_back(row + i, static_cast<int>(column), block(i, c) * it.value());
    }
}

}  // namespace

SteadyJacobian steady_jacobian(const StationaryStrip& strip, const DofMap& dofs, const SparseMatrix& elastic,
                               const std::vector<Vec4>& strains, const std::vector<MaterialState>& upstream,
                               const std::vector<MaterialState>& states) {
  ROLLER_ASSERT(elastic.rows() == dofs.n_free(), "K_e over the free dofs");
  SteadyJacobian out;
  out.n_free = dofs.n_free();
  const int n_free = static_cast<int>(out.n_free);
  Triplets entries;
  entries.reserve(static_cast<std::size_t>(elastic.nonZeros()) + 16 * static_cast<std::size_t>(strip.n_points()));
  for (int k = 0; k < elastic.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(elastic, k); it; ++it) entries.emplace_back(it.row(), it.col(), it.value());

  const StationaryStrip::StrainOperator& b = strip.strain_operator();
  int next_row = n_free;  // the next lane state's first unknown
  for (std::size_t s = 0; s < strip.streamlines().size(); ++s) {
    const std::vector<Index>& points = strip.streamlines()[s].points;
    int previous_row = -1;  // the state before the point: none until the lane first yields
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Index p = points[i];
      const MaterialParams& m = strip.material(p);
      const MaterialState& before = i == 0 ? upstream[s] : states[static_cast<std::size_t>(points[i - 1])];
      const Vec4 step = strains[p] - (i == 0 ? Vec4::Zero() : strains[points[i - 1]]);
      // The sweep's own yield flags are not kept: this one return mapping costs a hundredth of a
      // yielding point's differences below.
      const bool yields = update_material(m, step, before).yielded;
      if (!yields && previous_row < 0) continue;  // elastic from upstream: K_e holds it
      // An elastic step copies the state: the point's stress is tau of the last yielding step
      // upstream plus C eps, and its forces w B_p^T tau go to that step's unknowns.
      const int row = yields ? next_row : previous_row;
      for (int c = 0; c < 4; ++c)
        for (StationaryStrip::StrainOperator::InnerIterator it(b, static_cast<int>(4 * p + c)); it; ++it) {
          const Index column = dofs.free_index(it.col());
          if (column >= 0) entries.emplace_back(static_cast<int>(column), row + c, strip.weight(p) * it.value());
        }
      if (!yields) continue;
      const int d = state_size(m);
      next_row += d;
      for (int j = 0; j < d; ++j) entries.emplace_back(row + j, row + j, 1.0);
      ++out.n_yielding;
      const StepDerivatives dz = step_derivatives(m, step, before, states[p], d, strip.path_parts());
      if (previous_row >= 0)
        for (int j = 0; j < d; ++j)
          for (int k = 0; k < d; ++k)
            if (dz.a(j, k) != 0.0) entries.emplace_back(row + j, previous_row + k, -dz.a(j, k));
      // The state before holds sigma = tau_before + C eps_before; the step is eps_p - eps_before;
      // tau_p = sigma_p - C eps_p.
      MatX c_block = MatX::Zero(d, 4);
      c_block.topRows<4>() = elastic_matrix(m);
      add_times_strain_rows(strip, dofs, p, -(dz.g - c_block), row, entries);
      if (i > 0) add_times_strain_rows(strip, dofs, points[i - 1], -(dz.a * c_block - dz.g), row, entries);
      previous_row = row;
    }
  }
  out.matrix.resize(next_row, next_row);
  out.matrix.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace roller
