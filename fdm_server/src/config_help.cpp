// The --help text of the fdm_server section, generated from its declaration
// (dfc/common/sections/fdm_sections.hpp), plus the named materials.
#include "dfc/common/sections/fdm_sections.hpp"
#include "dfc/fdm/fdm_config.hpp"
#include "dfc/constitutive/named_materials.hpp"

namespace dfc::fdm {

std::string fdm_config_help() {
  return "  (a JSON object; unknown keys are errors, key paths are named in the error; the same keys are in scenario.schema.json)\n" +
         describe_section(sections::fdm_server()) + "Named materials (\"material.preset\"):\n" + constitutive::describe_named_materials();
}

}  // namespace dfc::fdm
