#include "roller/contact/contact_options.hpp"

#include <fmt/format.h>

namespace roller {

bool PenaltyOptions::is_valid(std::string* why) const {
  if (!(factor > 0.0)) {
    if (why) *why = fmt::format("contact.penalty.factor = {}: must be > 0", factor);
    return false;
  }
  if (!(tangential_factor > 0.0)) {
    if (why) *why = fmt::format("contact.penalty.tangential_factor = {}: must be > 0", tangential_factor);
    return false;
  }
  return true;
}

bool IpoptOptions::is_valid(std::string* why) const {
  auto bad = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!(tol > 0.0 && tol < 1.0)) return bad(fmt::format("contact.ipopt.tol = {}: must be in (0, 1)", tol));
  if (max_iter < 1) return bad(fmt::format("contact.ipopt.max_iter = {}: must be >= 1", max_iter));
  if (print_level < 0 || print_level > 12)
    return bad(fmt::format("contact.ipopt.print_level = {}: expected 0..12", print_level));
  if (!(regularization > 0.0))
    return bad(fmt::format("contact.ipopt.regularization = {}: must be > 0", regularization));
  if (!(fixed_point_tol > 0.0))
    return bad(fmt::format("contact.ipopt.fixed_point_tol = {}: must be > 0", fixed_point_tol));
  if (fixed_point_max < 1) return bad(fmt::format("contact.ipopt.fixed_point_max = {}: must be >= 1", fixed_point_max));
  for (const RawIpoptOption& r : raw)
    if (r.name == "linear_solver")
      return bad(
          fmt::format("contact.ipopt.options.linear_solver = {}: roller chooses Ipopt's linear solver per NLP; "
                      "use contact.ipopt.kkt_solver = \"auto\", \"dense\" or \"mumps\"",
                      r.text));
  return true;
}

bool ContactOptions::is_valid(std::string* why) const {
  if (!(friction >= 0.0 && friction <= 10.0)) {
    if (why) *why = fmt::format("contact.friction = {}: expected 0 <= mu <= 10", friction);
    return false;
  }
  return penalty.is_valid(why) && ipopt.is_valid(why);
}

}  // namespace roller
