#include "dfc/common/json_schema.hpp"

#include <cmath>

namespace dfc {

namespace {

using nlohmann::json;

// A section in an object that includes a file, or nested in one, is a patch
// of the included file's section (a JSON Merge Patch): its required keys may
// come from that file, at any depth. So each section has two forms: complete,
// and patch (the same keys, none required, its sections patches too).
enum class Form { complete, patch };

std::string def_name(const SectionDeclaration& section, Form form) { return form == Form::patch ? patch_def_name(section) : section.name; }

json section_body(const SectionDeclaration& section, json& defs, Form form);

json reference(const SectionDeclaration& section, json& defs, Form form) {
  const std::string name = def_name(section, form);
  if (!defs.contains(name)) {
    defs[name] = json::object();  // placeholder: a section may refer to itself
    defs[name] = form == Form::patch ? section_body(section, defs, Form::patch) : section_schema(section, defs);
  }
  return json{{"$ref", "#/$defs/" + name}};
}

void add_number_bounds(json& schema, Bounds bounds) {
  if (std::isfinite(bounds.min)) schema[bounds.min_exclusive ? "exclusiveMinimum" : "minimum"] = bounds.min;
  if (std::isfinite(bounds.max)) schema["maximum"] = bounds.max;
}

void add_integer_bounds(json& schema, const ParameterDeclaration& p) {
  if (p.integer_min != std::numeric_limits<std::int64_t>::min()) schema["minimum"] = p.integer_min;
  if (p.integer_max != std::numeric_limits<std::int64_t>::max()) schema["maximum"] = p.integer_max;
}

std::string description(const ParameterDeclaration& p) {
  std::string text = p.doc;
  if (!p.unit.empty() && p.unit != "-") text += " [" + p.unit + "]";
  if (p.presence == Presence::optional) text += " (absent: " + p.absent_means + ")";
  if (!p.upscaling.empty()) text += " (upscaling: " + p.upscaling + ")";
  return text;
}

// A scenario is read as JSON Merge Patches (RFC 7386: includes, variants), in
// which null removes a key: "variants": null drops an included file's
// variants, and a null given without an include is the key left out. So a key
// that may be absent may also be null. A required key may not: null would
// leave it missing.
void allow_null(json& schema) {
  if (schema.contains("type")) {
    // Typed values: a type list keeps the bounds, which apply to their type only.
    schema["type"] = json::array({schema["type"], "null"});
    if (schema.contains("enum")) schema["enum"].push_back(nullptr);
    return;
  }
  if (schema.contains("$ref")) {
    // A section: if/else, not anyOf, so that a validator reports an error
    // inside the section at its own key path rather than at the section.
    schema["if"] = {{"type", "null"}};
    schema["else"] = {{"$ref", schema["$ref"]}};
    schema.erase("$ref");
  }
  // Untyped (any value): null is already a value.
}

json value_schema(const ParameterDeclaration& p, json& defs, Form form) {
  json schema;
  switch (p.type) {
    case ValueType::number:
      schema["type"] = "number";
      add_number_bounds(schema, p.bounds);
      break;
    case ValueType::integer:
      schema["type"] = "integer";
      add_integer_bounds(schema, p);
      break;
    case ValueType::boolean: schema["type"] = "boolean"; break;
    case ValueType::string:
      schema["type"] = "string";
      if (!p.choices.empty()) schema["enum"] = p.choices;
      break;
    case ValueType::vector3:
    case ValueType::numbers: {
      json item{{"type", "number"}};
      add_number_bounds(item, p.bounds);
      schema = {{"type", "array"}, {"items", item}};
      if (p.type == ValueType::vector3) schema["minItems"] = schema["maxItems"] = 3;
      break;
    }
    case ValueType::integers3: {
      json item{{"type", "integer"}};
      add_integer_bounds(item, p);
      schema = {{"type", "array"}, {"items", item}, {"minItems", 3}, {"maxItems", 3}};
      break;
    }
    case ValueType::strings: {
      json item{{"type", "string"}};
      if (!p.choices.empty()) item["enum"] = p.choices;
      schema = {{"type", "array"}, {"items", item}};
      break;
    }
    case ValueType::object:
      if (p.section != nullptr) schema = reference(*p.section, defs, form);
      else schema["type"] = "object";
      break;
    case ValueType::objects:
      schema = {{"type", "array"}, {"items", p.section != nullptr ? reference(*p.section, defs, form) : json{{"type", "object"}}}};
      break;
    case ValueType::any: break;
  }
  schema["description"] = description(p);
  if (p.presence == Presence::defaulted) schema["default"] = p.default_value;
  if (!p.unit.empty()) schema["x-unit"] = p.unit;
  if (p.presence != Presence::required) allow_null(schema);
  return schema;
}

json required_keys(const SectionDeclaration& section) {
  json required = json::array();
  for (const auto& p : section.parameters)
    if (p.presence == Presence::required) required.push_back(p.key);
  return required;
}

json section_body(const SectionDeclaration& section, json& defs, Form form) {
  json schema{{"type", "object"}, {"description", section.doc}};
  json properties = json::object();
  for (const auto& p : section.parameters) properties[p.key] = value_schema(p, defs, form);
  // Any object of a scenario file may include another file (the coupler's
  // scenario_includes), whose keys it extends.
  properties["include"] = {{"type", "string"},
                           {"description", "a JSON file (relative to this file) whose keys this object extends; keys given here win"}};
  schema["properties"] = properties;
  // Notes are free-form: keys starting with '_' and "comment" (ConfigReader::finish).
  schema["patternProperties"] = {{"^_", json::object()}, {"^comment$", json::object()}};

  json conditions = json::array();
  if (const json required = required_keys(section); form == Form::complete && !required.empty()) schema["required"] = required;
  for (const auto& variant : section.variants) {
    json then{{"properties", json::object()}};
    if (variant.keys != nullptr) {
      for (const auto& p : variant.keys->parameters) then["properties"][p.key] = value_schema(p, defs, form);
      if (const json variant_required = required_keys(*variant.keys); form == Form::complete && !variant_required.empty())
        then["required"] = variant_required;
    }
    const ParameterDeclaration* selector = section.find(section.selector);
    json condition{{"properties", {{section.selector, {{"const", variant.value}}}}}};
    // A defaulted selector picks its default variant when absent.
    if (selector == nullptr || selector->presence != Presence::defaulted || selector->default_value != variant.value)
      condition["required"] = {section.selector};
    conditions.push_back({{"if", condition}, {"then", then}});
  }
  // An optional selector left out (a material named by its preset): the keys
  // of every variant may appear, to override the preset's values.
  if (const ParameterDeclaration* selector = section.find(section.selector); selector != nullptr && selector->presence == Presence::optional) {
    json any_variant{{"properties", json::object()}};
    for (const auto& variant : section.variants)
      if (variant.keys != nullptr)
        for (const auto& p : variant.keys->parameters) {
          json property = value_schema(p, defs, form);
          property["description"] = "(" + variant.value + ") " + property["description"].get<std::string>();
          if (!any_variant["properties"].contains(p.key)) any_variant["properties"][p.key] = property;
        }
    conditions.push_back({{"if", {{"not", {{"required", {section.selector}}}}}}, {"then", any_variant}});
  }
  if (!conditions.empty()) schema["allOf"] = conditions;
  // Keys the variants add are evaluated inside allOf, which additionalProperties
  // would not see; unevaluatedProperties (2020-12) does.
  schema["unevaluatedProperties"] = false;
  return schema;
}

}  // namespace

std::string patch_def_name(const SectionDeclaration& section) { return section.name + ".patch"; }

json section_schema(const SectionDeclaration& section, json& defs) {
  // The if/then/else (not oneOf) reports an error inside either form at its own key path.
  return {{"type", "object"},
          {"description", section.doc},
          {"if", {{"required", {"include"}}}},
          {"then", reference(section, defs, Form::patch)},
          {"else", section_body(section, defs, Form::complete)}};
}

json schema_document(const SectionDeclaration& root, const std::string& id, const std::string& title) {
  json defs = json::object();
  json document = section_schema(root, defs);
  json head{{"$schema", "https://json-schema.org/draft/2020-12/schema"}, {"$id", id}, {"title", title}};
  for (auto& [key, value] : document.items()) head[key] = value;
  head["$defs"] = defs;
  return head;
}

}  // namespace dfc
