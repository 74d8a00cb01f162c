#include "contact_tnlp.hpp"

#include <algorithm>
#include <cmath>

namespace roller::ipopt_detail {

ContactTnlp::ContactTnlp(NlpObjective& objective, const ContactRows& rows, const NlpStart& start)
    : objective_(objective), rows_(rows), start_(start) {
  std::vector<int> r(rows.hessian_nnz()), c(rows.hessian_nnz());
  rows.hessian_structure(r.data(), c.data());
  position_.resize(r.size());
  for (std::size_t e = 0; e < r.size(); ++e) {
    const int p = objective.hessian_position(r[e], c[e]);
    position_[e] = p >= 0 ? p : objective.hessian_nnz() + n_appended_++;
  }
}

bool ContactTnlp::get_nlp_info(IIndex& n, IIndex& m, IIndex& nnz_jac_g, IIndex& nnz_h_lag, IndexStyleEnum& style) {
  n = rows_.n_variables();
  m = rows_.n_constraints();
  nnz_jac_g = rows_.jacobian_nnz();
  nnz_h_lag = objective_.hessian_nnz() + n_appended_;
  style = TNLP::C_STYLE;
  return true;
}

bool ContactTnlp::get_bounds_info(IIndex /*n*/, Number* x_l, Number* x_u, IIndex /*m*/, Number* g_l, Number* g_u) {
  rows_.bounds(x_l, x_u, g_l, g_u);
  return true;
}

bool ContactTnlp::get_starting_point(IIndex /*n*/, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u,
                                     IIndex /*m*/, bool init_lambda, Number* lambda) {
  if (init_x) {
    std::copy(start_.primal.data(), start_.primal.data() + rows_.n_primal(), x);
    rows_.start_slacks(x);
  }
  if (init_z) rows_.start_bound_multipliers(start_.guess, z_l, z_u);
  if (init_lambda) rows_.start_multipliers(start_.guess, lambda);
  return true;
}

bool ContactTnlp::eval_f(IIndex /*n*/, const Number* x, bool /*new_x*/, Number& obj_value) {
  if (!objective_.value(x, obj_value)) return false;
  obj_value += rows_.friction_energy(x);
  return std::isfinite(obj_value);
}

bool ContactTnlp::eval_grad_f(IIndex n, const Number* x, bool /*new_x*/, Number* grad_f) {
  if (!objective_.gradient(x, grad_f)) return false;
  std::fill(grad_f + rows_.n_primal(), grad_f + n, 0.0);
  rows_.add_friction_gradient(x, grad_f);
  return true;
}

bool ContactTnlp::eval_g(IIndex /*n*/, const Number* x, bool /*new_x*/, IIndex /*m*/, Number* g) {
  rows_.constraints(x, g);
  return true;
}

bool ContactTnlp::eval_jac_g(IIndex /*n*/, const Number* x, bool /*new_x*/, IIndex /*m*/, IIndex /*nele_jac*/,
                             IIndex* i_row, IIndex* j_col, Number* values) {
  if (values)
    rows_.jacobian_values(x, values);
  else
    rows_.jacobian_structure(i_row, j_col);
  return true;
}

bool ContactTnlp::eval_h(IIndex /*n*/, const Number* x, bool /*new_x*/, Number obj_factor, IIndex /*m*/,
                         const Number* lambda, bool /*new_lambda*/, IIndex /*nele_hess*/, IIndex* i_row, IIndex* j_col,
                         Number* values) {
  const int n_objective = objective_.hessian_nnz();
  if (!values) {
    objective_.hessian_structure(i_row, j_col);
    std::vector<int> r(position_.size()), c(position_.size());
    rows_.hessian_structure(r.data(), c.data());
    for (std::size_t e = 0; e < position_.size(); ++e)
      if (position_[e] >= n_objective) {
        i_row[position_[e]] = r[e];
        j_col[position_[e]] = c[e];
      }
    return true;
  }
  if (!objective_.hessian_values(x, obj_factor, values)) return false;
  std::fill(values + n_objective, values + n_objective + n_appended_, 0.0);
  rows_.add_hessian(x, obj_factor, lambda, position_, values);
  return true;
}

void ContactTnlp::finalize_solution(Ipopt::SolverReturn /*status*/, IIndex n, const Number* x, const Number* /*z_l*/,
                                    const Number* /*z_u*/, IIndex /*m*/, const Number* /*g*/, const Number* lambda,
                                    Number /*obj_value*/, const Ipopt::IpoptData* /*ip_data*/,
                                    Ipopt::IpoptCalculatedQuantities* /*ip_cq*/) {
  solution_.finalized = true;
  solution_.z = Eigen::Map<const VecX>(x, n);
  solution_.forces = rows_.forces(x, lambda);
}

bool RimObjective::value(const Real* d, Real& f) {
  if (!base_.value(d, f)) return false;
  const Eigen::Map<const VecX> w(d + base_.n(), k_.rows());
  f += 0.5 * w.dot(k_ * w);
  return true;
}

bool RimObjective::gradient(const Real* d, Real* g) {
  if (!base_.gradient(d, g)) return false;
  Eigen::Map<VecX>(g + base_.n(), k_.rows()) = k_ * Eigen::Map<const VecX>(d + base_.n(), k_.rows());
  return true;
}

int RimObjective::hessian_nnz() const {
  const int m = static_cast<int>(k_.rows());
  return base_.hessian_nnz() + m * (m + 1) / 2;
}

void RimObjective::hessian_structure(int* row, int* col) const {
  base_.hessian_structure(row, col);
  int e = base_.hessian_nnz();
  const int nb = base_.n(), m = static_cast<int>(k_.rows());
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) {
      row[e] = nb + i;
      col[e++] = nb + j;
    }
}

bool RimObjective::hessian_values(const Real* d, Real obj_factor, Real* values) {
  if (!base_.hessian_values(d, obj_factor, values)) return false;
  int e = base_.hessian_nnz();
  const int m = static_cast<int>(k_.rows());
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) values[e++] = obj_factor * k_(i, j);
  return true;
}

int RimObjective::hessian_position(int r, int c) const {
  const int nb = base_.n();
  if (r < nb && c < nb) return base_.hessian_position(r, c);
  if (r < nb || c < nb) return -1;
  const int i = std::max(r, c) - nb, j = std::min(r, c) - nb;
  return base_.hessian_nnz() + i * (i + 1) / 2 + j;
}

}  // namespace roller::ipopt_detail
