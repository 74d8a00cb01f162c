#include "nlp_contact_rows.hpp"

#include <algorithm>
#include <cmath>

namespace roller::ipopt_detail {

FrictionTerms friction_terms(const std::vector<RowMap>& rows, const std::vector<Real>& fbar, Real mu, Real force_tol,
                             const IpoptOptions& o) {
  FrictionTerms f;
  f.law = o.friction;
  f.eps = o.regularization;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Real fb = fbar[rows[k].candidate];
    if (mu > 0.0 && fb > force_tol) {
      f.rows.push_back(static_cast<int>(k));
      f.weight.push_back(mu * fb);
    }
  }
  return f;
}

ContactRows::ContactRows(const IncrementProblem& problem, std::vector<RowMap> rows, FrictionTerms friction,
                         int n_primal, int roller_slot, int rim_slot)
    : problem_(problem),
      rows_(std::move(rows)),
      friction_(std::move(friction)),
      n_primal_(n_primal),
      roller_slot_(roller_slot),
      rim_slot_(rim_slot),
      n_slack_(friction_.split() ? static_cast<int>(friction_.rows.size()) : 0) {
  friction_of_.assign(rows_.size(), -1);
  for (std::size_t j = 0; j < friction_.rows.size(); ++j) friction_of_[friction_.rows[j]] = static_cast<int>(j);
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    const int row = static_cast<int>(k);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b <= a; ++b) {
        const int sa = slot_of(row, a), sb = slot_of(row, b);
        if (sa < 0 || sb < 0) continue;
        hessian_entries_.push_back({row, a, b, std::max(sa, sb), std::min(sa, sb)});
      }
  }
}

Vec2 ContactRows::increment(int k, const Real* z) const {
  Vec2 u = rows_[k].base;
  for (int a = 0; a < 2; ++a)
    if (rows_[k].slot[a] >= 0) u(a) += z[rows_[k].slot[a]];
  if (roller_slot_ >= 0) u.y() -= z[roller_slot_];
  return u;
}

Real ContactRows::slip(int k, const Real* z) const {
  return problem_.slip_at(problem_.candidates()[rows_[k].candidate], increment(k, z), rim(z));
}

Real ContactRows::regularized_force(int j, const Real* z) const {
  const Real s = slip(friction_.rows[j], z);
  return friction_.weight[j] * s / std::sqrt(s * s + friction_.eps * friction_.eps);
}

int ContactRows::jacobian_nnz() const {
  auto n_free = [this](int k) { return (rows_[k].slot[0] >= 0 ? 1 : 0) + (rows_[k].slot[1] >= 0 ? 1 : 0); };
  const int roller = roller_slot_ >= 0 ? 1 : 0;
  int nnz = 0;
  for (std::size_t k = 0; k < rows_.size(); ++k)
    nnz += n_free(static_cast<int>(k)) + roller + n_rim_entries(static_cast<int>(k));
  for (int j = 0; j < n_slack_; ++j) nnz += n_free(friction_.rows[j]) + roller + n_rim_entries(friction_.rows[j]) + 2;
  return nnz;
}

void ContactRows::bounds(Real* z_lower, Real* z_upper, Real* g_lower, Real* g_upper) const {
  const Real inf = 2e19;  // beyond Ipopt's nlp_upper_bound_inf (1e19): no bound
  for (int k = 0; k < n_variables(); ++k) {
    z_lower[k] = k < n_primal_ ? -inf : 0.0;
    z_upper[k] = inf;
  }
  const int n_rows = static_cast<int>(rows_.size());
  for (int r = 0; r < n_constraints(); ++r) {
    g_lower[r] = 0.0;
    g_upper[r] = r < n_rows ? inf : 0.0;
  }
}

void ContactRows::start_slacks(Real* z) const {
  for (int j = 0; j < n_slack_; ++j) {
    const Real s = slip(friction_.rows[j], z);
    z[n_primal_ + j] = std::max(s, 0.0);
    z[n_primal_ + n_slack_ + j] = std::max(-s, 0.0);
  }
}

void ContactRows::start_bound_multipliers(const RowForces& guess, Real* z_lower, Real* z_upper) const {
  for (int k = 0; k < n_variables(); ++k) z_lower[k] = z_upper[k] = 0.0;
  for (int j = 0; j < n_slack_; ++j) {
    const Real bound = friction_.weight[j];
    const Real ft = std::clamp(guess.tangential[friction_.rows[j]], -bound, bound);
    z_lower[n_primal_ + j] = bound + ft;
    z_lower[n_primal_ + n_slack_ + j] = bound - ft;
  }
}

void ContactRows::start_multipliers(const RowForces& guess, Real* lambda) const {
  const int n_rows = static_cast<int>(rows_.size());
  for (int r = 0; r < n_constraints(); ++r) lambda[r] = 0.0;
  for (int k = 0; k < n_rows; ++k) lambda[k] = -guess.normal[k];
  for (int j = 0; j < n_slack_; ++j) lambda[n_rows + j] = -guess.tangential[friction_.rows[j]];
}

Real ContactRows::friction_energy(const Real* z) const {
  Real e = 0.0;
  for (std::size_t j = 0; j < friction_.rows.size(); ++j) {
    if (friction_.split()) {
      e += friction_.weight[j] * (z[n_primal_ + j] + z[n_primal_ + n_slack_ + j]);
    } else {
      const Real s = slip(friction_.rows[j], z);
      e += friction_.weight[j] * std::sqrt(s * s + friction_.eps * friction_.eps);
    }
  }
  return e;
}

void ContactRows::add_friction_gradient(const Real* z, Real* gradient) const {
  for (std::size_t j = 0; j < friction_.rows.size(); ++j) {
    if (friction_.split()) {
      gradient[n_primal_ + j] = friction_.weight[j];
      gradient[n_primal_ + n_slack_ + j] = friction_.weight[j];
    } else {
      const int k = friction_.rows[j];
      const Vec2 v = regularized_force(static_cast<int>(j), z) * problem_.candidates()[rows_[k].candidate].tangent;
      for (int a = 0; a < 2; ++a)
        if (rows_[k].slot[a] >= 0) gradient[rows_[k].slot[a]] += v(a);
      if (roller_slot_ >= 0) gradient[roller_slot_] -= v.y();
      if (n_rim_entries(k) > 0) {
        const RimSample& r = rim_sample(k);
        const Real force = regularized_force(static_cast<int>(j), z);
        for (std::size_t q = 0; q < r.node.size(); ++q)
          for (int a = 0; a < 2; ++a) gradient[rim_slot_ + 2 * r.node[q] + a] += force * r.slip_weight[q](a);
      }
    }
  }
}

void ContactRows::constraints(const Real* z, Real* g) const {
  const auto& cands = problem_.candidates();
  const int n_rows = static_cast<int>(rows_.size());
  for (int k = 0; k < n_rows; ++k) g[k] = problem_.gap_at(cands[rows_[k].candidate], increment(k, z), rim(z));
  for (int j = 0; j < n_slack_; ++j)
    g[n_rows + j] = slip(friction_.rows[j], z) - z[n_primal_ + j] + z[n_primal_ + n_slack_ + j];
}

void ContactRows::jacobian_structure(int* row, int* col) const {
  const int n_rows = static_cast<int>(rows_.size());
  int e = 0;
  for (int k = 0; k < n_rows; ++k) {
    for (int a = 0; a < 2; ++a)
      if (rows_[k].slot[a] >= 0) {
        row[e] = k;
        col[e++] = rows_[k].slot[a];
      }
    if (roller_slot_ >= 0) {
      row[e] = k;
      col[e++] = roller_slot_;
    }
    if (n_rim_entries(k) > 0)
      for (Index node : rim_sample(k).node)
        for (int a = 0; a < 2; ++a) {
          row[e] = k;
          col[e++] = rim_slot_ + 2 * static_cast<int>(node) + a;
        }
  }
  for (int j = 0; j < n_slack_; ++j) {
    const RowMap& m = rows_[friction_.rows[j]];
    for (int a = 0; a < 2; ++a)
      if (m.slot[a] >= 0) {
        row[e] = n_rows + j;
        col[e++] = m.slot[a];
      }
    if (roller_slot_ >= 0) {
      row[e] = n_rows + j;
      col[e++] = roller_slot_;
    }
    if (n_rim_entries(friction_.rows[j]) > 0)
      for (Index node : rim_sample(friction_.rows[j]).node)
        for (int a = 0; a < 2; ++a) {
          row[e] = n_rows + j;
          col[e++] = rim_slot_ + 2 * static_cast<int>(node) + a;
        }
    row[e] = n_rows + j;
    col[e++] = n_primal_ + j;
    row[e] = n_rows + j;
    col[e++] = n_primal_ + n_slack_ + j;
  }
}

void ContactRows::jacobian_values(const Real* z, Real* values) const {
  const auto& cands = problem_.candidates();
  int e = 0;
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    const Vec2 n = problem_.normal_for(cands[rows_[k].candidate], increment(static_cast<int>(k), z));
    for (int a = 0; a < 2; ++a)
      if (rows_[k].slot[a] >= 0) values[e++] = n(a);
    if (roller_slot_ >= 0) values[e++] = -n.y();
    if (n_rim_entries(static_cast<int>(k)) > 0)
      for (const Vec2& weight : rim_sample(static_cast<int>(k)).gap_weight)
        for (int a = 0; a < 2; ++a) values[e++] = weight(a);
  }
  for (int j = 0; j < n_slack_; ++j) {
    const RowMap& m = rows_[friction_.rows[j]];
    const Vec2& t = cands[m.candidate].tangent;
    for (int a = 0; a < 2; ++a)
      if (m.slot[a] >= 0) values[e++] = t(a);
    if (roller_slot_ >= 0) values[e++] = -t.y();
    if (n_rim_entries(friction_.rows[j]) > 0)
      for (const Vec2& weight : rim_sample(friction_.rows[j]).slip_weight)
        for (int a = 0; a < 2; ++a) values[e++] = weight(a);
    values[e++] = -1.0;
    values[e++] = 1.0;
  }
}

void ContactRows::hessian_structure(int* row, int* col) const {
  for (std::size_t e = 0; e < hessian_entries_.size(); ++e) {
    row[e] = hessian_entries_[e].r;
    col[e] = hessian_entries_[e].c;
  }
}

void ContactRows::add_hessian(const Real* z, Real obj_factor, const Real* lambda, const std::vector<int>& position,
                              Real* values) const {
  const auto& cands = problem_.candidates();
  std::size_t e = 0;
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    if (e == hessian_entries_.size() || hessian_entries_[e].row_map != static_cast<int>(k)) continue;
    const ContactCandidate& c = cands[rows_[k].candidate];
    Mat2 block = problem_.gap_curvature(c, increment(static_cast<int>(k), z), lambda[k]);
    const int j = friction_of_[k];
    if (!friction_.split() && j >= 0 && obj_factor != 0.0) {
      const Real s = slip(static_cast<int>(k), z);
      const Real q = s * s + friction_.eps * friction_.eps;
      const Real curvature = friction_.weight[j] * friction_.eps * friction_.eps / (q * std::sqrt(q));
      block += obj_factor * curvature * c.tangent * c.tangent.transpose();
    }
    // The block is the curvature in the node's increment relative to the roller; the roller's
    // step enters that increment as -e_y (component 2: the y row and column, negated).
    auto entry = [&block](int a, int b) {
      const Real sign = (a == 2) != (b == 2) ? -1.0 : 1.0;
      return sign * block(a == 2 ? 1 : a, b == 2 ? 1 : b);
    };
    for (; e < hessian_entries_.size() && hessian_entries_[e].row_map == static_cast<int>(k); ++e)
      values[position[e]] += entry(hessian_entries_[e].a, hessian_entries_[e].b);
  }
}

RowForces ContactRows::forces(const Real* z, const Real* lambda) const {
  const int n_rows = static_cast<int>(rows_.size());
  RowForces f;
  f.normal.assign(n_rows, 0.0);
  f.tangential.assign(n_rows, 0.0);
  for (int k = 0; k < n_rows; ++k) f.normal[k] = -lambda[k];
  for (std::size_t j = 0; j < friction_.rows.size(); ++j)
    f.tangential[friction_.rows[j]] =
        friction_.split() ? -lambda[n_rows + static_cast<int>(j)] : -regularized_force(static_cast<int>(j), z);
  return f;
}

}  // namespace roller::ipopt_detail
