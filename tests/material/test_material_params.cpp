#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "roller/material/material_params.hpp"

using roller::MaterialParams;

namespace {

MaterialParams plastic_steel() {
  MaterialParams p;
  p.plastic = true;
  p.yield_stress = 50.0;
  p.tangent_modulus = 0.07 * p.youngs_modulus;
  return p;
}

std::string violation(const MaterialParams& p) {
  std::string why = "not cleared";
  CHECK_FALSE(p.is_valid(&why));
  return why;
}

}  // namespace

TEST_CASE("derived elastic moduli follow from E and nu", "[material]") {
  MaterialParams p;
  p.youngs_modulus = 2.1e5;
  p.poisson_ratio = 0.3;
  CHECK(p.shear_modulus() == Approx(2.1e5 / 2.6).epsilon(1e-14));
  CHECK(p.bulk_modulus() == Approx(2.1e5 / 1.2).epsilon(1e-14));
  CHECK(p.lame_lambda() == Approx(2.1e5 * 0.3 / (1.3 * 0.4)).epsilon(1e-14));
  // lambda + 2/3 G = K
  CHECK(p.lame_lambda() + 2.0 / 3.0 * p.shear_modulus() == Approx(p.bulk_modulus()).epsilon(1e-14));
}

TEST_CASE("plastic modulus is E E_T / (E - E_T)", "[material]") {
  MaterialParams p;
  p.tangent_modulus = 0.0;
  CHECK(p.plastic_modulus() == 0.0);
  p.tangent_modulus = p.youngs_modulus / 3.0;
  CHECK(p.plastic_modulus() == Approx(p.youngs_modulus / 2.0).epsilon(1e-14));
  p.tangent_modulus = 0.99 * p.youngs_modulus;
  CHECK(p.plastic_modulus() == Approx(99.0 * p.youngs_modulus).epsilon(1e-12));
}

TEST_CASE("default and thesis material parameters are valid and clear the message", "[material]") {
  std::string why = "not cleared";
  CHECK(MaterialParams{}.is_valid(&why));
  CHECK(why.empty());
  CHECK(plastic_steel().is_valid(&why));
  CHECK(why.empty());
  CHECK(plastic_steel().is_valid(nullptr));
  MaterialParams perfect = plastic_steel();
  perfect.tangent_modulus = 0.0;
  CHECK(perfect.is_valid(nullptr));
  // Plastic fields are ignored for an elastic material.
  MaterialParams elastic;
  elastic.yield_stress = -1.0;
  elastic.tangent_modulus = 1e9;
  CHECK(elastic.is_valid(nullptr));
}

TEST_CASE("is_valid names the field, its value and the violated rule", "[material]") {
  SECTION("Poisson ratio 0.5") {
    MaterialParams p;
    p.poisson_ratio = 0.5;
    CHECK(violation(p) == "material.poisson_ratio = 0.5: must satisfy 0 <= nu < 0.5");
  }
  SECTION("negative Poisson ratio") {
    MaterialParams p;
    p.poisson_ratio = -0.1;
    CHECK(violation(p) == "material.poisson_ratio = -0.1: must satisfy 0 <= nu < 0.5");
  }
  SECTION("NaN Poisson ratio") {
    MaterialParams p;
    p.poisson_ratio = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(violation(p), Catch::StartsWith("material.poisson_ratio = nan"));
  }
  SECTION("zero Young's modulus") {
    MaterialParams p;
    p.youngs_modulus = 0.0;
    CHECK_THAT(violation(p), Catch::StartsWith("material.youngs_modulus = 0: must be finite and > 0"));
  }
  SECTION("infinite Young's modulus") {
    MaterialParams p;
    p.youngs_modulus = std::numeric_limits<double>::infinity();
    CHECK_THAT(violation(p), Catch::StartsWith("material.youngs_modulus = inf: must be finite"));
  }
  SECTION("zero yield stress of a plastic material") {
    MaterialParams p = plastic_steel();
    p.yield_stress = 0.0;
    CHECK_THAT(violation(p), Catch::StartsWith("material.yield_stress = 0: must be finite and > 0"));
  }
  SECTION("tangent modulus equal to E") {
    MaterialParams p = plastic_steel();
    p.tangent_modulus = p.youngs_modulus;
    CHECK_THAT(violation(p),
               Catch::StartsWith("material.tangent_modulus = 210000: must satisfy 0 <= E_T < E = 210000"));
  }
  SECTION("negative tangent modulus") {
    MaterialParams p = plastic_steel();
    p.tangent_modulus = -5.0;
    CHECK_THAT(violation(p), Catch::StartsWith("material.tangent_modulus = -5: must satisfy 0 <= E_T"));
  }
  SECTION("negative density") {
    MaterialParams p;
    p.density = -7.8e-9;
    CHECK_THAT(violation(p), Catch::StartsWith("material.density = -7.8e-09: must be finite and >= 0"));
  }
  SECTION("no sub-steps") {
    MaterialParams p;
    p.n_substeps = 0;
    CHECK(violation(p) == "material.n_substeps = 0: must be >= 1");
  }
}
