#pragma once
// The rigid roller's frictionless contact with a strip of constant tangent K, condensed onto the
// surface nodes under the roller (docs/model.md, Stationary pass; the stationary pass's correction
// on the roller's contact): K du = b + f_c with the gaps closed at u + du. K is factorised once with
// its Schur complement S on those nodes' dofs (MUMPS); each solve reduces b onto them, solves the small dense
// problem there, S v = b_s + sum_i lambda_i n_i with the exact gaps g_i = |x_i + u_i + v_i - c| - R
// >= 0 complementary to lambda_i >= 0 and sum_i lambda_i (-n_i,y) = P (the roller's height c_y an
// unknown), and expands v to every dof. The small problem is solved by Newton's method on the gaps
// (normals of the last iterate) whose steps are linear complementarity problems, each by a
// primal-dual active set (Hintermüller, Ito & Kunisch 2002), warm-started from the last solve.
#include <string>
#include <vector>

#include "roller/assembly/dof_map.hpp"
#include "roller/contact/contact_records.hpp"
#include "roller/contact/roller.hpp"
#include "roller/core/types.hpp"
#include "roller/solver/linear_solver_options.hpp"
#include "roller/solver/mumps_factorization.hpp"

namespace roller {

class CondensedContact {
 public:
  // `tangent`: K over the free dofs of `dofs` (symmetric); `nodes` (by x, their dofs free) at
  // `positions` in the mesh: the nodes condensed; the roller of `radius` over x = centre_x.
  // NumericalError when K is singular.
  CondensedContact(const SparseMatrix& tangent, const DofMap& dofs, std::vector<Index> nodes,
                   std::vector<Vec2> positions, Real centre_x, Real radius, const LinearSolverOptions& linear_solver);
  ~CondensedContact();

  struct Press {
    VecX du;                                 // free dofs; empty when the press failed
    std::vector<NodeContactRecord> contact;  // every condensed node, by x (open ones at zero force)
    RollerPose pose;                         // the roller's centre at (centre_x, c_y)
    std::string message;                     // why it failed
  };
  // From the strip at `u` (all dofs) under the free-dof load `b`, the roller carrying `force`.
  Press solve(const VecX& u, const VecX& b, Real force);

 private:
  // The condensed problem's solution: the nodes' displacement v, their normal forces, the
  // roller's height and the nodes in contact; a message when it failed.
  struct Small {
    VecX v, lambda;
    Real height = 0.0;
    std::vector<bool> active;
    std::string message;
  };
  // From the nodes' positions `base` (x + u) and the load reduced onto them.
  Small solve_small(const std::vector<Vec2>& base, const VecX& reduced, Real force) const;

  Real centre_x_, radius_;
  std::vector<Index> nodes_;     // the condensed nodes, by x
  std::vector<Vec2> reference_;  // their positions in the mesh
  std::vector<Real> tributary_;  // their surface length (half the distance to each neighbour)
  std::vector<Index> schur_;     // their dofs' free indices: x, y of each node in turn
  MumpsSolver solver_;
  MatX compliance_;  // S^-1 on the condensed dofs (x, y of each node in turn)
  // The last solve's nodes in contact and roller height: the next one's start.
  std::vector<bool> active_;
  Real height_ = 0.0;
};

}  // namespace roller
