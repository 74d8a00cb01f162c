#pragma once
// What a backend measured in one increment, typed per backend (the idea of Drake's
// MathematicalProgramResult::get_solver_details<Solver>()): the interior-point backend fills
// IpoptDetails, the penalty backend PenaltyDetails, and a reader asks for the type it knows.
#include <string>
#include <variant>

#include "roller/core/types.hpp"

namespace roller {

struct IpoptDetails {
  Real complementarity = 0.0;       // max |F_N g| / F_ref
  Real constraint_violation = 0.0;  // max penetration of the constrained candidates [mm]
  int fixed_point_iterations = 0;   // friction passes (condensed: on the last linearisation)
  int nlp_solves = 0;               // NLP solves of the increment (cold restarts included)
  int cold_restarts = 0;            // warm-started NLPs that failed and were solved again cold
  int nlp_variables = 0;            // size of the last NLP
  int nlp_constraints = 0;
  int linearisations = 0;           // condensed formulation: linearisations of the strip
  int condensed_dofs = 0;           // condensed formulation: contact dofs of the last one
  double ipopt_time_s = 0.0;        // time inside Ipopt
  bool acceptable_level = false;    // Ipopt stopped at its acceptable level
  bool condensed_fallback = false;  // the full formulation solved what the condensed could not
  // `later` (solved after this) with the work of both: see BackendDetails::add.
  void add(const IpoptDetails& later);
  std::string brief() const;
};

struct PenaltyDetails {
  int active_set_passes = 0;  // passes of the frozen-status Newton
  int penalty_stages = 0;     // stages of the raised penalty
  void add(const PenaltyDetails& later);
  std::string brief() const;
};

class BackendDetails {
 public:
  // The details of type T, made (all zero) when none are held yet: for the backend that fills them.
  template <class T>
  T& fill() {
    if (!std::holds_alternative<T>(details_)) details_ = T{};
    return std::get<T>(details_);
  }
  // The details of type T; all zero when another backend (or none) solved: the fields a backend
  // does not measure are zero.
  template <class T>
  const T& get() const {
    static const T none{};
    const T* held = std::get_if<T>(&details_);
    return held ? *held : none;
  }
  // The non-zero fields, for messages.
  std::string brief() const;
  // The details of several solves of one increment or step (a suspended or force-controlled roller
  // solves the contact several times, a cut step several sub-increments), `later` solved last: the
  // work (NLP solves, linearisations, time, restarts, passes, stages) summed, the rest `later`'s.
  void add(const BackendDetails& later);

 private:
  std::variant<std::monostate, IpoptDetails, PenaltyDetails> details_;
};

}  // namespace roller
