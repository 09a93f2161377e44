#include "dfc/protocol/heartbeat_monitor.hpp"

#include <algorithm>
#include <cstdio>

#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/heartbeat.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::protocol {

namespace {
constexpr std::chrono::milliseconds kLongestInterval{1000};

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", seconds);
  return text;
}

double seconds_between(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}
}  // namespace

HeartbeatMonitor::HeartbeatMonitor(zmq::context_t& context, const std::string& endpoint, HangTimeouts timeouts,
                                   const std::optional<std::string>& server_key)
    : socket_(context, zmq::socket_type::dealer),
      endpoint_(endpoint),
      timeouts_{std::max(timeouts.silence, std::chrono::milliseconds(1)), std::max(timeouts.stall, std::chrono::milliseconds(1))},
      interval_(std::clamp(timeouts_.silence / 4, std::chrono::milliseconds(1), kLongestInterval)) {
  // A ping never blocks the wait (configure_socket's send timeout 0): to a
  // server that reads none, pings pile up to the high-water mark and the next
  // ones are dropped, not waited on.
  configure_socket(socket_, heartbeat::message_limits());
  authentication::secure_client_socket(socket_, server_key);
  socket_.connect(endpoint);
}

void HeartbeatMonitor::begin_wait() {
  last_life_ = Clock::now();
  last_poll_ = last_life_;
  // The first ping goes one interval into the wait: the replies of a fast
  // exchange (microseconds) cost no ping and no system call at all.
  last_ping_ = last_life_;
  first_seq_of_wait_ = next_seq_;
  progress_.reset();  // the counter moved while the client worked, or not: this wait judges only what it sees
}

void HeartbeatMonitor::read_pongs(Clock::time_point now) {
  while (auto frames = receive_frames(socket_, std::chrono::milliseconds(0))) {
    Message pong;
    try {
      pong = decode(frame_views(*frames, 0), heartbeat::message_limits());
    } catch (const DecodeError&) {
      continue;  // not a pong: no sign of life
    }
    if (pong.type != type::pong || !pong.reply_to) continue;
    ever_answered_ = true;
    last_pong_body_ = pong.body;
    if (*pong.reply_to < first_seq_of_wait_) continue;
    last_life_ = now;
    const auto progress = pong.body.find(heartbeat::progress_key);
    if (progress == pong.body.end() || !progress->is_number_integer()) continue;  // a server before 1.8: the silence rule alone
    const auto value = progress->get<std::int64_t>();
    if (!progress_ || value != *progress_) {
      progress_ = value;
      progress_since_ = now;
    }
  }
}

Liveliness HeartbeatMonitor::poll() {
  const auto now = Clock::now();
  // A client that itself did not run for half the silence timeout (the whole
  // job stopped and continued, as a batch system's suspend does with SIGSTOP
  // and SIGCONT; a suspended virtual machine) saw nothing of the server in
  // that time: the pause counts as neither silence nor stall, and a ping goes
  // out at once to learn where the server stands now.
  if (now - last_poll_ > timeouts_.silence / 2) {
    const auto paused = now - last_poll_;
    last_life_ += paused;
    progress_since_ += paused;
    last_ping_ = now - interval_;
  }
  last_poll_ = now;
  if (next_seq_ > first_seq_of_wait_) read_pongs(now);  // only a ping of this wait can be answered now
  if (now - last_ping_ >= interval_) {
    Message ping;
    ping.type = std::string(type::ping);
    ping.seq = next_seq_++;
    send_message(socket_, ping);
    last_ping_ = now;
  }
  if (now - last_life_ >= timeouts_.silence) return Liveliness::silent;
  if (progress_ && now - progress_since_ >= timeouts_.stall) return Liveliness::stalled;
  return Liveliness::alive;
}

std::string HeartbeatMonitor::last_pong_account(const std::string& pong) const {
  const auto number = [&](std::string_view key) -> std::string {
    const auto it = last_pong_body_.find(key);
    return it != last_pong_body_.end() && it->is_number() ? it->dump() : "?";
  };
  // Appended piece by piece: "literal" + std::string temporaries trip GCC 12's -Wrestrict (a false positive).
  std::string text;
  text.append("; the last ").append(pong).append(" said ").append(number(heartbeat::handled_key)).append(" requests handled, step ").append(number(heartbeat::step_key));
  const auto busy = last_pong_body_.find(heartbeat::busy_key);
  if (busy != last_pong_body_.end() && busy->is_number()) text.append(", busy for ").append(seconds_text(busy->get<double>()));
  return text;
}

std::string HeartbeatMonitor::silence_description() const {
  std::string text = "no pong from its heartbeat (" + endpoint_ + ") for " + seconds_text(seconds_between(last_life_, Clock::now()));
  if (!ever_answered_) return text + ", nor ever before";
  return text + last_pong_account("one");
}

std::string HeartbeatMonitor::stall_description() const {
  std::string text = "its heartbeat (" + endpoint_ + ") answers, but its progress";
  if (progress_) text.append(" stood at ").append(std::to_string(*progress_)).append(" for ").append(seconds_text(seconds_between(progress_since_, Clock::now())));
  return text + last_pong_account("pong");
}

}  // namespace dfc::protocol
