// Repeated passes: an elastic strip is left as it was found; a plastic three-pass run writes its
// per-pass files and continues from a checkpoint in the middle of a pass to the same bytes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../support/resume_copy.hpp"
#include "../support/run_roller.hpp"
#include "../support/run_scene.hpp"
#include "../support/temp_files.hpp"

using namespace roller;
namespace fs = std::filesystem;

namespace {

// Press 0.05 mm, roll 2 mm with creep, lift 0.25 mm clear: 8 steps per pass.
const std::string kPass =
    "roller.path=[{steps=[1,2], dy=-0.05}, {steps=[3,6], dx=2.0, slip=0.002}, "
    "{steps=[7,8], dy=0.3}]";

SceneOverride override_of(const std::string& text) { return parse_override(text); }

// A column of a CSV file with a header row, row by row.
std::vector<Real> column_values(const std::string& csv, const std::string& column) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::istringstream header(line);
  int index = -1;
  for (std::string name; std::getline(header, name, ',');) {
    ++index;
    if (name == column) break;
  }
  std::vector<Real> values;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (int i = 0; i <= index; ++i) std::getline(row, cell, ',');
    values.push_back(std::stod(cell));
  }
  return values;
}

// The largest |value| of a column of a CSV file with a header row.
Real column_peak(const std::string& csv, const std::string& column) {
  Real peak = 0.0;
  for (const Real v : column_values(csv, column)) peak = std::max(peak, std::abs(v));
  return peak;
}

}  // namespace

TEST_CASE("passes: an elastic strip rolled twice is left without stress or displacement", "[contact][passes]") {
  const Simulation sim =
      test::run_scene("rolling_friction", {override_of(kPass), {"steps.count", "8"}, {"passes.count", "2"}});
  REQUIRE(sim.state().steps_done == 16);
  REQUIRE(sim.state().pass_records.size() == 2);
  // The pass pressed: a peak pressure of a few hundred MPa.
  CHECK(sim.state().pass_records[1].peak_pressure > 100.0);
  Real stress = 0.0;
  for (const MaterialState& s : sim.model().states()) stress = std::max(stress, s.stress.cwiseAbs().maxCoeff());
  CHECK(stress <= 1e-8 * sim.state().pass_records[1].peak_pressure);
  CHECK(sim.model().total_displacement().cwiseAbs().maxCoeff() <= 1e-12);
  CHECK(sim.state().pass_records[1].surface_dux == Approx(0.0).margin(1e-12));
  CHECK(sim.state().pass_records[1].max_plastic_increment == 0.0);
}

TEST_CASE("passes: the second pass over an elastic strip repeats the first from the same start", "[contact][passes]") {
  // The strip is back in its virgin state after pass 1, so pass 2 must meet it exactly as pass 1
  // did: the roller returns to the pass's start before the first step (not to the end of pass 1,
  // from where the first increment would drag it back with a slip of the whole track).
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/rolling_friction.toml",
                            {override_of(kPass), {"steps.count", "8"}, {"passes.count", "2"}}));
  std::vector<Vec2> pass1_force, pass1_centre;
  for (int step = 1; step <= 16; ++step) {
    REQUIRE(sim.advance_step(step).converged());
    if (step <= 8) {
      pass1_force.push_back(force_on_roller(sim.state().contact));
      pass1_centre.push_back(sim.state().pose.centre);
      continue;
    }
    const Vec2& f = pass1_force[step - 9];
    INFO("step " << step);
    CHECK((sim.state().pose.centre - pass1_centre[step - 9]).norm() <= 1e-12);
    CHECK((force_on_roller(sim.state().contact) - f).norm() <= 1e-6 * std::max(1.0, f.norm()));
  }
}

TEST_CASE("passes: a plastic three-pass run writes per-pass files and resumes mid-pass to the same bytes",
          "[contact][passes]") {
  test::TempDir dir("roller_passes");
  const fs::path whole = dir.path() / "whole", split = dir.path() / "split";
  const std::string run =
      "run problems/rolling_friction.toml --set material.yield_stress=600.0 --set "
      "material.tangent_modulus=2100.0 --set steps.count=8 --set passes.count=3 --set "
      "'" +
      kPass +
      "' --set output.save_states=[12] --set output.vtu=false --set fatigue.dang_van_a=0.3 --set "
      "fatigue.dang_van_limit=300.0 --set fatigue.shear_fatigue_limit=300.0 --set fatigue.critical_shear_strain=11.0 "
      "--out ";
  const test::Run r = test::run_roller(run + whole.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("pass  2/3  step   12/24"));
  // One row per pass; one row per element of the column under the track's middle per pass.
  const std::string passes = test::read_text(whole / "passes.csv");
  CHECK(std::count(passes.begin(), passes.end(), '\n') == 1 + 3);
  const std::string depth = test::read_text(whole / "residual_depth.csv");
  const auto depth_rows = std::count(depth.begin(), depth.end(), '\n') - 1;
  CHECK(depth_rows % 3 == 0);
  CHECK(depth_rows >= 3 * 30);  // the strip's 30 rows of elements (mesh ny)
  // The fatigue indices: the same column's depths after every pass, the last pass's answer in
  // summary.json and on the answer line.
  const std::string fatigue = test::read_text(whole / "fatigue.csv");
  CHECK(std::count(fatigue.begin(), fatigue.end(), '\n') - 1 == depth_rows);
  const auto summary = nlohmann::json::parse(test::read_text(whole / "summary.json"));
  CHECK(summary["passes"]["count"] == 3);
  CHECK(summary["fatigue"]["pass"] == 3);
  CHECK(summary["fatigue"]["dang_van_index"].get<double>() > 0.0);
  CHECK(summary["fatigue"]["peak_pressure"].get<double>() > 0.0);
  CHECK_THAT(r.output, Catch::Contains("fatigue of pass 3: Dang Van"));
  // Kapoor's life by hand from passes.csv: gamma_c over the last pass's surface shear.
  const Real surface_shear = column_values(passes, "surface_shear_increment").back();
  REQUIRE(surface_shear != 0.0);
  CHECK(summary["fatigue"]["ratchetting_life"].get<double>() == Approx(11.0 / std::abs(surface_shear)).epsilon(1e-6));
  // Three passes of a hardening strip whose increments still fall: a verdict on the increments
  // (here "still falls ... run more passes"), not the one for too few passes.
  const std::string criterion = summary["passes"]["criterion"].get<std::string>();
  INFO(criterion);
  CHECK_THAT(criterion, Catch::Contains("of pass 1's in pass 3"));
  CHECK_THAT(criterion, !Catch::Contains("at least 3"));
  CHECK(summary["passes"].contains("p0_over_k") == false);  // depth-controlled: no load to measure
  // A finite strip's track: its ends and how far they lie from the window, in summary.json and on the
  // answer's line.
  CHECK(summary["passes"]["track"]["kind"] == "finite");
  CHECK(summary["passes"]["track"]["window_to_end_over_a"].get<double>() == 0.0);  // a track under 4a: its window
  CHECK_THAT(r.output, Catch::Contains("the residual stress is a finite track's") &&
                           Catch::Contains("x = 98 and 100 mm) bound passes.csv's window (x = 98 to 100 mm)"));

  // The run as if killed after step 12 (mid-pass 2).
  const test::Run resumed = test::resume_copy(run, whole, split, 12);
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  CHECK_THAT(resumed.output, Catch::Contains("resuming after step 12"));
  for (const char* f : {"passes.csv", "residual_depth.csv", "fatigue.csv", "roller.csv", "contact.csv"})
    CHECK(test::read_text(split / f) == test::read_text(whole / f));
  const auto resumed_summary = nlohmann::json::parse(test::read_text(split / "summary.json"));
  CHECK(resumed_summary["passes"] == summary["passes"]);
  CHECK(resumed_summary["fatigue"] == summary["fatigue"]);
}

TEST_CASE("a force-loaded roller resumes on the strip to the same bytes", "[contact][passes][force]") {
  // Burnishing: pressed to P in steps 1-3, rolled under P. The joint height solve runs once the
  // roller was on the strip in the previous increment; a resumed run must know that from its
  // checkpoint, or its first increment takes the passes and the answers drift at 1e-6.
  test::TempDir dir("roller_force_resume");
  const fs::path whole = dir.path() / "whole", split = dir.path() / "split";
  const std::string run =
      "run problems/burnishing.toml --steps 8 --set passes.count=1 --set output.save_states=[5] --set output.vtu=false "
      "--out ";
  const test::Run r = test::run_roller(run + whole.string());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  fs::copy(whole, split);
  fs::copy_file(whole / "state_0005.cbor", split / "checkpoint.cbor", fs::copy_options::overwrite_existing);
  const test::Run resumed = test::run_roller(run + split.string() + " --resume");
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  CHECK_THAT(resumed.output, Catch::Contains("resuming after step 5"));
  for (const char* f : {"roller.csv", "contact.csv"}) CHECK(test::read_text(split / f) == test::read_text(whole / f));
}

TEST_CASE("passes: alternating passes run the path mirrored, horizontal forces reversed with it", "[contact][passes]") {
  RollerSpec spec;
  spec.radius = 50.0;
  spec.path.resize(2);
  spec.path[0].first_step = 1;
  spec.path[0].last_step = 2;
  spec.path[0].fy = 400.0;
  spec.path[1].first_step = 3;
  spec.path[1].last_step = 6;
  spec.path[1].dx = 4.0;
  spec.path[1].fx = -30.0;  // the strip holds back a roller driven to +x
  const PassSpec alternate{2, PassDirection::Alternate};
  const RollerProgram program(spec, alternate, 6, Vec2(10.0, 60.0));
  CHECK(program.pass_start(1).centre.x() == 10.0);
  CHECK(program.pose(6.0).centre.x() == Approx(14.0));
  CHECK(program.pass_start(2).centre.x() == Approx(14.0));  // where the first pass's path ends
  CHECK(program.pose(12.0).centre.x() == Approx(10.0));     // and back: dx mirrored
  CHECK(program.force(6.0).fx.value() == -30.0);
  CHECK(program.force(12.0).fx.value() == 30.0);  // now it holds back a roller driven to -x
  CHECK(program.force(8.0).fy.value() == 400.0);
  CHECK(program.pass_of_step(6) == 1);
  CHECK(program.pass_of_step(7) == 2);
  CHECK(program.starts_later_pass(7));
  CHECK_FALSE(program.starts_later_pass(1));
  CHECK(program.ends_pass(12));
  // The driver prescribes what the pass's own path says.
  Simulation sim(load_scene(std::string(ROLLER_SOURCE_DIR) + "/problems/hertz.toml",
                            {{"steps.count", "6"},
                             {"passes.count", "2"},
                             {"passes.direction", "\"alternate\""},
                             {"roller.path", "[{steps=[1,2], fy=400.0}, {steps=[3,6], dx=4.0, fx=-30.0}]"}}));
  CHECK(sim.program().force(6.0).fx.value() == Approx(-30.0));
  CHECK(sim.program().force(12.0).fx.value() == Approx(30.0));
  CHECK(sim.program().force(8.0).fy.value() == Approx(400.0));
}

// The back-stresses are part of the state: an Armstrong-Frederick run resumed mid-pass from its
// checkpoint ends with the same bytes as the run that went through, with either backend (ipopt
// iterates the frozen recovery, penalty runs the unsymmetric Newton; docs/model.md, Hardening laws).
TEST_CASE("passes: an Armstrong-Frederick run resumes mid-pass to the same bytes, back-stresses and all",
          "[contact][passes][hardening][slow]") {
  for (const char* backend : {"ipopt", "penalty"}) {
    SECTION(backend) {
      test::TempDir dir("roller_passes_af");
      const fs::path whole = dir.path() / "whole", split = dir.path() / "split";
      const std::string run =
          std::string("run problems/rolling_friction.toml --contact ") + backend +
          " --set material.yield_stress=600.0 --set material.hardening=\"chaboche\" --set "
          "material.chaboche_C=[3e4,5e3] --set material.chaboche_gamma=[200.0,0.0] --set steps.count=8 --set "
          "passes.count=2 --set '" +
          kPass + "' --set output.save_states=[12] --set output.every=4 --out ";
      const test::Run r = test::run_roller(run + whole.string());
      INFO(r.output);
      REQUIRE(r.exit_code == 0);
      // The back-stresses reach the outputs: non-zero columns under the track, a VTU tensor.
      CHECK(column_peak(test::read_text(whole / "residual_depth.csv"), "back_xx") > 0.0);
      CHECK_THAT(test::read_text(whole / "step_0016.vtu"), Catch::Contains("Name=\"back_stress_1\""));
      const test::Run resumed = test::resume_copy(run, whole, split, 12);
      INFO(resumed.output);
      REQUIRE(resumed.exit_code == 0);
      for (const char* f : {"passes.csv", "residual_depth.csv", "roller.csv", "contact.csv", "step_0016.vtu"})
        CHECK(test::read_text(split / f) == test::read_text(whole / f));
    }
  }
}
