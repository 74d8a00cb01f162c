#include "roller/contact/contact_records.hpp"

#include "roller/core/error.hpp"

namespace roller {

std::vector<NodeContactRecord> contact_records(const IncrementSolution& solution, const Vec2& centre) {
  ROLLER_ASSERT(solution.contact.contact.size() == solution.candidates.size(), "one contact result per candidate");
  std::vector<NodeContactRecord> records;
  for (std::size_t i = 0; i < solution.candidates.size(); ++i) {
    const ContactCandidate& c = solution.candidates[i];
    const NodeContact& nc = solution.contact.contact[i];
    NodeContactRecord rec;
    rec.node = c.node;
    rec.position = c.position + Vec2(solution.u(2 * c.node), solution.u(2 * c.node + 1));
    rec.contact = nc;
    rec.tributary_length = c.tributary_length;
    rec.element_size = c.element_size;
    rec.force = contact_force(nc.normal_force, nc.tangential_force, (rec.position - centre).normalized(), c.tangent);
    records.push_back(rec);
  }
  return records;
}

}  // namespace roller
