#pragma once
// Vectors in JSON/CBOR documents (state files): plain number arrays, doubles kept exact.
#include <vector>

#include <nlohmann/json.hpp>

#include "roller/core/types.hpp"

namespace roller {

inline std::vector<Real> to_list(const VecX& v) { return std::vector<Real>(v.data(), v.data() + v.size()); }

inline VecX to_vec(const nlohmann::json& j) {
  const auto v = j.get<std::vector<Real>>();
  return Eigen::Map<const VecX>(v.data(), static_cast<Index>(v.size()));
}

}  // namespace roller
