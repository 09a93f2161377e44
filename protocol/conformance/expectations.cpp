#include "expectations.hpp"

#include "dfc/protocol/monitor_units.hpp"

#include <algorithm>
#include <cmath>

namespace dfc::conformance {

namespace protocol = dfc::protocol;

std::string describe(const protocol::Message& reply) {
  if (reply.type != protocol::type::error) return "'" + reply.type + "'";
  const auto& body = reply.body;
  const std::string code = body.contains("code") && body["code"].is_string() ? body["code"].get<std::string>() : "(no code)";
  const std::string message = body.contains("message") && body["message"].is_string() ? body["message"].get<std::string>() : "";
  return "error " + code + " (\"" + message.substr(0, 300) + "\")";
}

void expect_type(const protocol::Message& reply, std::string_view type, std::optional<std::int64_t> reply_to) {
  expect(reply.type == type, "expected '" + std::string(type) + "', got " + describe(reply));
  if (reply_to)
    expect(reply.reply_to == reply_to, "'" + reply.type + "' has reply_to " + (reply.reply_to ? std::to_string(*reply.reply_to) : "(none)") +
                                           " but answers seq " + std::to_string(*reply_to));
}

void expect_error(const protocol::Message& reply, std::initializer_list<std::string_view> codes) {
  std::string wanted;
  for (const auto code : codes) wanted += (wanted.empty() ? "" : " or ") + std::string(code);
  expect(reply.type == protocol::type::error, "expected error " + wanted + ", got " + describe(reply));
  const auto code = reply.body.find("code");
  expect(code != reply.body.end() && code->is_string(), "the error reply has no string body.code");
  expect(std::find(codes.begin(), codes.end(), code->get<std::string>()) != codes.end(), "expected error " + wanted + ", got " + describe(reply));
  const auto message = reply.body.find("message");
  expect(message != reply.body.end() && message->is_string() && !message->get<std::string>().empty(),
         "the error reply has no body.message saying what was wrong (SPEC.md §4.6)");
}

std::string shape_text(const std::vector<std::int64_t>& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i > 0) text += ',';
    text += shape[i] < 0 ? std::string("*") : std::to_string(shape[i]);
  }
  return text + "]";
}

const protocol::Array& expect_array(const protocol::Message& reply, std::string_view name, protocol::DType dtype,
                                    const std::vector<std::int64_t>& shape) {
  const protocol::Array* array = protocol::find_array(reply.arrays, name);
  const std::string wanted = std::string(protocol::dtype_name(dtype)) + " " + shape_text(shape);
  expect(array != nullptr, "'" + reply.type + "' lacks array '" + std::string(name) + "' (" + wanted + ")");
  bool shape_ok = array->shape.size() == shape.size();
  for (std::size_t i = 0; shape_ok && i < shape.size(); ++i) shape_ok = shape[i] < 0 || shape[i] == array->shape[i];
  expect(array->dtype == dtype && shape_ok, "array '" + std::string(name) + "' is " + std::string(protocol::dtype_name(array->dtype)) + " " +
                                                shape_text(array->shape) + ", expected " + wanted);
  if (dtype == protocol::DType::f64) {
    const auto values = array->to_f64();
    expect(std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); }),
           "array '" + std::string(name) + "' holds non-finite values");
  }
  return *array;
}

void expect_monitors(const nlohmann::json& monitors, std::string_view where) {
  expect(monitors.is_object(), std::string(where) + ": 'monitors' must be an object, got " + monitors.dump().substr(0, 200));
  for (const auto& [name, value] : monitors.items()) {
    expect(protocol::monitor_width(value) > 0,
           std::string(where) + ": monitor '" + name + "' must be a number or [x, y, z], got " + value.dump().substr(0, 200));
  }
}

void expect_step(const protocol::Message& reply, std::int64_t step) {
  expect(reply.step.has_value(), "'" + reply.type + "' lacks the header field 'step'");
  expect(*reply.step == step, "'" + reply.type + "' reports step " + std::to_string(*reply.step) + ", expected " + std::to_string(step));
}

}  // namespace dfc::conformance
