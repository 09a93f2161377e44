// libFuzzer harness for the scenario reader: the bytes are a scenario file,
// read by load_scenarios() exactly as `coupler check` reads one (size and
// regular-file checks, JSON text limits, duplicate keys, "include" files,
// "variants", then every key of parse_scenario). A bad scenario must end in
// dfc::UserError (ConfigError, JsonTextError are kinds of it), the documented
// way the reader refuses input; any other exception escapes and aborts, which
// libFuzzer reports as a crash.
//
// The input is written to scenario.json in a private folder made once per
// process, beside a few files it may include (a valid object, an array, a file
// that is not JSON, one that includes the scenario itself: a cycle) and a bin/
// folder holding executable stand-ins for the project's servers, so that
// "program": "dem_server" resolves and the reader goes on past it. Nothing is
// ever started: reading a scenario does not run its programs.
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "dfc/common/errors.hpp"
#include "dfc/coupler/scenario.hpp"

namespace {

namespace fs = std::filesystem;

[[noreturn]] void broken(const std::string& promise) {
  std::fprintf(stderr, "scenario_fuzzer: broken promise: %s\n", promise.c_str());
  __builtin_trap();
}

void write_file(const fs::path& path, std::string_view text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), std::streamsize(text.size()));
  if (!out) broken("cannot write " + path.string());
}

/// The private folder: made on first use, removed at exit (a crash leaves it, under TMPDIR).
/// Held by a pointer that is never freed, so that it outlives the exit handler that removes it.
const fs::path& workspace() {
  static const fs::path* const folder = [] {
    std::string pattern = (fs::temp_directory_path() / "dfc-scenario-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) broken("cannot make a folder under " + fs::temp_directory_path().string());
    const fs::path dir = pattern;
    // Includes the seed corpus names: the shipped scenarios' material files (stand-ins: any object will do,
    // the coupler passes participant sections on unread), and files for the reader's refusals.
    write_file(dir / "materials" / "soft_rock_softbond.json", R"({"contact": {"law": "softbond"}, "density_kg_m3": 2000})");
    write_file(dir / "materials" / "chalk_damagebond.json", R"({"contact": {"law": "damagebond"}, "density_kg_m3": 1800})");
    write_file(dir / "materials" / "cycle.json", R"({"include": "../scenario.json", "k": 1})");
    write_file(dir / "base.json",
               R"({"schema_version": 1, "name": "base", "participants": {"continuum": {"program": "fdm_server", "config": {}}}, "run": {"exchanges": 2}})");
    write_file(dir / "list.json", "[1, 2, 3]");
    write_file(dir / "broken.json", "{\"a\": ");
    for (const char* program : {"dem_server", "fdm_server", "rigid_continuum_server", "elastic_reference_server"}) {
      write_file(dir / "bin" / program, "#!/bin/sh\nexit 1\n");
      fs::permissions(dir / "bin" / program, fs::perms::owner_all);
    }
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(workspace(), ec);
    });
    return new fs::path(dir);
  }();
  return *folder;
}

/// DFC_FUZZ_TRACE=1: what the reader made of each input, to read what a crash input does.
void trace(const std::string& outcome) {
  static const bool on = std::getenv("DFC_FUZZ_TRACE") != nullptr;
  if (on) std::fprintf(stderr, "scenario_fuzzer: %s\n", outcome.c_str());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path& dir = workspace();
  const fs::path scenario = dir / "scenario.json";
  write_file(scenario, std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    const auto scenarios = dfc::coupler::load_scenarios(scenario, dir / "bin");
    // What `coupler run` relies on from a scenario that passed.
    if (scenarios.empty()) broken("load_scenarios returns at least one run");
    for (const auto& s : scenarios) {
      if (!dfc::coupler::is_single_folder_name(s.name)) broken("a scenario's name is one folder name");
      if (s.participants.empty()) broken("a scenario has a participant");
      if (s.coupling.exchange_interval < 1 || s.coupling.continuum_steps_per_exchange < 1) broken("steps per exchange are >= 1");
      if (s.run.exchanges < 1) broken("run.exchanges >= 1");
    }
    trace("OK: " + std::to_string(scenarios.size()) + " run(s)");
  } catch (const dfc::UserError& e) {
    // The documented refusal (ConfigError, JsonTextError and the file's own UserErrors).
    trace(e.what());
  }
  return 0;
}
