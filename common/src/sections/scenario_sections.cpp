// The coupler's part of a scenario, declared once (scenario_sections.hpp).
#include "dfc/common/sections/scenario_sections.hpp"

#include "dfc/common/durations.hpp"
#include "dfc/common/json_schema.hpp"
#include "dfc/common/sections/dem_sections.hpp"
#include "dfc/common/sections/continuum_sections.hpp"
#include "dfc/common/sections/fdm_sections.hpp"

namespace dfc::sections {

namespace {

using P = ParameterDeclaration;

// A wait the user sets: positive, bounded so that deadlines never overflow (durations.hpp).
constexpr Bounds kWait{0.0, kLongestWaitSeconds, true};
// Time steps below 1e-12 s are no physical model's (a DEM step of micron
// grains is ~1e-9 s); 1e-300 only made step counts overflow.
constexpr Bounds kTimeStep{1e-12, 1e6};

}  // namespace

const SectionDeclaration& scenario_gravity() {
  static const SectionDeclaration s{
      .name = "scenario.gravity",
      .doc = "the acceleration of the model: g_m_s2 * g_level along direction (the centrifuge's N g); passed to every server",
      .parameters = {P::number("g_m_s2", "m/s2", "Earth's gravity g").at_least(0.0).fallback(9.81),
                     P::number("g_level", "-", "N, the centrifuge's g-level").within(Bounds{0.0, 1e5, true}).fallback(1.0),
                     P::vector3("direction", "-", "direction of gravity (normalised; not zero)").fallback({0.0, 0.0, -1.0})},
  };
  return s;
}

const SectionDeclaration& scenario_participant() {
  static const SectionDeclaration s{
      .name = "scenario.participant",
      .doc = "a solver server: one the coupler starts (program) or a running one (endpoint)",
      .parameters = {P::string("program", "server to start: a built server's name (dem_server, fdm_server, rigid_continuum_server, "
                                          "elastic_reference_server, continuum_server) or a path relative to the scenario file")
                         .optional("endpoint"),
                     P::string("endpoint", "ZeroMQ endpoint of a running server, e.g. tcp://127.0.0.1:5555").optional("program"),
                     P::string("key_file", "with endpoint: the key file the running server was started with (its DFC_KEY_FILE; "
                                           "'coupler keys FILE' writes one), relative to the scenario file; the coupler makes the keys "
                                           "of the servers it starts itself (protocol/SPEC.md §2.1)")
                         .optional("connect without authentication"),
                     P::strings("args", "extra command-line arguments of the program").optional("none"),
                     P::integer("mpi_ranks", "the DEM (program dem_server) decomposed over this many MPI processes, started by "
                                             "mpi_launcher; the same bits for any number (docs/determinism.md §3)")
                         .integer_within(1)
                         .fallback(1),
                     P::strings("mpi_launcher", "with mpi_ranks above 1: the command that starts the processes, before '-n N' and the "
                                                "program (e.g. [\"srun\"] on a SLURM cluster, [\"mpiexec\"] for MPICH)")
                         .optional("[\"mpiexec\", \"--oversubscribe\"] (OpenMPI, from PATH)"),
                     P::any_object("config", "the server's section (dem_server --help, fdm_server --help, continuum_server --help); gravity comes from the top level")},
  };
  return s;
}

const SectionDeclaration& scenario_participants() {
  static const SectionDeclaration s{
      .name = "scenario.participants",
      .doc = "the solvers: a DEM, a continuum, or both (coupled)",
      .parameters = {P::object("dem", scenario_participant()).optional("no DEM"),
                     P::object("continuum", scenario_participant()).optional("no continuum")},
  };
  return s;
}

const SectionDeclaration& scenario_coupling() {
  static const SectionDeclaration s{
      .name = "scenario.coupling",
      .doc = "the exchange between DEM and continuum",
      .parameters = {P::integer("exchange_interval", "DEM steps per exchange").integer_within(1, kMaxStepsPerExchange).fallback(1),
                     P::integer("continuum_steps_per_exchange", "continuum steps per exchange").integer_within(1, kMaxStepsPerExchange).fallback(1),
                     P::number("dt_s", "s", "DEM time step").within(kTimeStep).optional("the largest step both servers allow"),
                     P::number("force_balance_tolerance", "-", "largest relative mismatch of the interface forces before the run stops")
                         .within(Bounds{0.0, 1.0, true})
                         .fallback(1e-9),
                     P::string("scheme", "coupling scheme").one_of({"serial"}).fallback("serial")},
  };
  return s;
}

const SectionDeclaration& scenario_stop_when() {
  static const SectionDeclaration s{
      .name = "scenario.stop_when",
      .doc = "stop before run.exchanges once equilibrium or a monitor's threshold is reached",
      .parameters = {P::number("unbalanced_force_ratio", "-", "stop when the servers' unbalanced force ratio falls below this, in (0, 1)")
                         .within(Bounds{0.0, 1.0, true})
                         .optional("no equilibrium criterion"),
                     P::string("monitor", "a time-series column \"<slot>_<monitor>\" of a number monitor, e.g. dem_pile_displacement_m")
                         .optional("no monitor criterion"),
                     P::number("at_least", "", "the monitor's threshold (in the monitor's unit)").optional("needed with monitor"),
                     P::integer("min_exchanges", "exchanges before a criterion may stop the run").integer_within(1).fallback(1)},
  };
  return s;
}

const SectionDeclaration& scenario_run() {
  static const SectionDeclaration s{
      .name = "scenario.run",
      .doc = "how long the run lasts and what it writes",
      .parameters = {P::integer("exchanges", "exchanges (or steps of a single server) to run").integer_within(1),
                     P::number("deadline_s", "s", "longest wait for one reply of a server, even one that answers its heartbeat, before it counts as hung").within(kWait).fallback(60.0),
                     P::number("hang_timeout_s", "s",
                               "a server that answers neither its request nor a heartbeat ping this long is hung, however long deadline_s "
                               "(servers of protocol 1.6 on; SPEC.md §9.1)")
                         .within(kWait)
                         .fallback(10.0),
                     P::number("stall_timeout_s", "s",
                               "a server whose heartbeat answers but whose work counter stands still this long (its main thread "
                               "deadlocked or spinning) is hung, however long deadline_s (servers of protocol 1.8 on; SPEC.md §9.1)")
                         .within(kWait)
                         .fallback(120.0),
                     P::number("startup_timeout_s", "s", "longest wait for a server to start").within(kWait).fallback(20.0),
                     P::integer("snapshot_every", "exchanges between snapshots (0: first and last only)").integer_within(0).fallback(0),
                     P::integer("checkpoint_every", "exchanges between checkpoints for --resume (0: none but on Ctrl-C)").integer_within(0).fallback(0),
                     P::object("stop_when", scenario_stop_when()).optional("run all exchanges")},
  };
  return s;
}

const SectionDeclaration& scenario_output() {
  static const SectionDeclaration s{
      .name = "scenario.output",
      .doc = "where the results go",
      .parameters = {P::string("directory", "folder of results.h5, results.xdmf, scenario.json and logs/ (not the working folder or the "
                                            "scenario's folder)")
                         .optional("results/<name>")},
  };
  return s;
}

const SectionDeclaration& scenario_variant() {
  static const SectionDeclaration s{
      .name = "scenario.variant",
      .doc = "one run of the scenario with `patch` applied as a JSON Merge Patch, named <name>_<label>, results in <output.directory>/<label>",
      .parameters = {P::string("label", "letters, digits, '_', '-' or '.'; names the results folder"),
                     P::any_object("patch", "JSON Merge Patch of the scenario (RFC 7386)")},
  };
  return s;
}

const SectionDeclaration& scenario() {
  static const SectionDeclaration s{
      .name = "scenario",
      .doc = "a virtual-centrifuge scenario (docs/running.md, Scenarios)",
      .parameters = {P::integer("schema_version", "version of this file format (this coupler reads 1)").integer_within(1),
                     P::string("name", "the run's name; results go to results/<name> unless output.directory says otherwise"),
                     P::string("description", "free text").fallback(""),
                     P::object("gravity", scenario_gravity()).optional("no gravity"),
                     P::object("participants", scenario_participants()),
                     P::object("coupling", scenario_coupling()).optional("the coupling section's defaults"),
                     P::object("run", scenario_run()),
                     P::object("output", scenario_output()).optional("results/<name>"),
                     P::objects("variants", scenario_variant()).optional("a single run")},
  };
  return s;
}

nlohmann::json scenario_schema() {
  using nlohmann::json;
  json schema = schema_document(scenario(), "https://github.com/dfc-project/dfc/scenario.schema.json", "dfc scenario");
  json& defs = schema["$defs"];
  // Each server's section under participants.<slot>.config, chosen by the
  // program's name: complete in a complete participant, a patch in one that
  // includes a file or lies in one that does (json_schema.hpp). The coupler
  // sets the servers' gravity itself, so a config must not.
  const auto add_servers = [&](json& participant, bool patch) {
    json server_sections = json::array();
    for (const auto& [program, section] : {std::pair{"fdm_server", &fdm_server()}, std::pair{"dem_server", &dem_server()},
                                                  std::pair{"continuum_server", &continuum_server()}}) {
      defs[section->name] = section_schema(*section, defs);
      const std::string name = patch ? patch_def_name(*section) : section->name;
      server_sections.push_back({{"if", {{"required", {"program"}}, {"properties", {{"program", {{"pattern", std::string("(^|/)") + program + "$"}}}}}}},
                                 {"then", {{"properties", {{"config", {{"$ref", "#/$defs/" + name}}}}}}}});
    }
    participant["allOf"] = server_sections;
    participant["properties"]["config"]["properties"] = {{"gravity_m_s2", false}};
  };
  add_servers(defs[scenario_participant().name]["else"], false);
  add_servers(defs[patch_def_name(scenario_participant())], true);
  // The format version this coupler reads (the declaration bounds it below only,
  // so that the coupler's own message names the version it reads).
  schema["else"]["properties"]["schema_version"]["const"] = kScenarioSchemaVersion;
  defs[patch_def_name(scenario())]["properties"]["schema_version"]["const"] = kScenarioSchemaVersion;
  return schema;
}

}  // namespace dfc::sections
