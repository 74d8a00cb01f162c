#pragma once
// Vectors in JSON/CBOR documents (state files). A vector is stored as a CBOR byte string of its
// doubles (IEEE 754, little-endian): exact, and a copy instead of one JSON value per number (a
// checkpoint of Z3 at refine 4, 67k numbers, took 2.8 ms a step to build as number arrays).
// Number arrays are still read, so small vectors written by hand or by older code load too.
#include <cstdint>
#include <cstring>
#include <vector>

#include <nlohmann/json.hpp>

#include "roller/core/types.hpp"

namespace roller {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "state files store doubles little-endian");

inline nlohmann::json to_list(const Real* data, std::size_t n) {
  std::vector<std::uint8_t> bytes(n * sizeof(Real));
  if (n > 0) std::memcpy(bytes.data(), data, bytes.size());
  return nlohmann::json::binary(std::move(bytes));
}
inline nlohmann::json to_list(const VecX& v) { return to_list(v.data(), static_cast<std::size_t>(v.size())); }
inline nlohmann::json to_list(const std::vector<Real>& v) { return to_list(v.data(), v.size()); }

// The doubles of a byte string written by to_list, or of a number array. A byte string whose
// length is not a whole number of doubles throws nlohmann::json::type_error, which the state
// file's reader reports as a damaged file.
inline std::vector<Real> to_reals(const nlohmann::json& j) {
  if (!j.is_binary()) return j.get<std::vector<Real>>();
  const auto& bytes = j.get_binary();
  if (bytes.size() % sizeof(Real) != 0)
    throw nlohmann::json::type_error::create(302, "a vector's byte string is not a whole number of doubles", &j);
  std::vector<Real> v(bytes.size() / sizeof(Real));
  if (!v.empty()) std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

inline VecX to_vec(const nlohmann::json& j) {
  const std::vector<Real> v = to_reals(j);
  return Eigen::Map<const VecX>(v.data(), static_cast<Index>(v.size()));
}

}  // namespace roller
