#pragma once
// A parameter a plug-in model declares next to its code (STYLE.md §6), so that
// --help and error messages come from the same table.
#include <string_view>

namespace dfc::fdm {

struct ModelParameter {
  std::string_view key;      ///< JSON key inside the material object
  std::string_view unit;     ///< SI unit, "-" for dimensionless
  std::string_view meaning;  ///< one sentence, with the admissible range
};

}  // namespace dfc::fdm
