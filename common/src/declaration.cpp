#include "dfc/common/declaration.hpp"

#include <cmath>
#include <set>
#include <sstream>

namespace dfc {

namespace {

std::string format_number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

ParameterDeclaration make(std::string key, ValueType type, std::string unit, std::string doc) {
  ParameterDeclaration p;
  p.key = std::move(key);
  p.type = type;
  p.unit = std::move(unit);
  p.doc = std::move(doc);
  return p;
}

std::string type_text(const ParameterDeclaration& p) {
  switch (p.type) {
    case ValueType::number: return "number";
    case ValueType::integer: return "integer";
    case ValueType::boolean: return "true|false";
    case ValueType::string:
    case ValueType::strings: {
      const char* any = p.type == ValueType::string ? "string" : "[strings]";
      if (p.choices.empty()) return any;
      std::string list;
      for (const auto& c : p.choices) list += (list.empty() ? "\"" : "|\"") + c + "\"";
      return p.type == ValueType::string ? list : "[" + list + ", ...]";
    }
    case ValueType::vector3: return "[x,y,z]";
    case ValueType::numbers: return "[numbers]";
    case ValueType::integers3: return "[i,j,k] integers";
    case ValueType::object: return "object";
    case ValueType::objects: return "[objects]";
    case ValueType::any: return "value";
  }
  return "value";
}

std::string integer_range(const ParameterDeclaration& p) {
  constexpr auto lowest = std::numeric_limits<std::int64_t>::min();
  constexpr auto highest = std::numeric_limits<std::int64_t>::max();
  if (p.integer_min != lowest && p.integer_max != highest)
    return "in [" + std::to_string(p.integer_min) + ", " + std::to_string(p.integer_max) + "]";
  if (p.integer_min != lowest) return ">= " + std::to_string(p.integer_min);
  if (p.integer_max != highest) return "<= " + std::to_string(p.integer_max);
  return "";
}

std::string bounds_text(const ParameterDeclaration& p) {
  switch (p.type) {
    case ValueType::number:
    case ValueType::vector3:
    case ValueType::numbers: {
      if (!std::isfinite(p.bounds.min) && !std::isfinite(p.bounds.max)) return "";
      std::string text = describe_bounds(p.bounds);
      // "a number in [0, 1]" -> "in [0, 1]"
      for (const std::string_view prefix : {"a positive number", "a number "})
        if (text.rfind(prefix, 0) == 0) return prefix == "a positive number" ? "> 0" : text.substr(prefix.size());
      return text;
    }
    case ValueType::integer:
    case ValueType::integers3: return integer_range(p);
    default: return "";
  }
}

// Sections already listed in this text: a section used under several keys
// (the contact law under contact, wall_contact, walls[].contact, pile.contact)
// is listed once and named where it recurs.
using Described = std::set<const SectionDeclaration*>;

void describe_into(std::ostringstream& out, const SectionDeclaration& section, int indent, Described& described);

void describe_parameter(std::ostringstream& out, const ParameterDeclaration& p, int indent, Described& described) {
  const std::string pad(std::size_t(indent), ' ');
  out << pad << p.key;
  if (!p.unit.empty()) out << " [" << p.unit << "]";
  out << "  " << type_text(p);
  if (const std::string range = bounds_text(p); !range.empty()) out << ", " << range;
  out << ", " << describe_presence(p);
  if (!p.doc.empty()) out << ": " << p.doc;
  if (!p.upscaling.empty()) out << " (upscaling: " << p.upscaling << ")";
  out << "\n";
  if ((p.type == ValueType::object || p.type == ValueType::objects) && p.section != nullptr) {
    if (described.insert(p.section).second) describe_into(out, *p.section, indent + 4, described);
    else out << pad << "    (the keys of " << p.section->name << ", listed above)\n";
  }
}

void describe_into(std::ostringstream& out, const SectionDeclaration& section, int indent, Described& described) {
  const std::string pad(std::size_t(indent), ' ');
  for (const auto& p : section.parameters) {
    describe_parameter(out, p, indent, described);
    if (p.key != section.selector) continue;
    for (const auto& variant : section.variants) {
      out << pad << "    " << section.selector << " \"" << variant.value << "\"";
      if (!variant.doc.empty()) out << ": " << variant.doc;
      out << "\n";
      if (variant.keys != nullptr) describe_into(out, *variant.keys, indent + 8, described);
    }
  }
}

}  // namespace

ParameterDeclaration ParameterDeclaration::number(std::string key, std::string unit, std::string doc) {
  return make(std::move(key), ValueType::number, std::move(unit), std::move(doc));
}
ParameterDeclaration ParameterDeclaration::integer(std::string key, std::string doc) {
  return make(std::move(key), ValueType::integer, "", std::move(doc));
}
ParameterDeclaration ParameterDeclaration::boolean(std::string key, std::string doc) {
  return make(std::move(key), ValueType::boolean, "", std::move(doc));
}
ParameterDeclaration ParameterDeclaration::string(std::string key, std::string doc) {
  return make(std::move(key), ValueType::string, "", std::move(doc));
}
ParameterDeclaration ParameterDeclaration::vector3(std::string key, std::string unit, std::string doc) {
  return make(std::move(key), ValueType::vector3, std::move(unit), std::move(doc));
}
ParameterDeclaration ParameterDeclaration::numbers(std::string key, std::string unit, std::string doc) {
  return make(std::move(key), ValueType::numbers, std::move(unit), std::move(doc));
}
ParameterDeclaration ParameterDeclaration::integers3(std::string key, std::string doc) {
  return make(std::move(key), ValueType::integers3, "", std::move(doc));
}
ParameterDeclaration ParameterDeclaration::strings(std::string key, std::string doc) {
  return make(std::move(key), ValueType::strings, "", std::move(doc));
}
ParameterDeclaration ParameterDeclaration::object(std::string key, const SectionDeclaration& section) {
  ParameterDeclaration p = make(std::move(key), ValueType::object, "", section.doc);
  p.section = &section;
  return p;
}
ParameterDeclaration ParameterDeclaration::any_object(std::string key, std::string doc) {
  return make(std::move(key), ValueType::object, "", std::move(doc));
}
ParameterDeclaration ParameterDeclaration::objects(std::string key, const SectionDeclaration& section) {
  ParameterDeclaration p = make(std::move(key), ValueType::objects, "", section.doc);
  p.section = &section;
  return p;
}
ParameterDeclaration ParameterDeclaration::any(std::string key, std::string doc) {
  return make(std::move(key), ValueType::any, "", std::move(doc));
}

ParameterDeclaration ParameterDeclaration::fallback(nlohmann::json value) const {
  ParameterDeclaration p = *this;
  p.presence = Presence::defaulted;
  p.default_value = std::move(value);
  return p;
}

ParameterDeclaration ParameterDeclaration::optional(std::string meaning) const {
  ParameterDeclaration p = *this;
  p.presence = Presence::optional;
  p.absent_means = std::move(meaning);
  return p;
}

ParameterDeclaration ParameterDeclaration::within(Bounds value_bounds) const {
  ParameterDeclaration p = *this;
  p.bounds = value_bounds;
  return p;
}

ParameterDeclaration ParameterDeclaration::integer_within(std::int64_t min, std::int64_t max) const {
  ParameterDeclaration p = *this;
  p.integer_min = min;
  p.integer_max = max;
  return p;
}

ParameterDeclaration ParameterDeclaration::one_of(std::vector<std::string> allowed) const {
  ParameterDeclaration p = *this;
  p.choices = std::move(allowed);
  return p;
}

ParameterDeclaration ParameterDeclaration::upscaled(std::string rule, double exponent) const {
  ParameterDeclaration p = *this;
  p.upscaling = std::move(rule);
  p.upscaling_exponent = exponent;
  return p;
}

const ParameterDeclaration* SectionDeclaration::find(std::string_view key) const noexcept {
  for (const auto& p : parameters)
    if (p.key == key) return &p;
  return nullptr;
}

const SectionVariant* SectionDeclaration::find_variant(std::string_view value) const noexcept {
  for (const auto& v : variants)
    if (v.value == value) return &v;
  return nullptr;
}

std::string describe_bounds(Bounds bounds) {
  const bool has_min = std::isfinite(bounds.min);
  const bool has_max = std::isfinite(bounds.max);
  if (has_min && bounds.min_exclusive && bounds.min == 0.0 && !has_max) return "a positive number";
  if (has_min && has_max)
    return "a number in " + std::string(bounds.min_exclusive ? "(" : "[") + format_number(bounds.min) + ", " +
           format_number(bounds.max) + "]";
  if (has_min) return "a number " + std::string(bounds.min_exclusive ? "> " : ">= ") + format_number(bounds.min);
  if (has_max) return "a number <= " + format_number(bounds.max);
  return "a finite number";
}

std::string describe_presence(const ParameterDeclaration& parameter) {
  switch (parameter.presence) {
    case Presence::required: return "required";
    case Presence::defaulted: {
      const nlohmann::json& v = parameter.default_value;
      return "default " + (v.is_number_float() ? format_number(v.get<double>()) : v.dump());
    }
    case Presence::optional: return "optional (absent: " + parameter.absent_means + ")";
  }
  return "";
}

std::string describe_section(const SectionDeclaration& section, int indent) {
  std::ostringstream out;
  Described described{&section};
  describe_into(out, section, indent, described);
  return out.str();
}

}  // namespace dfc
