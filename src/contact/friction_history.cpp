#include "roller/contact/friction_history.hpp"

namespace roller {

void FrictionHistory::seed(std::vector<ContactCandidate>& candidates) const {
  for (auto& c : candidates) {
    const auto h = nodes_.find(c.node);
    if (h == nodes_.end()) continue;
    c.tangential_force = h->second.tangential_force;
    c.normal_force_guess = h->second.normal_force;
  }
}

void FrictionHistory::record(const std::vector<ContactCandidate>& candidates, const std::vector<NodeContact>& contact) {
  nodes_.clear();
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (contact[i].status != ContactStatus::Open) nodes_[candidates[i].node] = contact[i];
}

void seed_normal_forces(std::vector<ContactCandidate>& candidates, const std::vector<ContactCandidate>& last,
                        const std::vector<NodeContact>& contact) {
  std::map<Index, Real> normal;
  for (std::size_t i = 0; i < last.size() && i < contact.size(); ++i)
    normal[last[i].node] = contact[i].status == ContactStatus::Open ? 0.0 : contact[i].normal_force;
  for (auto& c : candidates) {
    const auto f = normal.find(c.node);
    if (f != normal.end()) c.normal_force_guess = f->second;
  }
}

nlohmann::json FrictionHistory::save() const {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [node, c] : nodes_)
    list.push_back({node, c.normal_force, c.tangential_force, c.gap, c.slip, static_cast<int>(c.status)});
  return list;
}

void FrictionHistory::load(const nlohmann::json& list) {
  nodes_.clear();
  for (const auto& f : list) {
    NodeContact c;
    c.normal_force = f.at(1).get<Real>();
    c.tangential_force = f.at(2).get<Real>();
    c.gap = f.at(3).get<Real>();
    c.slip = f.at(4).get<Real>();
    c.status = static_cast<ContactStatus>(f.at(5).get<int>());
    nodes_[f.at(0).get<Index>()] = c;
  }
}

}  // namespace roller
