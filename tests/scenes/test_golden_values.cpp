// Golden values: the roller's centre and force at every step of the validation and thesis scenes
// at refine 1, both backends, against tests/golden/*.csv (written by scripts/update_golden.sh).
// Both backends agreeing is not enough: a change that moves the physics of both together (the
// gap, the material, the dynamics) passes every agreement test and fails here.
//
// Tolerances: forces within 1e-6 of the scene's peak force, the centre within 1e-6 mm. The same
// algorithm reproduces its answer far closer than that (round-off differences between machines,
// BLAS, stay well inside); a real change does not: a Young's modulus 0.1 % off fails (the last
// test case). This is a regression check, not an accuracy bound: an answer's distance from the
// exact discrete solution is set by the backend's tolerances and can be larger. Hertz with ipopt,
// step 2: 2e-6 of the peak force from the solution at contact.ipopt.tol = 1e-12, because Ipopt's
// complementarity (F_N g <= tol F_ref) lets candidates near the contact edge keep small forces;
// a change of the working set moves it (docs/benchmarks-log.md, "A smaller working set for the
// contact NLP").
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"

using namespace roller;

namespace {

struct RollerRow {
  int step = 0;
  Vec2 centre = Vec2::Zero();
  Vec2 force = Vec2::Zero();
};

std::vector<RollerRow> read_golden(const std::string& name) {
  const std::string path = std::string(ROLLER_SOURCE_DIR) + "/tests/golden/" + name + ".csv";
  std::ifstream in(path);
  REQUIRE(in.good());
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "step,xc,yc,fx,fy");
  std::vector<RollerRow> rows;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    RollerRow r;
    char comma = 0;
    s >> r.step >> comma >> r.centre.x() >> comma >> r.centre.y() >> comma >> r.force.x() >> comma >> r.force.y();
    REQUIRE(!s.fail());
    rows.push_back(r);
  }
  return rows;
}

// Runs the scene step by step, recording what roller.csv records.
std::vector<RollerRow> run(const std::string& scene, const std::string& backend,
                           std::vector<SceneOverride> overrides = {}) {
  overrides.push_back({"contact.backend", "\"" + backend + "\""});
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/" + scene + ".toml", overrides));
  std::vector<RollerRow> rows{{0, sim.state().pose.centre, force_on_roller(sim.state().contact)}};
  for (int step = 1; step <= sim.scene().steps.n_steps; ++step) {
    REQUIRE(sim.advance_step(step).converged());
    rows.push_back({step, sim.state().pose.centre, force_on_roller(sim.state().contact)});
  }
  return rows;
}

// The largest deviation from the golden rows, as a fraction of its tolerance (<= 1: agrees).
Real worst_deviation(const std::vector<RollerRow>& golden, const std::vector<RollerRow>& got) {
  REQUIRE(got.size() == golden.size());
  Real peak = 0.0;
  for (const auto& g : golden) peak = std::max(peak, g.force.norm());
  const Real force_tol = 1e-6 * peak, centre_tol = 1e-6;
  Real worst = 0.0;
  for (std::size_t k = 0; k < golden.size(); ++k) {
    REQUIRE(got[k].step == golden[k].step);
    worst = std::max(worst, (got[k].force - golden[k].force).lpNorm<Eigen::Infinity>() / force_tol);
    worst = std::max(worst, (got[k].centre - golden[k].centre).lpNorm<Eigen::Infinity>() / centre_tol);
  }
  return worst;
}

}  // namespace

TEST_CASE("golden values: roller centre and force per step of every scene at refine 1, both backends",
          "[scenes][golden][slow]") {
  const std::string backend = GENERATE("ipopt", "penalty");
  for (const char* scene :
       {"hertz", "cattaneo", "z1_outf05", "z1_outf10", "z2_infini", "z2_large", "z3_data01", "z4_v25"}) {
    SECTION(scene) {
      INFO(scene << " with " << backend);
      CHECK(worst_deviation(read_golden(std::string(scene) + "_" + backend), run(scene, backend)) <= 1.0);
    }
  }
}

TEST_CASE("golden values: the comparison sees a Young's modulus 0.1 % off", "[scenes][golden]") {
  const std::vector<RollerRow> golden = read_golden("hertz_ipopt");
  CHECK(worst_deviation(golden, run("hertz", "ipopt")) <= 1.0);
  CHECK(worst_deviation(golden, run("hertz", "ipopt", {{"material.E", "2.1021e5"}})) > 100.0);
}
