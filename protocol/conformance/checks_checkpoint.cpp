// SPEC.md §4.7 (protocol 1.3): checkpoint and restore. A server with
// capability checkpoint writes its state where it is told and restores it
// only while configured; a missing or damaged file gets BAD_CHECKPOINT and
// changes nothing. A server without it answers both with UNSUPPORTED.
#include <filesystem>
#include <fstream>

#include "check.hpp"
#include "context.hpp"
#include "expectations.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

namespace fs = std::filesystem;

/// A checkpoint file in the checker's own folder, which goes with it (before,
/// a folder of a guessable name in /tmp that a skipped or failed check left behind).
fs::path scratch_file(const Context& context, const std::string& name) { return context.scratch_folder() / name; }

/// checkpoint and restore came with 1.3 (SPEC.md §1): the other checkpoint
/// checks skip an older server, and this one holds it to the older answer.
constexpr int kSinceMinor = 3;

// Without the capability: UNSUPPORTED; from a server older than 1.3, which
// knows neither request, UNKNOWN_TYPE.
void without_capability_is_unsupported(Context& context) {
  if (context.checkpoint) throw NotApplicable("the server has capability checkpoint");
  const bool older = context.declared_minor && *context.declared_minor < kSinceMinor;
  const char* code = older ? "UNKNOWN_TYPE" : "UNSUPPORTED";
  expect_error(context.request(protocol::type::checkpoint, {{"path", scratch_file(context, "unsupported.checkpoint").string()}}), {code});
  expect_error(context.request(protocol::type::restore, {{"path", scratch_file(context, "unsupported.checkpoint").string()}}), {code});
}

void needs_capability(const Context& context) {
  if (!context.checkpoint) throw NotApplicable("the server lacks capability checkpoint");
}

void missing_path_is_bad_message(Context& context) {
  needs_capability(context);
  expect_error(context.request(protocol::type::checkpoint), {"BAD_MESSAGE"});
  expect_error(context.request(protocol::type::restore, {{"path", 3}}), {"BAD_MESSAGE"});
}

void missing_file_is_bad_checkpoint(Context& context) {
  needs_capability(context);
  expect_error(context.request(protocol::type::restore, {{"path", scratch_file(context, "never_written.checkpoint").string()}}), {"BAD_CHECKPOINT"});
}

void damaged_file_is_bad_checkpoint(Context& context) {
  needs_capability(context);
  const fs::path file = scratch_file(context, "damaged.checkpoint");
  std::ofstream(file, std::ios::binary) << "DFCCKPT1 not a checkpoint";
  expect_error(context.request(protocol::type::restore, {{"path", file.string()}}), {"BAD_CHECKPOINT"});
}

void write_then_restore_while_configured(Context& context) {
  needs_capability(context);
  const fs::path file = scratch_file(context, "configured.checkpoint");
  const protocol::Message written = context.request(protocol::type::checkpoint, {{"path", file.string()}});
  expect_type(written, protocol::type::checkpointed);
  expect_step(written, context.step);
  expect(fs::is_regular_file(file), "the server answered checkpointed but wrote no file at " + file.string());
  const protocol::Message restored = context.request(protocol::type::restore, {{"path", file.string()}});
  expect_type(restored, protocol::type::restored);
  expect_step(restored, context.step);
}

void restore_when_running_is_out_of_order(Context& context) {
  needs_capability(context);
  expect_error(context.request(protocol::type::restore, {{"path", scratch_file(context, "configured.checkpoint").string()}}), {"OUT_OF_ORDER"});
}

void checkpoint_when_running_has_current_step(Context& context) {
  needs_capability(context);
  const fs::path file = scratch_file(context, "running.checkpoint");
  const protocol::Message written = context.request(protocol::type::checkpoint, {{"path", file.string()}});
  expect_type(written, protocol::type::checkpointed);
  expect_step(written, context.step);
  expect(fs::is_regular_file(file), "the server answered checkpointed but wrote no file at " + file.string());
}

}  // namespace

std::vector<Check> checkpoint_checks_configured() {
  using M = Milestone;
  return {
      {"checkpoint.unsupported", "without capability checkpoint, checkpoint and restore get UNSUPPORTED (before 1.3: UNKNOWN_TYPE)",
       M::configured, M::none, true, without_capability_is_unsupported},
      {"checkpoint.missing_path", "checkpoint or restore without a string body.path gets BAD_MESSAGE", M::configured, M::none, true,
       missing_path_is_bad_message, kSinceMinor},
      {"checkpoint.missing_file", "restore from a file that does not exist gets BAD_CHECKPOINT", M::configured, M::none, true,
       missing_file_is_bad_checkpoint, kSinceMinor},
      {"checkpoint.damaged_file", "restore from a damaged file gets BAD_CHECKPOINT", M::configured, M::none, true,
       damaged_file_is_bad_checkpoint, kSinceMinor},
      {"checkpoint.configured_round_trip", "checkpoint while configured gets checkpointed and a file; restore of it gets restored at that step",
       M::configured, M::none, true, write_then_restore_while_configured, kSinceMinor},
  };
}

std::vector<Check> checkpoint_checks_running() {
  using M = Milestone;
  return {
      {"checkpoint.restore_refused_when_running", "restore after advancing gets OUT_OF_ORDER", M::stepped, M::none, true,
       restore_when_running_is_out_of_order, kSinceMinor},
      {"checkpoint.running", "checkpoint after advancing gets checkpointed at the current step and a file", M::stepped, M::none, true,
       checkpoint_when_running_has_current_step, kSinceMinor},
  };
}

}  // namespace dfc::conformance
