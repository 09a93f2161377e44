#include "dfc/protocol/codec.hpp"

#include <cstring>
#include <limits>
#include <set>

#include "dfc/common/json_text.hpp"

namespace dfc::protocol {

std::string encode_header(const Message& message) {
  nlohmann::json header = {
      {"protocol", kProtocolName}, {"version", message.version}, {"type", message.type}, {"seq", message.seq}, {"body", message.body}};
  if (message.reply_to) header["reply_to"] = *message.reply_to;
  if (message.step) header["step"] = *message.step;
  nlohmann::json descriptors = nlohmann::json::array();
  for (const auto& array : message.arrays)
    descriptors.push_back({{"name", array.name}, {"dtype", dtype_name(array.dtype)}, {"shape", array.shape}});
  header["arrays"] = std::move(descriptors);
  // Frame 0 is UTF-8 (SPEC.md §3), and a string that is not must not stop a
  // reply from being sent: error texts quote the request's bytes (the JSON
  // parser's "last read: ..." of a header that is not UTF-8, a value cut to
  // 40 bytes inside a character), and nlohmann's default is to throw, which
  // ended the server. Invalid bytes are sent as U+FFFD instead.
  return header.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

namespace {

std::optional<std::int64_t> integer_field(const nlohmann::json& header, const char* key, std::optional<std::int64_t> seq, bool required) {
  const auto it = header.find(key);
  if (it == header.end() || it->is_null()) {
    if (required) throw DecodeError(ErrorCode::bad_message, std::string("header field '") + key + "' is missing", seq);
    return std::nullopt;
  }
  if (!it->is_number_integer() || (it->is_number_unsigned() && it->get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max())) ||
      it->get<std::int64_t>() < 0)
    throw DecodeError(ErrorCode::bad_message, std::string("header field '") + key + "' must be a non-negative integer", seq);
  return it->get<std::int64_t>();
}

Array decode_array(const nlohmann::json& descriptor, std::span<const std::byte> frame, std::size_t index, const Limits& limits,
                   std::optional<std::int64_t> seq) {
  const std::string where = "array descriptor " + std::to_string(index);
  if (!descriptor.is_object()) throw DecodeError(ErrorCode::bad_array, where + " is not an object", seq);
  const auto name = descriptor.find("name");
  const auto dtype = descriptor.find("dtype");
  const auto shape = descriptor.find("shape");
  if (name == descriptor.end() || !name->is_string() || name->get<std::string>().empty())
    throw DecodeError(ErrorCode::bad_array, where + ": 'name' must be a non-empty string", seq);
  Array array;
  array.name = name->get<std::string>();
  const std::string label = "array '" + array.name + "'";
  if (dtype == descriptor.end() || !dtype->is_string() || !dtype_from_name(dtype->get<std::string>()))
    throw DecodeError(ErrorCode::bad_array, label + ": 'dtype' must be one of f64, f32, i64, i32, u8", seq);
  array.dtype = *dtype_from_name(dtype->get<std::string>());
  if (shape == descriptor.end() || !shape->is_array() || shape->size() > 8)
    throw DecodeError(ErrorCode::bad_array, label + ": 'shape' must be an array of at most 8 non-negative integers", seq);
  // Compute the byte size with overflow checks before touching any memory:
  // a header must not be able to make the receiver allocate (SPEC.md §8).
  std::uint64_t bytes = dtype_size(array.dtype);
  for (const auto& extent : *shape) {
    if (!extent.is_number_integer() || extent.get<std::int64_t>() < 0)
      throw DecodeError(ErrorCode::bad_array, label + ": shape entries must be non-negative integers", seq);
    const auto e = extent.get<std::uint64_t>();
    if (e != 0 && bytes > std::numeric_limits<std::uint64_t>::max() / e)
      throw DecodeError(ErrorCode::too_large, label + ": shape overflows", seq);
    bytes *= e;
    array.shape.push_back(std::int64_t(e));
  }
  if (bytes > limits.max_array_bytes)
    throw DecodeError(ErrorCode::too_large,
                      label + " declares " + std::to_string(bytes) + " bytes; the limit is " + std::to_string(limits.max_array_bytes), seq);
  if (frame.size() != bytes)
    throw DecodeError(ErrorCode::bad_array,
                      label + ": shape and dtype give " + std::to_string(bytes) + " bytes but its frame has " + std::to_string(frame.size()), seq);
  array.bytes.assign(frame.begin(), frame.end());
  return array;
}

}  // namespace

Message decode(std::span<const std::span<const std::byte>> frames, const Limits& limits) {
  if (frames.empty()) throw DecodeError(ErrorCode::bad_message, "empty message: frame 0 must be the JSON header", std::nullopt);
  const auto header_frame = frames[0];
  if (header_frame.size() > limits.max_header_bytes)
    throw DecodeError(ErrorCode::too_large,
                      "header frame has " + std::to_string(header_frame.size()) + " bytes; the limit is " + std::to_string(limits.max_header_bytes),
                      std::nullopt);
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (frames[i].size() > limits.max_array_bytes)
      throw DecodeError(ErrorCode::too_large,
                        "frame " + std::to_string(i) + " has " + std::to_string(frames[i].size()) + " bytes; the limit is " +
                            std::to_string(limits.max_array_bytes),
                        std::nullopt);
  const std::string_view text(reinterpret_cast<const char*>(header_frame.data()), header_frame.size());
  nlohmann::json header;
  try {
    // Nesting is limited while parsing: the body is copied below, recursively,
    // and a header 131 000 levels deep (well under max_header_bytes) overflowed the stack.
    header = parse_json_text(text);
  } catch (const JsonTextError& e) {
    if (e.kind() == JsonTextError::Kind::too_deep)
      throw DecodeError(ErrorCode::bad_message, "frame 0 nests objects and arrays more than " + std::to_string(kMaxJsonNesting) +
                                                    " levels deep (at " + (e.key_path().empty() ? "the top level" : e.key_path()) + ")",
                        std::nullopt);
    throw DecodeError(ErrorCode::bad_message, "frame 0 is not a JSON object: " + std::string(e.what()), std::nullopt);
  }
  if (!header.is_object()) throw DecodeError(ErrorCode::bad_message, "frame 0 is not a JSON object", std::nullopt);

  // seq first, so every later error can name the request it answers.
  const std::optional<std::int64_t> seq = integer_field(header, "seq", std::nullopt, true);
  const auto protocol = header.find("protocol");
  if (protocol == header.end() || !protocol->is_string() || protocol->get<std::string>() != kProtocolName)
    throw DecodeError(ErrorCode::bad_message, "header field 'protocol' must be \"dfc\"", seq);
  const auto version = header.find("version");
  if (version == header.end() || !version->is_string() || !parse_version(version->get<std::string>()))
    throw DecodeError(ErrorCode::bad_message, "header field 'version' must be a string \"MAJOR.MINOR\"", seq);
  const auto type = header.find("type");
  if (type == header.end() || !type->is_string() || type->get<std::string>().empty())
    throw DecodeError(ErrorCode::bad_message, "header field 'type' must be a non-empty string", seq);

  Message message;
  message.type = type->get<std::string>();
  message.version = version->get<std::string>();
  message.seq = *seq;
  message.reply_to = integer_field(header, "reply_to", seq, false);
  message.step = integer_field(header, "step", seq, false);
  if (const auto body = header.find("body"); body != header.end() && !body->is_null()) {
    if (!body->is_object()) throw DecodeError(ErrorCode::bad_message, "header field 'body' must be an object", seq);
    message.body = *body;
  }

  const auto arrays = header.find("arrays");
  const std::size_t declared = (arrays == header.end() || arrays->is_null()) ? 0 : (arrays->is_array() ? arrays->size() : SIZE_MAX);
  if (declared == SIZE_MAX) throw DecodeError(ErrorCode::bad_message, "header field 'arrays' must be an array", seq);
  if (frames.size() - 1 > limits.max_arrays || declared > limits.max_arrays)
    throw DecodeError(ErrorCode::too_large, "more than " + std::to_string(limits.max_arrays) + " array frames", seq);
  if (declared != frames.size() - 1)
    throw DecodeError(ErrorCode::bad_array,
                      "header declares " + std::to_string(declared) + " arrays but " + std::to_string(frames.size() - 1) + " array frames follow",
                      seq);
  std::set<std::string> names;
  for (std::size_t i = 0; i < declared; ++i) {
    message.arrays.push_back(decode_array((*arrays)[i], frames[i + 1], i, limits, seq));
    if (!names.insert(message.arrays.back().name).second)
      throw DecodeError(ErrorCode::bad_array, "array name '" + message.arrays.back().name + "' appears twice", seq);
  }
  return message;
}

}  // namespace dfc::protocol
