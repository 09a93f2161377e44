#include "dfc/protocol/message.hpp"

#include <charconv>

namespace dfc::protocol {

std::string version_string() { return std::to_string(kVersionMajor) + "." + std::to_string(kVersionMinor); }

Message make_error(std::optional<std::int64_t> request_seq, ErrorCode code, const std::string& message, const std::string& key) {
  Message reply;
  reply.type = type::error;
  reply.reply_to = request_seq;
  reply.body = {{"code", error_code_name(code)}, {"message", message}};
  if (!key.empty()) reply.body["key"] = key;
  return reply;
}

std::optional<std::pair<int, int>> parse_version(std::string_view text) {
  const auto dot = text.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 >= text.size()) return std::nullopt;
  // from_chars would take a sign ("-0.0", "1.-0"); a version is digits only.
  const auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!is_digit(text.front()) || !is_digit(text[dot + 1])) return std::nullopt;
  int major = 0;
  int minor = 0;
  const auto* end = text.data() + text.size();
  const auto [p1, e1] = std::from_chars(text.data(), text.data() + dot, major);
  const auto [p2, e2] = std::from_chars(text.data() + dot + 1, end, minor);
  if (e1 != std::errc() || e2 != std::errc() || p1 != text.data() + dot || p2 != end || major < 0 || minor < 0) return std::nullopt;
  return std::make_pair(major, minor);
}

}  // namespace dfc::protocol
