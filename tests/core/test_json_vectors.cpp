// Vectors in state files (core/json_vectors.hpp): byte strings of doubles, exact both ways;
// number arrays still read; a byte string that is not whole doubles refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "roller/core/json_vectors.hpp"

using namespace roller;

TEST_CASE("json vectors: doubles survive CBOR exactly as byte strings, arrays still read, bad lengths refused",
          "[io]") {
  const std::vector<Real> v{
      0.1, -1e-300, 3.0e300, std::nextafter(1.0, 2.0), -0.0, std::numeric_limits<Real>::denorm_min()};
  nlohmann::json doc;
  doc["v"] = to_list(v);
  doc["empty"] = to_list(std::vector<Real>{});
  REQUIRE(doc["v"].is_binary());
  const nlohmann::json back = nlohmann::json::from_cbor(nlohmann::json::to_cbor(doc));
  const std::vector<Real> w = to_reals(back.at("v"));
  REQUIRE(w.size() == v.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    CHECK(w[k] == v[k]);
    CHECK(std::signbit(w[k]) == std::signbit(v[k]));
  }
  CHECK(to_reals(back.at("empty")).empty());
  const VecX x = to_vec(back.at("v"));
  CHECK(x.size() == static_cast<Index>(v.size()));
  CHECK(x(3) == v[3]);

  CHECK(to_reals(nlohmann::json::array({1.5, -2.0})) == std::vector<Real>{1.5, -2.0});  // a number array
  nlohmann::json truncated = to_list(v);
  truncated.get_binary().pop_back();
  CHECK_THROWS_AS(to_reals(truncated), nlohmann::json::type_error);
}
