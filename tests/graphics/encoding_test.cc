// The text encodings of the animation files (graphics/encoding.h).

#include <string>

#include <gtest/gtest.h>

#include "graphics/encoding.h"

namespace mechflow::graphics {
namespace {

TEST(EncodingTest, Base64FollowsRfc4648) {
  const auto of = [](const std::string& s) { return Base64(s.data(), s.size()); };
  EXPECT_EQ(of(""), "");
  EXPECT_EQ(of("f"), "Zg==");
  EXPECT_EQ(of("fo"), "Zm8=");
  EXPECT_EQ(of("foo"), "Zm9v");
  EXPECT_EQ(of("foobar"), "Zm9vYmFy");
  const unsigned char high[] = {0xff, 0xfe, 0x00};
  EXPECT_EQ(Base64(high, 3), "//4A");
}

TEST(EncodingTest, QuotedEscapesWhatJsonNeeds) {
  EXPECT_EQ(Quoted("car.Body"), "\"car.Body\"");
  EXPECT_EQ(Quoted("a \"b\" \\ c"), "\"a \\\"b\\\" \\\\ c\"");
  EXPECT_EQ(Quoted("tab\there\n"), "\"tab\\u0009here\\u000a\"");
}

}  // namespace
}  // namespace mechflow::graphics
