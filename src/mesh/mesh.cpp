#include "roller/mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "roller/core/error.hpp"

namespace roller {
namespace {

// Plain Levenshtein distance: node-set names are short, so the quadratic cost is irrelevant.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

// The closest known name, if it is close enough to be a plausible typo.
std::string suggestion(const std::string& name, const std::map<std::string, std::vector<Index>>& sets) {
  constexpr std::size_t max_typo_distance = 2;
  std::string best;
  std::size_t best_distance = max_typo_distance + 1;
  for (const auto& [known, nodes] : sets) {
    const std::size_t distance = edit_distance(name, known);
    if (distance < best_distance) {
      best = known;
      best_distance = distance;
    }
  }
  return best;
}

std::string known_names(const std::map<std::string, std::vector<Index>>& sets) {
  std::string names;
  for (const auto& [known, nodes] : sets) {
    if (!names.empty()) names += ", ";
    names += known;
  }
  return names.empty() ? "(none)" : names;
}

}  // namespace

const std::vector<Index>& Mesh::node_set(const std::string& name) const {
  const auto found = node_sets.find(name);
  if (found != node_sets.end()) return found->second;
  std::string message = "unknown mesh node set '" + name + "'";
  const std::string guess = suggestion(name, node_sets);
  if (!guess.empty()) message += " (did you mean '" + guess + "'?)";
  message += "; known node sets: " + known_names(node_sets);
  throw InputError(message);
}

std::vector<Index> node_masters(const Mesh& mesh) {
  std::vector<Index> masters(static_cast<std::size_t>(mesh.n_nodes()));
  for (Index a = 0; a < mesh.n_nodes(); ++a) masters[a] = a;
  if (mesh.period <= 0.0) return masters;
  const std::vector<Index>& left = mesh.node_set("left");
  const std::vector<Index>& right = mesh.node_set("right");
  ROLLER_ASSERT(left.size() == right.size(), "a periodic mesh's two edges have as many nodes");
  for (std::size_t k = 0; k < right.size(); ++k) masters[right[k]] = left[k];
  return masters;
}

Vec2 element_centroid(const Mesh& mesh, Index e) {
  Vec2 c = Vec2::Zero();
  for (Index a : mesh.elements[e]) c += mesh.nodes[a];
  return c / static_cast<Real>(mesh.elements[e].size());
}

Real nearest_image_x(const Mesh& mesh, Real x, Real near) {
  if (mesh.period <= 0.0) return x;
  return x + mesh.period * std::round((near - x) / mesh.period);
}

}  // namespace roller
