#pragma once
// What one increment starts from, what its solves did and what it commits: the words of the
// contact session (contact_session.hpp) and of the solves inside it.
#include <string>
#include <vector>

#include "roller/contact/backend.hpp"
#include "roller/contact/friction_history.hpp"
#include "roller/contact/increment_problem.hpp"
#include "roller/contact/roller.hpp"
#include "roller/dynamics/suspension.hpp"

namespace roller {

// What an increment's solves did: the outcome of the last one, the work of all of them (a coupled
// roller solves the contact several times).
struct IncrementReport {
  Termination status = Termination::Failed;
  SolveCounters counters;
  Real residual = 0.0;
  Real max_penetration = 0.0;
  Index n_yielded = 0;        // integration points that yielded in the committed increment
  BackendDetails details;     // the contact solves' work summed, the rest of the last one
  int suspension_passes = 0;  // passes coupling the suspension with the contact
  int load_passes = 0;        // contact solves finding the height that carries the prescribed force
  std::string message;
  bool converged() const { return status == Termination::Converged; }
};

// What a converged increment commits.
struct IncrementSolution {
  VecX u;  // increment of all dofs
  std::vector<ContactCandidate> candidates;
  BackendResult contact;
  Real deflection = 0.0;               // a suspended roller's deflection from its anchor
  Vec2 load_offset = Vec2::Zero();     // force control: the centre's offset that carries the forces
  Vec2 load_stiffness = Vec2::Zero();  // and the slopes -dF/dw there per axis (0: not force-controlled)
};

// What the increment starts from besides the strip: the roller's motion (its end as prescribed,
// the load offset added), the forces prescribed on it, and what the run's last increments left.
struct IncrementStart {
  RollerMotion motion;
  PrescribedForce force;
  const FrictionHistory* friction = nullptr;
  const Suspension* suspension = nullptr;
  Vec2 load_offset = Vec2::Zero();
  Vec2 load_stiffness = Vec2::Zero();
  Vec2 roller_force = Vec2::Zero();  // of the strip on the roller at the start [N per mm]
  const VecX* rim = nullptr;         // an elastic roller's rim displacements at the start (null: none yet)
};

}  // namespace roller
