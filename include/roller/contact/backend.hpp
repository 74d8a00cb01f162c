#pragma once
// Contact backends: solve one IncrementProblem (DESIGN "ContactBackend"). The non-virtual
// solve() validates, times and checks the result (no NaN leaves a backend); the private
// do_solve() is backend specific. Backends report failure; the driver decides to cut the step.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roller/contact/increment_problem.hpp"
#include "roller/contact/contact_options.hpp"
#include "roller/solver/newton.hpp"

namespace roller {

enum class ContactStatus { Open, Stick, Slip };
const char* to_string(ContactStatus s);

// Result per contact candidate (same order as IncrementProblem::candidates()).
struct NodeContact {
  Real normal_force = 0.0;      // F_N >= 0 on the strip node [N per mm width]
  Real tangential_force = 0.0;  // F_T along the candidate's tangent [N per mm width]
  Real gap = 0.0;               // g at the solution [mm] (negative = penetration)
  Real slip = 0.0;              // tangential slip increment against the roller surface [mm]
  ContactStatus status = ContactStatus::Open;
};

struct BackendResult {
  NewtonStatus status = NewtonStatus::Failure;
  std::string message;
  VecX x;                           // free-dof increment
  std::vector<NodeContact> contact;
  int iterations = 0;               // Newton or interior-point iterations (all passes)
  int factorizations = 0;
  Real residual = 0.0;              // relative equilibrium residual at the solution
  Real max_penetration = 0.0;       // max(0, -min gap) [mm]
  double wall_s = 0.0;
  std::map<std::string, Real> stats;  // backend-specific: complementarity, constraint_violation,
                                      // fixed_point_iterations, ...
  bool converged() const { return status == NewtonStatus::Converged; }
  std::string brief_report() const;
};

class ContactBackend {
 public:
  virtual ~ContactBackend() = default;
  BackendResult solve(IncrementProblem& problem, const VecX& x0);
  virtual std::string name() const = 0;

 private:
  virtual BackendResult do_solve(IncrementProblem& problem, const VecX& x0) = 0;
};

// Throws InputError naming the option when the options are invalid. `newton` controls the
// penalty backend's Newton iterations (the scene's [newton] table).
std::unique_ptr<ContactBackend> make_contact_backend(const ContactOptions& options,
                                                     const NewtonOptions& newton);

}  // namespace roller
