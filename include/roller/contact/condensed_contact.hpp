#pragma once
// The rigid roller's contact with a strip of constant tangent K, condensed onto the surface nodes
// under the roller (docs/model.md, Stationary pass; the stationary pass's correction on the
// roller's contact): K du = b + f_c with the gaps closed at u + du and Coulomb's law between the
// roller and the strip. K is factorised once with its Schur complement S on those nodes' dofs
// (MUMPS); each solve reduces b onto them, solves the small dense problem there, S v = b_s +
// sum_i (lambda_n,i n_i + lambda_t,i t_i) with the exact gaps g_i = |x_i + u_i + v_i - c| - R >= 0
// complementary to lambda_n,i >= 0, the steady slip (Kalker's: the creep plus the material
// derivative of the tangential displacement, upwind along the surface) zero where |lambda_t| <
// mu lambda_n and opposed by lambda_t = mu lambda_n where it slips, the roller carrying P (its
// height an unknown) and, under a horizontal force, Q (its creep an unknown). The small problem is
// solved by Newton's method on the gaps and slips (normals of the last iterate) whose steps are
// linear complementarity problems, each by a primal-dual active set on the contact and stick sets
// (Hintermüller, Ito & Kunisch 2002; Hüeber, Stadler & Wohlmuth 2008), warm-started from the last
// solve.
#include <optional>
#include <string>
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/elastic_roller.hpp"
#include "roller/contact/roller.hpp"
#include "roller/core/types.hpp"
#include "roller/solver/linear_solver_options.hpp"
#include "roller/solver/mumps_factorization.hpp"

namespace roller {

// What the roller carries and how it turns in the steady pass.
struct CondensedLoad {
  Real force = 0.0;        // P: the strip's vertical force on the roller [N/mm]
  Real friction = 0.0;     // mu; 0: frictionless
  Real travel_sign = 1.0;  // +1: the roller moves towards +x (the material enters the contact from +x)
  // The roller's creep, 1 - omega R / V (0 rolls freely, 1 slides; the transient's `slip`), or with
  // a horizontal force (the strip's on the roller) the creep's start: it is then an unknown that
  // carries the force.
  Real creep = 0.0;
  std::optional<Real> horizontal_force;
};

// One roller's place in a condensed contact: the surface nodes under it (by x; ids into the
// iterate u, whose node a has the dofs 2a, 2a + 1), their positions in the mesh, their dofs'
// indices among the tangent's unknowns (x, y of each node in turn) and the roller's centre x.
// Several places (the phases' copies of the strip, each under its own roller) share one tangent.
struct CondensedPlace {
  std::vector<Index> nodes;
  std::vector<Vec2> positions;
  std::vector<Index> unknowns;
  Real centre_x = 0.0;
};

class CondensedContact {
 public:
  // `tangent`: K over the free dofs of `dofs`, symmetric, or with `symmetry` General any square
  // matrix whose first unknowns are the free dofs (the steady Jacobian, its lanes' states after
  // them: they are condensed with the rest); `nodes` (by x, their dofs free) at `positions` in the
  // mesh: the nodes condensed; the roller of `radius` over x = centre_x. NumericalError when K is
  // singular.
  CondensedContact(const SparseMatrix& tangent, const DofMap& dofs, std::vector<Index> nodes,
                   std::vector<Vec2> positions, Real centre_x, Real radius, const LinearSolverOptions& linear_solver,
                   MumpsSolver::Symmetry symmetry = MumpsSolver::Symmetry::Symmetric);
  // The same with one roller per place, each carrying the same load; `free` of the tangent's
  // unknowns are the free dofs (the rest carry no load).
  CondensedContact(const SparseMatrix& tangent, Index free, std::vector<CondensedPlace> places, Real radius,
                   const LinearSolverOptions& linear_solver, MumpsSolver::Symmetry symmetry);
  ~CondensedContact();

  struct Press {
    VecX du;                                 // free dofs; empty when the press failed
    std::vector<NodeContactRecord> contact;  // every condensed node, by place and x (open ones at zero force)
    RollerPose pose;                         // the first place's roller: its centre at (centre_x, c_y)
    Real creep = 0.0;                        // the first place's creep: the load's, or the one that carries Q
    std::string message;                     // why it failed
  };
  // From the strip at `u` (all dofs) under the free-dof load `b`, each roller carrying `load`.
  Press solve(const VecX& u, const VecX& b, const CondensedLoad& load);
  // The next solve's start at place `to`: `other`'s last zones, roller height and creep at its
  // place `from` (the same nodes).
  void start_from(const CondensedContact& other, int from = 0, int to = 0);
  // The next solve starts as the first did: no node in contact, the rollers at height 0, creep 0.
  void restart();
  // Elastic rollers of the rim `rim` at every place: H (2n x 2n over a place's nodes,
  // elastic_roller.hpp's rim_compliance; each node's contact point at the angle asin(dx/R) from the
  // lowest point, over its tributary length) moves the rim at node i by -(H f)_i under the nodes'
  // contact forces f, so the gaps and slips take v + H f where the strip moves by v.
  void set_roller(const RimStiffness& rim);
  int n_places() const { return static_cast<int>(places_.size()); }
  const CondensedPlace& place(int k) const { return places_[static_cast<std::size_t>(k)]; }

 private:
  // A node's place in the contact; a slipping node's traction is slip_sign mu lambda_n.
  enum class Zone : unsigned char { Open, Stick, Slip };
  struct Sets {
    std::vector<Zone> zone;
    std::vector<Real> slip_sign;
    bool operator==(const Sets& o) const { return zone == o.zone && slip_sign == o.slip_sign; }
  };
  // The condensed problem's solution: the nodes' displacement v, their normal and tangential
  // forces and slips, each roller's height and creep and the nodes' zones; a message when it failed.
  struct Small {
    VecX v, rim, lambda_n, lambda_t, slip;  // rim: H f, the rollers' share of the gaps and slips
    VecX height, creep;
    Sets sets;
    std::string message;
  };
  // From the nodes' positions `base` (x + u) and the load reduced onto them.
  Small solve_small(const std::vector<Vec2>& base, const VecX& reduced, const CondensedLoad& load) const;
  // The node whose material reaches node i next from upstream (-1 at its place's upstream end).
  Index upstream(Index i, Real travel_sign) const;
  void build(const SparseMatrix& tangent, MumpsSolver::Symmetry symmetry);

  Real radius_;
  std::vector<CondensedPlace> places_;
  Index unknowns_ = 0, free_ = 0;  // the tangent's, and of them the free dofs (the first ones)
  // Over every place's nodes in turn:
  std::vector<Index> nodes_;     // the condensed nodes
  std::vector<Vec2> reference_;  // their positions in the mesh
  std::vector<int> place_of_;    // their place
  std::vector<Index> first_;     // per place, its first node's index here (and the end at n_places)
  std::vector<Real> tributary_;  // their surface length (half the distance to each neighbour)
  std::vector<Index> schur_;     // their dofs' indices among the tangent's unknowns: x, y of each node in turn
  MumpsSolver solver_;
  MatX compliance_;         // S^-1 on the condensed dofs (x, y of each node in turn)
  MatX roller_compliance_;  // H over the same dofs, block diagonal by place; empty: rigid rollers
  // The last solve's zones, rollers' heights and creeps: the next one's start.
  Sets sets_;
  VecX height_, creep_;
};

}  // namespace roller
