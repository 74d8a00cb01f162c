#pragma once
// The one Ipopt adapter of the interior-point backend: an objective over the formulation's
// primal variables (NlpObjective: the strip's energy in ipopt_full.cpp, the condensed quadratic
// model in ipopt_condensed.cpp) plus the contact rows (nlp_contact_rows.hpp).
#include <string>
#include <vector>

#include <IpTNLP.hpp>

#include "nlp_contact_rows.hpp"

namespace roller::ipopt_detail {

using IIndex = Ipopt::Index;
using Ipopt::Number;

// The objective part of an increment's NLP over the primal variables d.
class NlpObjective {
 public:
  virtual ~NlpObjective() = default;
  virtual int n() const = 0;
  // false: it cannot be evaluated at d (Ipopt then shortens its step).
  virtual bool value(const Real* d, Real& f) = 0;
  virtual bool gradient(const Real* d, Real* g) = 0;  // fills g[0..n)
  // Lower triangle of the Hessian: a fixed structure, values scaled by obj_factor.
  virtual int hessian_nnz() const = 0;
  virtual void hessian_structure(int* row, int* col) const = 0;
  virtual bool hessian_values(const Real* d, Real obj_factor, Real* values) = 0;
  // Where the objective stores the lower-triangle entry (r, c), or -1 when it has no entry there
  // (the contact curvature then gets an entry of its own, which Ipopt sums with the others).
  virtual int hessian_position(int r, int c) const = 0;
  // The cause of the last failed evaluation ("" if none).
  virtual std::string evaluation_error() const { return ""; }
  // The variable of the suspended roller's vertical step among d, -1 when the roller is given.
  virtual int roller_slot() const { return -1; }
  // The first of an elastic roller's rim displacements among d, -1 when the roller is rigid.
  virtual int rim_slot() const { return -1; }
};

// An objective with an elastic roller's rim displacements w appended to the base's variables:
// f = base(d) + 1/2 w^T K w (docs/model.md, Elastic roller); K's lower triangle is a dense block
// of the Hessian.
class RimObjective final : public NlpObjective {
 public:
  RimObjective(NlpObjective& base, const MatX& stiffness) : base_(base), k_(stiffness) {}
  int n() const override { return base_.n() + static_cast<int>(k_.rows()); }
  bool value(const Real* d, Real& f) override;
  bool gradient(const Real* d, Real* g) override;
  int hessian_nnz() const override;
  void hessian_structure(int* row, int* col) const override;
  bool hessian_values(const Real* d, Real obj_factor, Real* values) override;
  int hessian_position(int r, int c) const override;
  std::string evaluation_error() const override { return base_.evaluation_error(); }
  int roller_slot() const override { return base_.roller_slot(); }
  int rim_slot() const override { return base_.n(); }

 private:
  NlpObjective& base_;
  const MatX& k_;
};

// Start values of one NLP solve.
struct NlpStart {
  VecX primal;      // d
  RowForces guess;  // forces per row, for the multipliers of a warm start
};

// A solved NLP.
struct NlpSolution {
  bool finalized = false;
  VecX z;            // all NLP variables
  RowForces forces;  // per row
};

class ContactTnlp : public Ipopt::TNLP {
 public:
  ContactTnlp(NlpObjective& objective, const ContactRows& rows, const NlpStart& start);

  const NlpSolution& solution() const { return solution_; }

  bool get_nlp_info(IIndex& n, IIndex& m, IIndex& nnz_jac_g, IIndex& nnz_h_lag, IndexStyleEnum& style) override;
  bool get_bounds_info(IIndex n, Number* x_l, Number* x_u, IIndex m, Number* g_l, Number* g_u) override;
  bool get_starting_point(IIndex n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, IIndex m,
                          bool init_lambda, Number* lambda) override;
  bool eval_f(IIndex n, const Number* x, bool new_x, Number& obj_value) override;
  bool eval_grad_f(IIndex n, const Number* x, bool new_x, Number* grad_f) override;
  bool eval_g(IIndex n, const Number* x, bool new_x, IIndex m, Number* g) override;
  bool eval_jac_g(IIndex n, const Number* x, bool new_x, IIndex m, IIndex nele_jac, IIndex* i_row, IIndex* j_col,
                  Number* values) override;
  bool eval_h(IIndex n, const Number* x, bool new_x, Number obj_factor, IIndex m, const Number* lambda, bool new_lambda,
              IIndex nele_hess, IIndex* i_row, IIndex* j_col, Number* values) override;
  void finalize_solution(Ipopt::SolverReturn status, IIndex n, const Number* x, const Number* z_l, const Number* z_u,
                         IIndex m, const Number* g, const Number* lambda, Number obj_value,
                         const Ipopt::IpoptData* ip_data, Ipopt::IpoptCalculatedQuantities* ip_cq) override;

 private:
  NlpObjective& objective_;
  const ContactRows& rows_;
  const NlpStart& start_;
  std::vector<int> position_;  // per contact Hessian entry: its index among the Hessian's values
  int n_appended_ = 0;         // contact Hessian entries after the objective's
  NlpSolution solution_;
};

}  // namespace roller::ipopt_detail
