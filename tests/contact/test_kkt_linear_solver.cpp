// The rule that picks Ipopt's linear solver per NLP (contact/ipopt/ipopt_common.hpp): the dense KKT
// solver (solver/dense_kkt_solver.hpp) for small NLPs under auto, as chosen otherwise.
#include <catch2/catch.hpp>

#include "contact/ipopt/ipopt_common.hpp"

using namespace roller;

TEST_CASE("Ipopt's linear solver: dense for small NLPs under auto, as chosen otherwise", "[ipopt]") {
  using ipopt_detail::kkt_linear_solver;
  CHECK(kkt_linear_solver(KktSolver::Auto, 100, 50) == "ma27");  // n + 2m = 200: the bound
  CHECK(kkt_linear_solver(KktSolver::Auto, 101, 50) == "mumps");
  CHECK(kkt_linear_solver(KktSolver::Dense, 5000, 3000) == "ma27");
  CHECK(kkt_linear_solver(KktSolver::Mumps, 4, 1) == "mumps");
}
