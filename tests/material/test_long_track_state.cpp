// material/long_track_state.hpp against the closed form of a plastic strain uniform along x on a
// base held in x and y: sigma_xx = -E (ep_xx + nu ep_zz) / (1 - nu^2), sigma_zz = nu sigma_xx - E ep_zz.
#include <catch2/catch.hpp>

#include "roller/material/long_track_state.hpp"

using namespace roller;

namespace {

// Hooke's law in plane strain on the material update's strains [xx, yy, zz, 2xy].
Vec4 hooke(const MaterialParams& m, const Vec4& elastic_strain) {
  const Real lambda = m.lame_lambda(), g = m.shear_modulus();
  const Real trace = elastic_strain(0) + elastic_strain(1) + elastic_strain(2);
  Vec4 s = 2.0 * g * elastic_strain;
  s(3) = g * elastic_strain(3);
  s.head<3>().array() += lambda * trace;
  return s;
}

}  // namespace

TEST_CASE("long track state: a finite strip's state with the plastic strain of a long track's", "[material]") {
  const MaterialParams m;                                // E = 210000 MPa, nu = 0.3
  const Vec4 plastic(1.3e-3, -0.4e-3, -0.9e-3, 0.7e-3);  // deviatoric: xx + yy + zz = 0
  // The finite strip's total strain: an xx part its ends left, a zz part of B-bar, any yy and shear.
  const Vec4 total(2.1e-4, -0.6e-3, 0.3e-4, 0.95e-3);
  MaterialState leaving;
  leaving.stress = hooke(m, total - plastic);
  leaving.eq_plastic_strain = 2.2e-3;
  leaving.plastic_work = 1.5;
  leaving.yield_stress = 900.0;
  leaving.back_stress[0] = Vec4(10.0, -4.0, -6.0, 3.0);

  const LongTrackState track = long_track_state(leaving, total, m);
  const MaterialState& s = track.state;
  const Real e = m.youngs_modulus, nu = m.poisson_ratio;
  const Real sxx = -e * (plastic(0) + nu * plastic(2)) / (1.0 - nu * nu);
  CHECK(s.stress(0) == Approx(sxx).epsilon(1e-12));
  CHECK(s.stress(2) == Approx(nu * sxx - e * plastic(2)).epsilon(1e-12));
  CHECK(s.stress(1) == 0.0);
  CHECK(s.stress(3) == 0.0);
  CHECK(s.eq_plastic_strain == leaving.eq_plastic_strain);
  CHECK(s.plastic_work == leaving.plastic_work);
  CHECK(s.yield_stress == leaving.yield_stress);
  CHECK(s.back_stress[0] == leaving.back_stress[0]);
  // The long track's strain of the pass: no xx or zz part, the plastic shear, and in yy the
  // plastic strain with the elastic strain of the long track's stress.
  CHECK(std::abs(track.pass_strain(0)) <= 1e-18);
  CHECK(std::abs(track.pass_strain(2)) <= 1e-18);
  CHECK(track.pass_strain(3) == Approx(plastic(3)).epsilon(1e-12));
  CHECK(track.pass_strain(1) == Approx(plastic(1) - nu * (s.stress(0) + s.stress(2)) / e).epsilon(1e-12));

  // A state that is already a long track's stays as it is.
  const MaterialState again = long_track_state(s, Vec4::Zero(), m).state;
  CHECK((again.stress - s.stress).cwiseAbs().maxCoeff() <= 1e-12 * std::abs(sxx));
}
