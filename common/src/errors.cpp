#include "dfc/common/errors.hpp"

namespace dfc {

namespace {
std::string join_key(const std::string& key_path, const std::string& reason) {
  return key_path.empty() ? reason : key_path + ": " + reason;
}
}  // namespace

ConfigError::ConfigError(std::string key_path, std::string reason)
    : UserError(join_key(key_path, reason)), key_path_(std::move(key_path)), reason_(std::move(reason)) {}

ConfigError ConfigError::with_prefix(const std::string& prefix) const {
  if (prefix.empty()) return *this;
  return ConfigError(key_path_.empty() ? prefix : prefix + "." + key_path_, reason_);
}

}  // namespace dfc
