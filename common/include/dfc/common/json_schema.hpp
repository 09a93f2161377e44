#pragma once
// JSON Schema (draft 2020-12) of declared sections (declaration.hpp), so that
// editors and independent validators check a scenario against the same
// declarations the parsers use.
#include <string>

#include <nlohmann/json.hpp>

#include "dfc/common/declaration.hpp"

namespace dfc {

/// Schema of one section; nested sections are placed in `defs` (by name) and
/// referenced with "$ref": "#/$defs/<name>". An object with "include" is
/// checked against the section's patch form (defs[patch_def_name(section)]),
/// any other against the complete one ("else").
[[nodiscard]] nlohmann::json section_schema(const SectionDeclaration& section, nlohmann::json& defs);

/// The name in `defs` of the section's patch form: the schema of the section
/// in an object that includes a file (none of its keys required, at any depth).
[[nodiscard]] std::string patch_def_name(const SectionDeclaration& section);

/// A complete schema document whose root is `root`, with $schema, $id, title and $defs.
[[nodiscard]] nlohmann::json schema_document(const SectionDeclaration& root, const std::string& id, const std::string& title);

}  // namespace dfc
