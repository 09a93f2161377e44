#include "dfc/coupler/participant.hpp"

#include "dfc/common/durations.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/echo.hpp"
#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/key_file.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::coupler {

void StopRequest::check(const std::string& pending) {
  if (!requested()) return;
  const auto now = std::chrono::steady_clock::now();
  if (!first_seen_) first_seen_ = now;
  if (now - *first_seen_ > kGrace + granted_)
    throw RunInterrupted("stopped by a signal (Ctrl-C) during " + pending + ", which did not end within " + std::to_string(kGrace.count()) +
                         " ms of it");
}

Participant::Participant(zmq::context_t& context, const ParticipantSpec& spec, const std::filesystem::path& log_dir,
                         std::chrono::milliseconds startup_timeout, protocol::HangTimeouts hang, StopRequest& stop,
                         const protocol::RunKeyFile* run_keys)
    : spec_(spec), stop_(&stop), context_(&context), hang_(hang) {
  std::string endpoint = spec.endpoint;
  std::optional<std::string> server_key;
  if (endpoint.empty()) {
    std::vector<std::string> args = spec.args;
    args.insert(args.end(), {"--bind", "tcp://127.0.0.1:*"});
    // The key file's path goes in the environment, not among the arguments:
    // a server that knows no DFC_KEY_FILE (one before 1.7) still starts.
    process_ = std::make_unique<ChildProcess>(spec.executable, args, log_dir / (spec.slot + ".stderr.log"),
                                              log_dir / (spec.slot + ".stdout.log"),
                                              run_keys ? std::vector{run_keys->environment_entry()} : std::vector<std::string>());
    const auto listening = process_->wait_for_endpoint(startup_timeout, spec.slot + " server '" + spec.program + "'",
                                                       [this] { stop_->check("the start of server " + label()); });
    endpoint = listening.endpoint;
    if (const auto problem = protocol::endpoint_problem(endpoint))
      throw ConfigError(spec.key_path() + ".program", "'" + spec.program + "' printed the line 'DFC-LISTENING " + echoed(endpoint, kMaxEchoedPathBytes) + "', which is no endpoint: " +
                                                          *problem + "; a protocol v1 server prints the endpoint it bound (SPEC.md §2)");
    authenticated_ = listening.authenticated && run_keys != nullptr;
    if (authenticated_) server_key = run_keys->keys().public_key;
  } else if (!spec.key_file.empty()) {
    try {
      server_key = protocol::read_key_file(spec.key_file).public_key;
    } catch (const UserError& e) {
      throw ConfigError(spec.key_path() + ".key_file", e.what());
    }
    authenticated_ = true;
  }
  client_ = std::make_unique<protocol::SolverClient>(context, endpoint, label(), server_key);
  client_->connection().set_wait_hook([this] { check_alive(); });
}

std::string Participant::label() const {
  std::string text = spec_.slot + " (";
  text += spec_.endpoint.empty() ? spec_.program : spec_.endpoint;
  if (process_) text += ", pid " + std::to_string(process_->pid());
  return text + ")";
}

bool Participant::has(std::string_view capability) const {
  const auto narrowed = configured_info_.find("capabilities");
  if (narrowed == configured_info_.end() || !narrowed->is_array()) return hello_.has(capability);
  for (const auto& c : *narrowed)
    if (c.is_string() && c.get<std::string>() == capability) return true;
  return false;
}

void Participant::check_alive() {
  stop_->check("the wait for server " + label());
  if (!process_) return;
  if (const auto exited = process_->exit_description())
    throw ParticipantFailure("server " + label() + " " + *exited + ". Last lines of its stderr (" + process_->stderr_log().string() +
                             "):\n" + process_->stderr_tail(15));
}

void Participant::fail(const std::exception& error, const std::string& doing) {
  if (const auto* failure = dynamic_cast<const ParticipantFailure*>(&error)) throw *failure;
  if (const auto* config = dynamic_cast<const ConfigError*>(&error)) throw *config;
  if (const auto* interrupted = dynamic_cast<const RunInterrupted*>(&error)) throw *interrupted;
  std::string message = "server " + label() + " failed while " + doing + ": " + error.what();
  if (const auto* hung = dynamic_cast<const protocol::HungError*>(&error)) {
    hung_ = true;
    if (hung->kind() == protocol::HungError::Kind::silent)
      message = "server " + label() + " stopped answering while " + doing + ": " + hung->account() +
                ". It is hung or stopped (SIGSTOP, a frozen node): a busy server still answers its heartbeat; run.hang_timeout_s sets how long the coupler waits";
    else
      message = "server " + label() + " answers but makes no progress while " + doing + ": " + hung->account() +
                ". Its main thread is deadlocked or spinning (SPEC.md §9.1); if one of its requests legitimately spends longer than " +
                seconds_text(hang_.stall) + " without a step, raise run.stall_timeout_s";
  } else if (dynamic_cast<const protocol::TimeoutError*>(&error) != nullptr) {
    message = "server " + label() + " did not answer while " + doing + " (" + error.what() +
              "); it is hung or too slow: raise run.deadline_s if it is only slow";
    // A server started by hand that holds another key than the scenario names,
    // or none where it names one, or one where it names none, drops every
    // message unanswered (SPEC.md §2.1).
    if (!process_ && !greeted_)
      message += authenticated_ ? "; or it does not hold the key of " + spec_.key_path() +
                                      ".key_file: it was started with another DFC_KEY_FILE, or with none, or it is a server before protocol 1.7, "
                                      "which knows no key (then remove key_file)"
                                : "; or it was started with a key file (DFC_KEY_FILE) that the scenario does not name in " + spec_.key_path() +
                                      ".key_file";
  }
  if (const auto* remote = dynamic_cast<const protocol::RemoteError*>(&error))
    message = "server " + label() + " refused while " + doing + ": [" + remote->code() + "] " + remote->what();
  if (process_) {
    message += "\n  Last lines of its stderr (" + process_->stderr_log().string() + "):\n" + process_->stderr_tail(15);
  }
  throw ParticipantFailure(message);
}

void Participant::hello(std::chrono::milliseconds deadline) {
  try {
    hello_ = client_->hello("coupler", deadline);
    greeted_ = true;
    const auto version = protocol::parse_version(hello_.protocol_version);
    if (process_ && !authenticated_ && version && version->second >= protocol::authentication::kSinceMinor)
      throw ParticipantFailure("server " + label() + " declares protocol " + hello_.protocol_version + " but did not take the run's key from " +
                               std::string(protocol::authentication::kKeyFileVariable) + " (it printed no '" +
                               std::string(protocol::authentication::kAnnouncement) +
                               "' line): it would answer any process on this host. A 1.7 server must authenticate (protocol/SPEC.md §2.1)");
    if (!hello_.heartbeat_endpoint.empty()) client_->connection().watch_heartbeat(*context_, hello_.heartbeat_endpoint, hang_);
  } catch (const std::exception& e) {
    fail(e, "greeting it (hello)");
  }
}

nlohmann::json Participant::configure(std::chrono::milliseconds deadline) {
  const std::string section = spec_.config.dump();
  try {
    configured_info_ = client_->configure(section, deadline).value("info", nlohmann::json::object());
    return configured_info_;
  } catch (const protocol::RemoteError& e) {
    if (e.code() == "BAD_CONFIG") {
      std::string reason = e.what();
      if (!e.key().empty() && reason.rfind(e.key() + ": ", 0) == 0) reason.erase(0, e.key().size() + 2);
      throw ConfigError(spec_.key_path() + ".config" + (e.key().empty() ? "" : "." + e.key()), reason + " (reported by " + spec_.program + ")");
    }
    fail(e, "configuring it");
  } catch (const std::exception& e) {
    fail(e, "configuring it");
  }
}

void Participant::stop() noexcept {
  try {
    // Short limits: a server that hung already cost a whole deadline; one
    // that stopped answering its heartbeat would not answer shutdown either.
    if (!hung_ && (!process_ || !process_->exit_description())) client_->shutdown(std::chrono::milliseconds(1000));
  } catch (...) {
    // It may already be gone; killing below is the fallback.
  }
  // After Ctrl-C the user is waiting: a server that does not exit at once is killed.
  const auto grace = std::chrono::milliseconds(stop_->requested() || hung_ ? 200 : 1000);
  if (process_ && !process_->wait_exit(grace)) process_->kill();
}

void StopRequest::grant(std::chrono::milliseconds extra) {
  first_seen_ = std::chrono::steady_clock::now();
  granted_ = extra;
}

}  // namespace dfc::coupler
