#pragma once
// The roller couplings of an increment (docs/model.md, Roller couplings), one shape for all: each
// moves the roller of an IncrementSolve and solves the contact until the roller is in balance,
// leaving the solution and the work in it.
//   placed     its motion prescribed: one contact solve;
//   suspended  on its viscoelastic suspension: the deflection w with k_eff w + h = F_y(w), jointly
//              in one solve where the backend can, else by the suspension's fixed point;
//   loaded     under prescribed forces: the centre's offsets with F(w) = P, the vertical one
//              jointly where the backend can, each else by the root finder solve_for_force.
#include "increment_solve.hpp"

namespace roller {

void couple_placed(IncrementSolve& solve);
void couple_suspended(IncrementSolve& solve);
void couple_loaded(IncrementSolve& solve);

}  // namespace roller
