// The strip's material by depth (material/layered_material.hpp): the yield profile's
// interpolation and ends, the bands from the top, and which layers follow the profile.
#include <catch2/catch.hpp>

#include <string>

#include "roller/material/layered_material.hpp"

using namespace roller;

TEST_CASE("yield profile: linear between its points, constant beyond its ends", "[material][layers]") {
  const YieldProfile p{{{0.2, 1600.0}, {1.0, 1200.0}, {1.5, 800.0}}};
  CHECK(p.at(0.0) == 1600.0);  // above the first point
  CHECK(p.at(0.2) == 1600.0);
  CHECK(p.at(0.6) == Approx(1400.0).epsilon(1e-14));
  CHECK(p.at(1.0) == 1200.0);
  CHECK(p.at(1.25) == Approx(1000.0).epsilon(1e-14));
  CHECK(p.at(1.5) == 800.0);
  CHECK(p.at(7.0) == 800.0);                             // below the last point
  CHECK(YieldProfile{{{0.5, 900.0}}}.at(3.0) == 900.0);  // one point: a constant
}

TEST_CASE("yield profile: depths increasing from 0, yield stresses positive", "[material][layers][errors]") {
  std::string why;
  CHECK(YieldProfile{{{0.0, 900.0}, {1.0, 800.0}}}.is_valid(&why));
  CHECK_FALSE(YieldProfile{{{0.0, 900.0}, {1.0, 800.0}, {1.0, 700.0}}}.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("yield_profile[2]") && Catch::Contains("strictly increasing depths"));
  CHECK_FALSE(YieldProfile{{{0.5, 900.0}, {0.2, 800.0}}}.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("yield_profile[1]: depth 0.2 mm after depth 0.5 mm"));
  CHECK_FALSE(YieldProfile{{{-0.1, 900.0}}}.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("depth >= 0"));
  CHECK_FALSE(YieldProfile{{{0.0, 0.0}}}.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("yield stress 0 MPa"));
}

TEST_CASE("layered material: bands from the top over [material], the profile where no layer overrides it",
          "[material][layers]") {
  MaterialParams core;
  core.plastic = true;
  core.yield_stress = 800.0;
  LayeredMaterial m = LayeredMaterial::uniform(core);
  CHECK(m.is_homogeneous());
  CHECK(m.at_depth(5.0).material.yield_stress == 800.0);
  CHECK(m.at_depth(5.0).layer == 0);

  MaterialLayer coat;
  coat.thickness = 0.1;
  coat.material = core;
  coat.material.youngs_modulus = 3.0e5;
  coat.material.yield_stress = 2000.0;
  coat.follows_profile = false;  // it gave its own yield_stress
  MaterialLayer case_layer;
  case_layer.thickness = 0.9;
  case_layer.material = core;  // follows the profile
  m.layers = {coat, case_layer};
  m.yield_profile = YieldProfile{{{0.0, 1600.0}, {2.0, 800.0}}};
  CHECK(m.boundaries() == std::vector<Real>{0.1, 1.0});
  CHECK(m.at_depth(0.05).layer == 0);
  CHECK(m.at_depth(0.05).material.yield_stress == 2000.0);
  CHECK(m.at_depth(0.05).material.youngs_modulus == 3.0e5);
  CHECK(m.at_depth(0.5).layer == 1);
  CHECK(m.at_depth(0.5).material.yield_stress == Approx(1400.0).epsilon(1e-14));
  CHECK(m.at_depth(1.0).layer == 2);  // on a boundary: the band below
  CHECK(m.at_depth(1.5).material.yield_stress == Approx(1000.0).epsilon(1e-14));
  CHECK(m.at_depth(3.0).material.yield_stress == 800.0);
  CHECK(m.surface().youngs_modulus == 3.0e5);
  CHECK(m.any_plastic());
}
