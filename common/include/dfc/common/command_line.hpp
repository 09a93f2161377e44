#pragma once
// Values of command-line options, checked: "--idle-timeout abc" is a UserError
// naming the option and what it takes, not a bare "stod" from the library.
#include <cstdint>
#include <string>
#include <string_view>

#include "dfc/common/config_reader.hpp"

namespace dfc {

/// The whole of `text` as a finite number within `bounds`.
[[nodiscard]] double parse_number_option(std::string_view option, const std::string& text, Bounds bounds);

/// The whole of `text` as a decimal integer in [min_value, max_value].
[[nodiscard]] std::uint64_t parse_count_option(std::string_view option, const std::string& text, std::uint64_t min_value,
                                               std::uint64_t max_value);

}  // namespace dfc
