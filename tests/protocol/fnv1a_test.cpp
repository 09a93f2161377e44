// The scenario hash of SPEC.md §4.2: FNV-1a 64, 16 lowercase hex digits.
// Known vectors from the FNV reference test suite.
#include <gtest/gtest.h>

#include "dfc/common/version.hpp"

namespace dfc {
namespace {

TEST(Fnv1a64, MatchesKnownVectors) {
  EXPECT_EQ(fnv1a64_hex(""), "cbf29ce484222325");  // the offset basis itself
  EXPECT_EQ(fnv1a64_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(fnv1a64_hex("foobar"), "85944171f73967e8");
}

TEST(Fnv1a64, HashesEveryByteIncludingNulAndHighBytes) {
  using namespace std::string_view_literals;
  EXPECT_NE(fnv1a64_hex("a\0"sv), fnv1a64_hex("a"sv));
  EXPECT_NE(fnv1a64_hex("{}\n"), fnv1a64_hex("{}"));  // whitespace matters: the exact bytes are hashed
  const std::string hash = fnv1a64_hex("\xff\x80");
  EXPECT_EQ(hash.size(), 16u);
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos) << hash;
}

}  // namespace
}  // namespace dfc
