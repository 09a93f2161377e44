// SPEC.md §8: limits are enforced with TOO_LARGE, and what a header merely
// declares never makes the receiver allocate (checked with AllocationProbe).
#include <gtest/gtest.h>

#include <cstdint>
#include <new>

#include "allocation_probe.hpp"
#include "codec_test_support.hpp"

namespace dfc::protocol::testing {
namespace {

// Far above what decoding a small header needs, far below the sizes declared below.
constexpr std::size_t kSmallAllocation = 64 * 1024;

std::string ping_with_arrays(const std::string& arrays) {
  return R"({"protocol":"dfc","version":"1.0","type":"ping","seq":1,"arrays":)" + arrays + "}";
}

TEST(CodecLimits, HeaderAtTheLimitPassesAndOneByteMoreIsTooLarge) {
  Limits limits;
  limits.max_header_bytes = 200;
  const auto ping_padded = [](std::size_t pad) {
    std::string header = R"({"protocol":"dfc","version":"1.0","type":"ping","seq":1,"body":{"pad":")";
    header.append(pad, 'x');
    header.append(R"("}})");
    return header;
  };
  const std::size_t pad = limits.max_header_bytes - ping_padded(0).size();
  ASSERT_EQ(ping_padded(pad).size(), limits.max_header_bytes);
  EXPECT_NO_THROW((void)decode_texts({ping_padded(pad)}, limits));
  EXPECT_EQ(decode_error_code({ping_padded(pad + 1)}, limits), ErrorCode::too_large);
}

TEST(CodecLimits, OversizedArrayFrameIsTooLargeEvenWhenTheShapeMatches) {
  Limits limits;
  limits.max_array_bytes = 64;
  EXPECT_NO_THROW((void)decode_texts({ping_with_arrays(R"([{"name":"a","dtype":"f64","shape":[8]}])"), std::string(64, '\0')}, limits));
  EXPECT_EQ(decode_error_code({ping_with_arrays(R"([{"name":"a","dtype":"f64","shape":[9]}])"), std::string(72, '\0')}, limits),
            ErrorCode::too_large);
}

TEST(CodecLimits, MoreArraysThanAllowedIsTooLarge) {
  Limits limits;
  limits.max_arrays = 2;
  std::string descriptors = "[";
  std::vector<std::string> frames{""};
  for (int i = 0; i < 3; ++i) {
    descriptors += std::string(i ? "," : "") + R"({"name":"a)" + std::to_string(i) + R"(","dtype":"u8","shape":[0]})";
    frames.emplace_back();
  }
  frames[0] = ping_with_arrays(descriptors + "]");
  EXPECT_EQ(decode_error_code(frames, limits), ErrorCode::too_large);
  // Declaring too many is refused before the descriptors are looked at, even without frames.
  EXPECT_EQ(decode_error_code({frames[0]}, limits), ErrorCode::too_large);
}

TEST(CodecLimits, DeclaredShapeOverTheLimitIsTooLargeWithoutAllocating) {
  const std::vector<std::string> frames{ping_with_arrays(R"([{"name":"a","dtype":"f64","shape":[1000000000000000]}])"), std::string(8, '\0')};
  AllocationProbe probe;
  EXPECT_EQ(decode_error_code(frames), ErrorCode::too_large);
  EXPECT_LT(probe.largest(), kSmallAllocation);
}

TEST(CodecLimits, OverflowingShapeIsTooLargeWithoutAllocating) {
  // 2^40 cubed times 8 bytes overflows 64 bits: a naive product would wrap to a small number.
  const std::vector<std::string> frames{ping_with_arrays(R"([{"name":"a","dtype":"f64","shape":[1099511627776,1099511627776,1099511627776]}])"),
                                        std::string(8, '\0')};
  AllocationProbe probe;
  EXPECT_EQ(decode_error_code(frames), ErrorCode::too_large);
  EXPECT_LT(probe.largest(), kSmallAllocation);
}

TEST(CodecLimits, DeclaredShapeUnderTheLimitButLargerThanItsFrameIsBadArrayWithoutAllocating) {
  // 200 MB is allowed by the default limit; the 8-byte frame must be noticed before any copy.
  const std::vector<std::string> frames{ping_with_arrays(R"([{"name":"a","dtype":"f64","shape":[25000000]}])"), std::string(8, '\0')};
  AllocationProbe probe;
  EXPECT_EQ(decode_error_code(frames), ErrorCode::bad_array);
  EXPECT_LT(probe.largest(), kSmallAllocation);
}

TEST(CodecLimits, AllocationProbeSeesLargeAllocations) {
  // Guards the three tests above: the probe must notice an allocation of the size they rule out.
  AllocationProbe probe;
  std::vector<std::byte> big(1 << 20);
  EXPECT_GE(probe.largest(), big.size());
}

// A volatile sink keeps the compiler from eliding the new/delete pairs below.
void* volatile allocation_sink = nullptr;

TEST(CodecLimits, AllocationProbeSeesNothrowAndAlignedAllocations) {
  // libzmq allocates with new (std::nothrow) and over-aligned types use the
  // aligned forms: the probe must replace them all, or a sanitizer build pairs
  // its own allocation with our free and aborts before any test runs.
  struct alignas(256) OverAligned {
    std::byte bytes[200'000];
  };
  {
    AllocationProbe probe;
    auto* memory = new (std::nothrow) std::byte[300'000];
    allocation_sink = memory;
    EXPECT_GE(probe.largest(), 300'000u);
    delete[] memory;
  }
  {
    AllocationProbe probe;
    auto* aligned = new OverAligned;
    allocation_sink = aligned;
    EXPECT_GE(probe.largest(), sizeof(OverAligned));
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(aligned) % alignof(OverAligned), 0u);
    delete aligned;
  }
  {
    AllocationProbe probe;
    auto* aligned = new (std::nothrow) OverAligned;
    allocation_sink = aligned;
    EXPECT_GE(probe.largest(), sizeof(OverAligned));
    delete aligned;
  }
}

// SPEC.md §8 (1.1): a header nested far deeper than kMaxJsonNesting yet under
// max_header_bytes is BAD_MESSAGE. Decoding it used to copy the body
// recursively and kill dem_server and fdm_server with a stack overflow.
TEST(CodecLimits, HeaderNestedTooDeepIsBadMessageNotACrash) {
  constexpr std::size_t kLevels = 131'000;
  const std::string deep = R"({"protocol":"dfc","version":"1.0","type":"ping","seq":1,"body":{"x":)" + std::string(kLevels, '[') +
                           std::string(kLevels, ']') + "}}";
  ASSERT_LT(deep.size(), Limits{}.max_header_bytes);
  EXPECT_EQ(decode_error_code({deep}), ErrorCode::bad_message);
  // 64 levels (the header object is the first) still decode.
  const std::string at_limit = R"({"protocol":"dfc","version":"1.0","type":"ping","seq":1,"body":{"x":)" + std::string(62, '[') +
                               std::string(62, ']') + "}}";
  EXPECT_NO_THROW((void)decode_texts({at_limit}, Limits{}));
}

}  // namespace
}  // namespace dfc::protocol::testing
