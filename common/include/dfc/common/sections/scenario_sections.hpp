#pragma once
// Declarations of the coupler's part of a scenario file (declaration.hpp):
// the top level, gravity, participants, coupling, run, output and variants,
// read by coupler/src/scenario.cpp, and the whole-scenario JSON Schema
// (scenario.schema.json) that joins them with each server's section.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "dfc/common/declaration.hpp"

namespace dfc::sections {

/// The scenario file's top level.
[[nodiscard]] const SectionDeclaration& scenario();
[[nodiscard]] const SectionDeclaration& scenario_gravity();
[[nodiscard]] const SectionDeclaration& scenario_participants();
/// One participant: a server the coupler starts (program) or connects to (endpoint).
[[nodiscard]] const SectionDeclaration& scenario_participant();
[[nodiscard]] const SectionDeclaration& scenario_coupling();
[[nodiscard]] const SectionDeclaration& scenario_run();
[[nodiscard]] const SectionDeclaration& scenario_stop_when();
[[nodiscard]] const SectionDeclaration& scenario_output();
[[nodiscard]] const SectionDeclaration& scenario_variant();

/// The scenario file format this coupler reads ("schema_version").
inline constexpr int kScenarioSchemaVersion = 1;

/// Most solver steps one exchange may ask of a server (protocol/SPEC.md §4,
/// dfc::protocol::kMaxStepsPerAdvance, checked equal where the coupler reads it).
inline constexpr std::int64_t kMaxStepsPerExchange = 1'000'000'000;

/// The JSON Schema (draft 2020-12) of a whole scenario: the coupler's keys
/// and, under participants.<slot>.config, the section of the server the
/// participant's program names (fdm_server, dem_server).
[[nodiscard]] nlohmann::json scenario_schema();

}  // namespace dfc::sections
