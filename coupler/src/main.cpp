// coupler — runs a virtual-centrifuge scenario: starts the solver servers,
// brokers the DEM–continuum boundary exchange over protocol v1, writes HDF5 +
// XDMF results. See README.md and protocol/SPEC.md.
//
//   coupler run SCENARIO.json [--out DIR] [--no-progress]
//   coupler run --resume DIR [--no-progress]
//   coupler check SCENARIO.json
//   coupler expand SCENARIO.json
//   coupler schema
//   coupler keys FILE
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <new>
#include <string_view>

#include "dfc/common/declaration.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/sections/scenario_sections.hpp"
#include "dfc/common/version.hpp"
#include "dfc/coupler/coupled_run.hpp"
#include "dfc/coupler/participant.hpp"
#include "dfc/coupler/scenario.hpp"
#include "dfc/protocol/key_file.hpp"
#include "dfc/protocol/message.hpp"

namespace {

namespace fs = std::filesystem;
std::atomic<bool> g_stop_requested{false};

extern "C" void request_stop(int /*signal*/) { g_stop_requested.store(true); }

void print_help() {
  std::cout << "coupler — coupled DEM–FDM virtual-centrifuge runs\n\n"
               "Usage:\n"
               "  coupler run SCENARIO.json [--out DIR] [--no-progress]\n"
               "      Start the servers the scenario names, run it, write DIR/results.h5 (+ .xdmf)\n"
               "      (DIR defaults to the scenario's output.directory, else results/<name>).\n"
               "  coupler run --resume DIR [SCENARIO.json] [--no-progress]\n"
               "      Continue the run in DIR from its last checkpoint (run.checkpoint_every, or the one\n"
               "      a Ctrl-C writes) into the same results file; the scenario is DIR/scenario.json\n"
               "      (a SCENARIO.json given must equal it). See docs/checkpoints.md.\n"
               "  coupler check SCENARIO.json\n"
               "      Validate the scenario: the top level here, each participant's section by\n"
               "      starting its server and configuring it. Runs no step.\n"
               "  coupler expand SCENARIO.json\n"
               "      Print the scenario as the coupler reads it (includes resolved, one entry per variant), as JSON.\n"
               "  coupler schema\n"
               "      Print the JSON Schema (draft 2020-12) of scenario files (scenario.schema.json).\n"
               "  coupler keys FILE\n"
               "      Write a fresh key file (mode 0600) for a server started by hand: start it with\n"
               "      DFC_KEY_FILE=FILE and name FILE in the scenario's participants.<slot>.key_file, so that\n"
               "      only holders of FILE can talk to it (protocol/SPEC.md section 2.1). Servers the\n"
               "      coupler starts get keys of their own per run.\n"
               "  coupler --help | --version\n\n"
               "Exit status: 0 success; 1 a server failed or the interface force balance broke\n"
               "(the message names the server; results written so far stay readable);\n"
               "2 bad input (the message names the scenario key); 130 stopped by Ctrl-C\n"
               "(results up to then are written).\n\n"
               "Scenario (JSON, schema_version 1; every object may also \"include\" a file whose keys it extends):\n"
            << dfc::describe_section(dfc::sections::scenario())
            << "See README.md (Scenarios), scenarios/*.json and, for each server's config, dem_server --help and fdm_server --help.\n";
}

fs::path own_bin_dir() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : self.parent_path();
}

int run_command(int argc, char** argv) {
  if (argc < 2) {
    print_help();
    return 2;
  }
  const std::string_view command = argv[1];
  if (command == "--help" || command == "-h" || command == "help") {
    print_help();
    return 0;
  }
  if (command == "--version") {
    std::cout << "coupler " << dfc::project_version() << " (protocol " << dfc::protocol::version_string() << ")\n";
    return 0;
  }
  if (command == "schema") {
    std::cout << dfc::sections::scenario_schema().dump(2) << "\n";
    return 0;
  }
  if (command == "keys") {
    if (argc != 3 || argv[2][0] == '\0') throw dfc::UserError("coupler keys takes the path of the key file to write (coupler keys FILE)");
    std::error_code ec;
    if (fs::symlink_status(argv[2], ec).type() != fs::file_type::not_found)
      throw dfc::UserError(std::string("'") + argv[2] + "' exists; servers started with it would no longer be reached: remove it first or choose another path");
    dfc::protocol::write_key_file(argv[2], dfc::protocol::authentication::generate_key_pair());
    std::cout << "wrote " << argv[2] << " (mode 0600); start the server with " << dfc::protocol::authentication::kKeyFileVariable << "="
              << argv[2] << " and name the file in participants.<slot>.key_file\n";
    return 0;
  }
  if (command == "expand") {
    if (argc != 3) throw dfc::UserError("coupler expand takes one scenario file (coupler expand SCENARIO.json)");
    nlohmann::json documents = nlohmann::json::array();
    for (const auto& scenario : dfc::coupler::load_scenarios(argv[2], own_bin_dir(), dfc::coupler::ScenarioFileRole::input))
      documents.push_back(scenario.document);
    std::cout << documents.dump(2) << "\n";
    return 0;
  }
  if (command != "run" && command != "check")
    throw dfc::UserError("unknown command '" + std::string(command) + "'; expected 'run', 'check', 'expand', 'schema' or 'keys' (see coupler --help)");
  fs::path scenario_path;
  dfc::coupler::RunOptions options;
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--out") {
      if (i + 1 >= argc || argv[i + 1][0] == '\0') throw dfc::UserError("--out needs a folder for the results");
      options.output_directory = argv[++i];
    } else if (arg == "--resume") {
      if (command != "run") throw dfc::UserError("--resume belongs to 'coupler run' (coupler run --resume DIR)");
      if (i + 1 >= argc || argv[i + 1][0] == '\0') throw dfc::UserError("--resume needs the folder of the run to continue");
      options.output_directory = argv[++i];
      options.resume = true;
    } else if (arg == "--no-progress") {
      options.progress = false;
    } else if (arg == "--help" || arg == "-h") {  // `coupler run --help` (and `./vc run --help`) as users type it
      print_help();
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      throw dfc::UserError("unknown option '" + std::string(arg) + "' (see coupler --help)");
    } else if (scenario_path.empty()) {
      scenario_path = arg;
    } else {
      throw dfc::UserError("more than one scenario given ('" + scenario_path.string() + "' and '" + std::string(arg) + "')");
    }
  }
  if (options.resume && scenario_path.empty()) scenario_path = options.output_directory / "scenario.json";
  if (scenario_path.empty()) throw dfc::UserError("no scenario file given (coupler " + std::string(command) + " SCENARIO.json)");
  // A resumed run writes into its own folder, where its scenario copy is: that is no clash.
  if (command == "run" && options.output_directory != fs::path() && !options.resume)
    if (const auto problem = dfc::coupler::output_directory_problem(options.output_directory, scenario_path))
      throw dfc::UserError("--out " + *problem);

  // Resuming reads the run's own record (DIR/scenario.json unless a copy is given).
  const auto scenarios = dfc::coupler::load_scenarios(
      scenario_path, own_bin_dir(), options.resume ? dfc::coupler::ScenarioFileRole::run_record : dfc::coupler::ScenarioFileRole::input);
  const bool variants = !scenarios.front().variant_label.empty();
  if (options.resume && variants)
    throw dfc::UserError("--resume continues one run; '" + scenario_path.string() + "' has variants: resume each variant's folder (DIR/<label>)");
  if (command == "check") {
    for (const auto& scenario : scenarios) {
      std::cout << "Checking " << scenario_path.string() << (variants ? " (" + scenario.name + ")" : std::string()) << " ...\n";
      dfc::coupler::check_scenario(scenario, std::cout);
    }
    std::cout << scenario_path.string() << ": OK" << (variants ? " (" + std::to_string(scenarios.size()) + " variants)" : std::string()) << "\n";
    return 0;
  }
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  std::signal(SIGPIPE, SIG_IGN);
  options.stop_requested = &g_stop_requested;
  const fs::path out_override = options.output_directory;
  for (std::size_t k = 0; k < scenarios.size(); ++k) {
    const auto& scenario = scenarios[k];
    if (variants) {
      std::cout << "=== Variant " << k + 1 << "/" << scenarios.size() << ": " << scenario.name << "\n";
      if (!out_override.empty()) options.output_directory = out_override / scenario.variant_label;
    }
    const int status = dfc::coupler::run_scenario(scenario, options, std::cout, std::cerr);
    if (status != 0) return status;
  }
  if (variants) {
    const fs::path parent = scenarios.front().output_directory.parent_path();
    const fs::path folder = out_override.empty() ? parent : out_override;
    std::cout << "All " << scenarios.size() << " variants done. Overlay plots: tools/plot_results.py " << (folder / "*" / "results.h5").string()
              << " --out " << folder.string() << "\n";
  }
  return 0;
}

/// The servers' OpenMP threads idle between advances while the coupler and
/// the other server work. libgomp's default lets them spin there for up to
/// 300 000 iterations, which takes the cores the others need: with a two-core
/// job beside it, the demo pile's exchange took 19 ms spinning against 5 ms
/// sleeping (bench/exchange_overhead.sh, docs/exchange_cost.md). Sleeping costs
/// ~10-20 % on an idle machine. Set before any thread or server starts; a
/// user's own OMP_WAIT_POLICY or GOMP_SPINCOUNT is kept.
void let_idle_server_threads_sleep() {
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr) ::setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    let_idle_server_threads_sleep();
    return run_command(argc, argv);
  } catch (const dfc::ConfigError& e) {
    std::cerr << "coupler: scenario error at " << (e.key_path().empty() ? "(top level)" : e.key_path()) << ": " << e.reason() << "\n";
    return 2;
  } catch (const dfc::UserError& e) {
    std::cerr << "coupler: " << e.what() << "\n";
    return 2;
  } catch (const dfc::coupler::ParticipantFailure& e) {
    std::cerr << "coupler: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "coupler: out of memory: the scenario needs more memory than this machine has; make the model smaller (fewer particles "
                 "or zones) or run it on a larger machine\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "coupler: internal error: " << e.what() << "\n";
    return 1;
  }
}
