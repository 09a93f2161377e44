#include "dfc/common/state_archive.hpp"

namespace dfc {

void StateWriter::vector(const std::vector<bool>& v) {
  value(std::uint64_t(v.size()));
  for (const bool b : v) value(std::uint8_t(b));
}

void StateWriter::string(std::string_view s) {
  value(std::uint64_t(s.size()));
  bytes(s.data(), s.size());
}

void StateReader::vector(std::vector<bool>& v) {
  const auto n = value<std::uint64_t>();
  if (n > remaining()) fail("a flag array of " + std::to_string(n) + " entries");
  v.assign(std::size_t(n), false);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = value<std::uint8_t>() != 0;
}

std::string StateReader::string() {
  const auto n = value<std::uint64_t>();
  if (n > remaining()) fail("a text of " + std::to_string(n) + " bytes");
  return std::string(take(std::size_t(n)), std::size_t(n));
}

void StateReader::tag(std::string_view name) {
  work_progress::advance();  // as StateWriter::tag
  const std::size_t at = position_;
  const auto n = value<std::uint64_t>();
  if (n != name.size() || n > remaining() || std::string_view(take(std::size_t(n)), std::size_t(n)) != name) {
    position_ = at;
    fail("section '" + std::string(name) + "'");
  }
}

void StateReader::finish() const {
  if (remaining() != 0) fail("its end (" + std::to_string(remaining()) + " bytes are left over)");
}

void StateReader::fail(const std::string& what_was_expected) const {
  throw StateFormatError(what_ + " is damaged or of another layout: expected " + what_was_expected + " at byte " + std::to_string(position_) +
                         " of " + std::to_string(in_.size()));
}

const char* StateReader::take(std::size_t n) {
  if (n > remaining()) fail(std::to_string(n) + " more bytes");
  const char* p = in_.data() + position_;
  position_ += n;
  return p;
}

}  // namespace dfc
