// SPEC.md §3, §7, §8: malformed headers, disagreeing array descriptors and
// over-limit frames each get the right error, and the server keeps running
// (the runner pings after each). The arrays ride on `ping`, which is allowed
// in every state, so the arrays are the only thing wrong with the message.
#include "check.hpp"
#include "context.hpp"
#include "expectations.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

constexpr std::size_t kLargestHeaderTried = 64u << 20;  // beyond that, the test itself would be the problem
constexpr std::size_t kMostArraysTried = 100'000;

nlohmann::json descriptor(std::string_view name, std::string_view dtype, nlohmann::json shape) {
  return {{"name", name}, {"dtype", dtype}, {"shape", std::move(shape)}};
}

/// Sends `header` plus `arrays` as frames and expects one of `codes`; the
/// header carries a seq, so the error must answer it when it names one.
void expect_refused(Context& context, const nlohmann::json& header, const std::vector<std::string>& arrays,
                    std::initializer_list<std::string_view> codes) {
  std::vector<std::string> frames{header.dump()};
  frames.insert(frames.end(), arrays.begin(), arrays.end());
  const protocol::Message reply = context.send_frames(frames);
  expect_error(reply, codes);
  if (header.contains("seq") && reply.reply_to)
    expect(*reply.reply_to == header["seq"].get<std::int64_t>(),
           "the error has reply_to " + std::to_string(*reply.reply_to) + " but the request's seq was " + header["seq"].dump());
}

void unknown_type(Context& context) { expect_refused(context, context.raw_header("teleport"), {}, {"UNKNOWN_TYPE"}); }

void header_not_json(Context& context) {
  expect_error(context.send_frames({"this is {not JSON"}), {"BAD_MESSAGE"});
}

void header_not_object(Context& context) { expect_error(context.send_frames({"[1, 2, 3]"}), {"BAD_MESSAGE"}); }

void header_without_type(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header.erase("type");
  expect_refused(context, header, {}, {"BAD_MESSAGE"});
}

void header_without_seq(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header.erase("seq");
  expect_refused(context, header, {}, {"BAD_MESSAGE"});
}

void wrong_protocol_name(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["protocol"] = "not-dfc";
  expect_refused(context, header, {}, {"BAD_MESSAGE"});
}

void body_not_object(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["body"] = "a string";
  expect_refused(context, header, {}, {"BAD_MESSAGE"});
}

void header_over_limit(Context& context) {
  const std::size_t limit = context.limits.max_header_bytes;
  if (limit > kLargestHeaderTried) throw NotApplicable("max_header_bytes " + std::to_string(limit) + " is too large to exceed in a test");
  // Valid JSON of exactly limit + 1 bytes, so only its size is wrong.
  nlohmann::json header = context.raw_header("ping");
  header["body"] = {{"pad", ""}};
  const std::size_t base = header.dump().size();
  if (base <= limit) header["body"]["pad"] = std::string(limit + 1 - base, 'x');
  expect_refused(context, header, {}, {"TOO_LARGE"});
}

// SPEC.md §8 (1.1): a header nested far deeper than 64 levels, yet under
// max_header_bytes, gets BAD_MESSAGE; a server that parses it into a tree and
// copies it recursively dies of a stack overflow instead.
void header_nested_too_deep(Context& context) {
  constexpr std::size_t kLevels = 100'000;
  std::string header = context.raw_header("ping").dump();
  const std::string nested = ",\"deep\":" + std::string(kLevels, '[') + std::string(kLevels, ']');
  if (header.size() + nested.size() > context.limits.max_header_bytes)
    throw NotApplicable("max_header_bytes " + std::to_string(context.limits.max_header_bytes) + " is too small for a deeply nested header");
  header.insert(header.size() - 1, nested);  // before the closing brace
  expect_error(context.send_frames({header}), {"BAD_MESSAGE"});
}

void too_many_arrays(Context& context) {
  const std::size_t count = context.limits.max_arrays + 1;
  if (count > kMostArraysTried) throw NotApplicable("max_arrays " + std::to_string(count - 1) + " is too large to exceed in a test");
  nlohmann::json header = context.raw_header("ping");
  header["arrays"] = nlohmann::json::array();
  for (std::size_t i = 0; i < count; ++i) header["arrays"].push_back(descriptor(std::to_string(i), "u8", {0}));
  expect_refused(context, header, std::vector<std::string>(count), {"TOO_LARGE"});
}

void descriptor_count_differs_from_frames(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["arrays"] = {descriptor("a", "f64", {1}), descriptor("b", "f64", {1})};
  expect_refused(context, header, {std::string(8, '\0')}, {"BAD_ARRAY"});
}

void frame_length_differs_from_shape(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["arrays"] = {descriptor("a", "f64", {3})};
  expect_refused(context, header, {std::string(16, '\0')}, {"BAD_ARRAY"});
}

void unknown_dtype(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["arrays"] = {descriptor("a", "c128", {1})};
  expect_refused(context, header, {std::string(16, '\0')}, {"BAD_ARRAY"});
}

void negative_extent(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["arrays"] = {descriptor("a", "f64", {-1})};
  expect_refused(context, header, {std::string(8, '\0')}, {"BAD_ARRAY"});
}

void duplicate_array_names(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["arrays"] = {descriptor("a", "f64", {1}), descriptor("a", "f64", {1})};
  expect_refused(context, header, {std::string(8, '\0'), std::string(8, '\0')}, {"BAD_ARRAY"});
}

// A server that believed the shape would try to allocate 8 PB; the reply
// (and the ping after it) show it checked the size before allocating.
void huge_declared_shape(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  header["arrays"] = {descriptor("a", "f64", {1'000'000'000'000'000LL})};
  expect_refused(context, header, {std::string(8, '\0')}, {"TOO_LARGE", "BAD_ARRAY"});
}

void overflowing_shape(Context& context) {
  nlohmann::json header = context.raw_header("ping");
  const std::int64_t big = std::int64_t(1) << 40;  // big^3 * 8 overflows 64 bits
  header["arrays"] = {descriptor("a", "f64", {big, big, big})};
  expect_refused(context, header, {std::string(8, '\0')}, {"TOO_LARGE", "BAD_ARRAY"});
}

// SPEC.md §3.1 (1.4): a server numbers every reply it sends, one counter for
// all of them, so the reply to a message it could not decode takes the next
// number too; that reply has no reply_to, since no seq could be read.
void replies_are_numbered_in_sending_order(Context& context) {
  const protocol::Message before = context.request(protocol::type::ping);
  const protocol::Message refused = context.send_frames({"this is {not JSON"});
  const protocol::Message after = context.request(protocol::type::ping);
  expect_error(refused, {"BAD_MESSAGE"});
  expect(!refused.reply_to.has_value(), "the error to an undecodable message has reply_to " +
                                            (refused.reply_to ? std::to_string(*refused.reply_to) : std::string()) + ", but it answers no seq");
  expect(refused.seq == before.seq + 1 && after.seq == refused.seq + 1,
         "three replies in a row carry seq " + std::to_string(before.seq) + ", " + std::to_string(refused.seq) + ", " +
             std::to_string(after.seq) + "; a server numbers its replies 0, 1, 2, ... in sending order, errors to undecodable messages included");
}

}  // namespace

std::vector<Check> malformed_message_checks() {
  using M = Milestone;
  return {
      {"malformed.unknown_type", "type 'teleport' gets UNKNOWN_TYPE", M::greeted, M::none, true, unknown_type},
      {"malformed.header_not_json", "a header frame that is not JSON gets BAD_MESSAGE", M::greeted, M::none, true, header_not_json},
      {"malformed.header_not_object", "a JSON header that is not an object gets BAD_MESSAGE", M::greeted, M::none, true, header_not_object},
      {"malformed.missing_type", "a header without 'type' gets BAD_MESSAGE", M::greeted, M::none, true, header_without_type},
      {"malformed.missing_seq", "a header without 'seq' gets BAD_MESSAGE", M::greeted, M::none, true, header_without_seq},
      {"malformed.wrong_protocol", "protocol 'not-dfc' gets BAD_MESSAGE", M::greeted, M::none, true, wrong_protocol_name},
      {"malformed.body_not_object", "a 'body' that is not an object gets BAD_MESSAGE", M::greeted, M::none, true, body_not_object},
      {"limits.header_too_large", "a header of max_header_bytes + 1 bytes gets TOO_LARGE", M::greeted, M::none, true, header_over_limit},
      {"limits.nesting_too_deep", "a header nested 100 000 levels deep gets BAD_MESSAGE (1.1)", M::greeted, M::none, true,
       header_nested_too_deep, 1},
      {"limits.too_many_arrays", "max_arrays + 1 array frames get TOO_LARGE", M::greeted, M::none, true, too_many_arrays},
      {"arrays.count_mismatch", "2 descriptors with 1 frame get BAD_ARRAY", M::greeted, M::none, true, descriptor_count_differs_from_frames},
      {"arrays.length_mismatch", "f64 [3] in a 16-byte frame gets BAD_ARRAY", M::greeted, M::none, true, frame_length_differs_from_shape},
      {"arrays.unknown_dtype", "dtype 'c128' gets BAD_ARRAY", M::greeted, M::none, true, unknown_dtype},
      {"arrays.negative_extent", "shape [-1] gets BAD_ARRAY", M::greeted, M::none, true, negative_extent},
      {"arrays.duplicate_names", "two arrays named 'a' get BAD_ARRAY", M::greeted, M::none, true, duplicate_array_names},
      {"arrays.huge_declared_shape", "f64 [1e15] in an 8-byte frame gets TOO_LARGE or BAD_ARRAY without allocating", M::greeted, M::none,
       true, huge_declared_shape},
      {"arrays.overflowing_shape", "a shape whose byte size overflows 64 bits gets TOO_LARGE or BAD_ARRAY", M::greeted, M::none, true,
       overflowing_shape},
      {"malformed.reply_seq_order", "reply seqs go up by one across replies, an undecodable message's error included (1.4)", M::greeted,
       M::none, true, replies_are_numbered_in_sending_order, 4},
  };
}

}  // namespace dfc::conformance
