// roller command line: parse, load, run, report. Exit codes: 0 success, 1 a step failed
// (results of completed steps are on disk), 2 bad input, 3 the machine refused (disk full, out
// of memory), 4 an internal error (a bug: please report it).
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <optional>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <signal.h>
#include <unistd.h>

#include "commands.hpp"
#include "roller/core/error.hpp"
#include "roller/core/version.hpp"
#include "roller/driver/simulation.hpp"
#include "roller/io/scene_loader.hpp"
#include "roller/io/scene_warnings.hpp"

namespace {

// SIGINT (Ctrl-C) or SIGTERM: the run stops after the step under way with its files, checkpoint
// and summary.json ("interrupted", exit 128 + signal); the handler is reset, so a second signal
// ends the process at once.
std::atomic<int> stop_signal{0};

extern "C" void request_stop(int signal) {
  stop_signal.store(signal);
  static const char note[] = "\nroller: stopping after the step under way (send the signal again to stop at once)\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, note, sizeof(note) - 1);
}

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

struct RunArgs {
  std::string scene;
  std::string out;
  int refine = 0;
  int steps = 0;
  std::string contact;
  std::string initial_state;
  bool resume = false;
  bool overwrite = false;
  std::vector<std::string> sets;
};

int run_scene(const RunArgs& args) {
  std::vector<roller::SceneOverride> overrides;
  for (const auto& s : args.sets) overrides.push_back(roller::parse_override(s));
  if (args.refine > 0) overrides.push_back({"mesh.refine", std::to_string(args.refine)});
  if (args.steps > 0) overrides.push_back({"steps.count", std::to_string(args.steps)});
  if (!args.contact.empty()) overrides.push_back({"contact.backend", "\"" + args.contact + "\""});
  roller::Scene scene = roller::load_scene(args.scene, overrides);
  if (!args.initial_state.empty()) scene.initial_state = std::filesystem::absolute(args.initial_state);
  roller::RunOptions options;
  options.out_dir = args.out.empty() ? "out/" + scene.name : args.out;
  options.progress = &std::cout;
  options.resume = args.resume;
  options.overwrite = args.overwrite;
  options.stop_signal = &stop_signal;
  const std::string out = options.out_dir.string();
  std::optional<roller::Simulation> built;
  try {
    built.emplace(scene);
  } catch (const std::exception& e) {  // the memory check before the mesh is built, or memory refused
    if (roller::status_of(e) == roller::RunStatus::SystemError)
      roller::write_stopped_summary(scene, options, roller::RunStatus::SystemError, roller::message_of(e));
    throw;
  }
  roller::Simulation& sim = *built;
  std::cout << fmt::format("roller: scene '{}' ({}), {} elements {}, {} dofs ({} free), {} steps -> {}\n",
                           sim.scene().name, sim.scene().title, sim.model().mesh().n_elements(),
                           roller::enum_name(sim.model().mesh().element_type), sim.model().n_dofs(),
                           sim.model().dof_map().n_free(), sim.scene().total_steps(), out);
  for (const std::string& warning : roller::scene_warnings(sim.scene(), sim.model().mesh()))
    std::cerr << "roller: warning: " << warning << "\n";
  install_stop_handlers();
  const roller::RunSummary summary = sim.run(options);
  std::cout << fmt::format("roller: {} in {:.2f} s ({} solver iterations, peak memory {:.0f} MiB); results in {}\n",
                           summary.message, summary.wall_s, summary.totals.iterations, summary.peak_memory_mb, out);
  return roller::exit_code(summary.status, summary.signal);
}

// Exit code 3 without the libraries' exit handlers: out of memory, an OpenBLAS thread may be
// retrying its buffer's mapping for ever, and OpenBLAS's handler would wait for it (a hang seen
// under ulimit -v). Our files are closed by then.
int system_exit() {
  std::cout.flush();
  std::cerr.flush();
  std::_Exit(3);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"roller: finite-element contact of a roller (rigid or elastic) with an elastic-plastic strip"};
  app.require_subcommand(1);
  app.set_version_flag("--version", [] {
    const roller::BuildInfo b = roller::build_info();
    return fmt::format("roller {} (commit {}), Ipopt {}, MUMPS {}", b.version, b.commit, b.ipopt_version,
                       b.mumps_version);
  });

  RunArgs run_args;
  CLI::App* run = app.add_subcommand("run", "run a scene file (see docs/scenes.md)");
  run->add_option("scene", run_args.scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  run->add_option("--out,-o", run_args.out, "output folder (default out/<scene name>)");
  run->add_option("--refine", run_args.refine, "mesh refinement factor (overrides mesh.refine)")
      ->check(CLI::Range(1, 64));
  run->add_option("--steps", run_args.steps,
                  "number of steps to run (overrides steps.count; refused where it would cut a pass of a scene with "
                  "[passes] short: use --set passes.count=N there)")
      ->check(CLI::Range(1, 1000000));
  run->add_option("--contact", run_args.contact, "contact backend (overrides contact.backend)")
      ->check(CLI::IsMember({"penalty", "ipopt"}));
  run->add_flag("--resume", run_args.resume,
                "continue the run in the output folder from its checkpoint.cbor (a killed or shortened run)");
  run->add_flag("--overwrite", run_args.overwrite,
                "run into an output folder that holds other files or another scene's output, removing the run files "
                "in it");
  run->add_option("--initial-state", run_args.initial_state,
                  "start from the strip state saved by another run (overrides restart.from)")
      ->check(CLI::ExistingFile);
  run->add_option("--set", run_args.sets, "override a scene value, e.g. --set material.E=2e5")->type_name("KEY=VALUE");
  const roller::app::Command monotonicity = roller::app::add_monotonicity_command(app);
  const roller::app::Command scene_keys = roller::app::add_scene_keys_command(app);
  const roller::app::Command output_columns = roller::app::add_output_columns_command(app);
  const roller::app::Command shakedown_limit = roller::app::add_shakedown_limit_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end the parse with code 0; every other parse error is bad input,
    // exit code 2 like a bad scene (CLI11's own codes would be 100-115).
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (*run) return run_scene(run_args);
    if (app.got_subcommand("monotonicity")) return monotonicity();
    if (app.got_subcommand("scene-keys")) return scene_keys();
    if (app.got_subcommand("output-columns")) return output_columns();
    if (app.got_subcommand("shakedown-limit")) return shakedown_limit();
  } catch (const roller::InputError& e) {
    std::cerr << "roller: input error: " << e.what() << "\n";
    return 2;
  } catch (const roller::SystemError& e) {
    std::cerr << "roller: system error: " << e.what() << "\n";
    return system_exit();
  } catch (const std::bad_alloc& e) {
    std::cerr << "roller: system error: " << roller::message_of(e) << "\n";
    return system_exit();
  } catch (const std::exception& e) {
    std::cerr << "roller: internal error: " << e.what() << " (please report it with the scene file)\n";
    return 4;
  }
  return 0;
}
