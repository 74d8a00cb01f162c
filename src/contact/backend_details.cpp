#include "roller/contact/backend_details.hpp"

#include <type_traits>

#include <fmt/format.h>

namespace roller {

namespace {

// Appends "name value" when the value is not zero.
void add_field(std::string& s, const char* name, double value) {
  if (value != 0.0) s += fmt::format("{}{} {:.3g}", s.empty() ? "" : ", ", name, value);
}

}  // namespace

void IpoptDetails::add(const IpoptDetails& later) {
  const IpoptDetails work = *this;
  *this = later;
  nlp_solves += work.nlp_solves;
  cold_restarts += work.cold_restarts;
  linearisations += work.linearisations;
  ipopt_time_s += work.ipopt_time_s;
  acceptable_level = acceptable_level || work.acceptable_level;
  condensed_fallback = condensed_fallback || work.condensed_fallback;
}

std::string IpoptDetails::brief() const {
  std::string s;
  add_field(s, "complementarity", complementarity);
  add_field(s, "constraint_violation", constraint_violation);
  add_field(s, "fixed_point_iterations", fixed_point_iterations);
  add_field(s, "nlp_solves", nlp_solves);
  add_field(s, "cold_restarts", cold_restarts);
  add_field(s, "nlp_variables", nlp_variables);
  add_field(s, "nlp_constraints", nlp_constraints);
  add_field(s, "linearisations", linearisations);
  add_field(s, "condensed_dofs", condensed_dofs);
  add_field(s, "ipopt_time_s", ipopt_time_s);
  add_field(s, "acceptable_level", acceptable_level ? 1.0 : 0.0);
  add_field(s, "condensed_fallback", condensed_fallback ? 1.0 : 0.0);
  return s;
}

void PenaltyDetails::add(const PenaltyDetails& later) {
  const PenaltyDetails work = *this;
  *this = later;
  active_set_passes += work.active_set_passes;
  penalty_stages += work.penalty_stages;
}

std::string PenaltyDetails::brief() const {
  std::string s;
  add_field(s, "active_set_passes", active_set_passes);
  add_field(s, "penalty_stages", penalty_stages);
  return s;
}

std::string BackendDetails::brief() const {
  return std::visit(
      [](const auto& d) -> std::string {
        if constexpr (std::is_same_v<std::decay_t<decltype(d)>, std::monostate>)
          return "";
        else
          return d.brief();
      },
      details_);
}

void BackendDetails::add(const BackendDetails& later) {
  // A solve that measured nothing (no free dofs, a failed start) counts as its backend's zeros.
  const bool later_none = std::holds_alternative<std::monostate>(later.details_);
  const bool merged = std::visit(
      [&later, later_none](auto& mine) {
        using T = std::decay_t<decltype(mine)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return false;
        } else {
          if (const T* same = std::get_if<T>(&later.details_)) {
            mine.add(*same);
            return true;
          }
          if (later_none) mine.add(T{});
          return later_none;
        }
      },
      details_);
  if (!merged) details_ = later.details_;
}

}  // namespace roller
