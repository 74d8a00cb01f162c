// problems/uniaxial_ratchet.toml: a one-element block under an asymmetric stress cycle. The
// block is homogeneous, so its strain at each peak is the material point's on the same path
// (plane strain, S_xx = 0, S_yy prescribed), which a Newton on (E_xx, E_yy) integrates here
// independently of the finite-element machinery (docs/validation.md, Hardening laws).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "../support/run_scene.hpp"
#include "roller/material/j2_plasticity.hpp"

using namespace roller;

namespace {

// The block's mean axial strain E_yy at the end of every step (top displacement / height).
std::vector<Real> block_strains(const std::vector<SceneOverride>& overrides,
                                const std::string& name = "uniaxial_ratchet") {
  // Newton to a relative residual of 1e-12, so that the comparison with the point is not limited
  // by the scene's 1e-8 (amplified by E over the plastic tangent in the strain).
  std::vector<SceneOverride> o = overrides;
  o.push_back({"newton.residual_tolerance", "1e-12"});
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + name + ".toml", o));
  const Mesh& mesh = sim.model().mesh();
  std::vector<Real> strains;
  for (int step = 1; step <= sim.scene().total_steps(); ++step) {
    REQUIRE(sim.advance_step(step).converged());
    Real uy = 0.0;
    int n = 0;
    for (Index a = 0; a < mesh.n_nodes(); ++a)
      if (mesh.nodes[a].y() > 0.5) {
        uy += sim.model().total_displacement()(2 * a + 1);
        ++n;
      }
    strains.push_back(uy / n / 1.0);
  }
  return strains;
}

// The same path at a material point: S = [0, s_yy, S_zz, 0] with E_zz = 0, Newton on (E_xx, E_yy).
std::vector<Real> point_strains(const MaterialParams& p, const std::vector<Real>& s_yy) {
  MaterialState state = initial_state(p);
  Real eps_yy = 0.0;
  std::vector<Real> strains;
  for (Real target : s_yy) {
    Vec4 de = Vec4::Zero();
    MaterialUpdate u;
    for (int it = 0; it < 50; ++it) {
      u = update_material(p, de, state);
      const Vec2 r(u.stress(0), u.stress(1) - target);
      if (r.norm() <= 1e-10 * p.yield_stress) break;
      Mat2 j;
      j << u.tangent(0, 0), u.tangent(0, 1), u.tangent(1, 0), u.tangent(1, 1);
      const Vec2 d = j.inverse() * r;
      de(0) -= d(0);
      de(1) -= d(1);
    }
    state = u.trial;
    eps_yy += de(1);
    strains.push_back(eps_yy);
  }
  return strains;
}

// The scene's sigma_yy at the end of every step: force per top node x 2 nodes / 1 mm.
std::vector<Real> scene_stress_history(const Scene& scene) {
  std::vector<Real> s;
  for (int step = 1; step <= scene.total_steps(); ++step) s.push_back(2.0 * scene.loads[0].fy->at_step(step));
  return s;
}

}  // namespace

TEST_CASE("uniaxial_ratchet: the block ratchets like its material point, by the same strain every cycle",
          "[scenes][hardening]") {
  const Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/uniaxial_ratchet.toml");
  const std::vector<Real> fe = block_strains({});
  const std::vector<Real> point = point_strains(scene.material, scene_stress_history(scene));
  REQUIRE(fe.size() == point.size());
  // To 1e-8 of the strain, or of the strain range (~1e-2) where the strain crosses zero.
  for (std::size_t k = 0; k < fe.size(); ++k) CHECK(fe[k] == Approx(point[k]).epsilon(1e-8).margin(1e-10));
  // Strain at the sigma_max peaks (steps 20, 60, ...): every cycle ratchets the same way. In
  // plane strain S_zz still drifts, so the rate settles slowly instead of being constant at once
  // as in uniaxial stress (tests/material/test_hardening_laws.cpp has that closed form).
  std::vector<Real> peaks;
  for (std::size_t k = 19; k < fe.size(); k += 40) peaks.push_back(fe[k]);
  const Real first = peaks[1] - peaks[0];
  INFO("ratchet strain per cycle: first " << first << ", last " << peaks.back() - peaks[peaks.size() - 2]);
  CHECK(first > 1e-4);
  for (std::size_t c = 1; c + 1 < peaks.size(); ++c) {
    const Real rate = peaks[c + 1] - peaks[c];
    CHECK(rate > 0.9 * first);
    CHECK(rate < 1.1 * first);
  }
}

TEST_CASE("uniaxial_ratchet with Prager's linear kinematic hardening closes its loop after the first cycle",
          "[scenes][hardening]") {
  // gamma = 0: the back-stress is linear (Prager, C = 5e4 MPa).
  const std::vector<Real> fe = block_strains({{"material.chaboche_gamma", "[0.0]"}});
  std::vector<Real> peaks;
  for (std::size_t k = 19; k < fe.size(); k += 40) peaks.push_back(fe[k]);
  // The peak strain moves once, by a little (S_zz settles in plane strain), then each cycle's
  // change is at most a tenth of the one before, down to round-off: a closed loop. The
  // Armstrong-Frederick block ratchets by ~1.1e-3 a cycle.
  std::vector<Real> change;
  for (std::size_t c = 0; c + 1 < peaks.size(); ++c) change.push_back(std::abs(peaks[c + 1] - peaks[c]));
  CHECK(change[0] < 1e-5);
  for (std::size_t c = 0; c + 1 < change.size(); ++c) {
    INFO("cycle " << c + 1 << ": change " << change[c] << ", then " << change[c + 1]);
    CHECK(change[c + 1] <= std::max(0.1 * change[c], 1e-14));
  }
}

TEST_CASE("ratchet_rail: the R260 block follows its material point and ratchets less every cycle",
          "[scenes][hardening]") {
  const Scene scene = load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/ratchet_rail.toml");
  REQUIRE(scene.material.n_back_stresses() == 6);
  REQUIRE(scene.material.voce_saturation == -40.0);
  const std::vector<Real> fe = block_strains({}, "ratchet_rail");
  const std::vector<Real> point = point_strains(scene.material, scene_stress_history(scene));
  REQUIRE(fe.size() == point.size());
  for (std::size_t k = 0; k < fe.size(); ++k) CHECK(fe[k] == Approx(point[k]).epsilon(1e-8).margin(1e-10));
  // The slow back-stresses (gamma = 20 and 0.01) take up the mean stress: the strain at the
  // sigma_max peaks grows every cycle, by less each time.
  std::vector<Real> peaks;
  for (std::size_t k = 19; k < fe.size(); k += 40) peaks.push_back(fe[k]);
  for (std::size_t c = 1; c + 1 < peaks.size(); ++c) {
    INFO("cycle " << c + 1 << ": " << peaks[c] - peaks[c - 1] << ", then " << peaks[c + 1] - peaks[c]);
    CHECK(peaks[c + 1] - peaks[c] > 0.0);
    CHECK(peaks[c + 1] - peaks[c] < peaks[c] - peaks[c - 1]);
  }
}
