// The animation page (graphics/animation.h): the JSON it embeds in a
// <script> holds no '<', '>' or '&' whatever the diagram names, so no name
// can end the element ("</script>") or hide the rest of the page ("<!--"
// with "<script>", the HTML parser's escaped script data).

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "graphics/animation.h"
#include "tests/cli/mechflow_command.h"
#include "tests/graphics/hostile_names.h"

namespace mechflow {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t i = 0; (i = text.find(what, i)) != std::string::npos; i += what.size()) ++n;
  return n;
}

TEST(ScriptSafeJsonTest, EscapesWhatTheHtmlParserReadsInAScript) {
  EXPECT_EQ(graphics::ScriptSafeJson("{\"a\":\"<!--<script></script>&\xE2\x80\xA8\xE2\x80\xA9\"}"),
            "{\"a\":\"\\u003c!--\\u003cscript\\u003e\\u003c/script\\u003e\\u0026\\u2028\\u2029\"}");
  // other text, UTF-8 included, as it was: U+2027, U+00E9, a backslash's escape
  EXPECT_EQ(graphics::ScriptSafeJson("{\"b\":\"\xE2\x80\xA7 \xC3\xA9 \\\\ [1,2]\"}"),
            "{\"b\":\"\xE2\x80\xA7 \xC3\xA9 \\\\ [1,2]\"}");
}

TEST(AnimationPageTest, NamesCannotEndOrHideTheDataScript) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("mechflow_animation_names_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "d.xml") << testing::kHostileNamesDiagram;
  const auto run = testing::RunMechflow("run " + (dir / "d.xml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string page = testing::ReadFile(dir / "out" / "d.html");
  const std::string open = "const MECHFLOW_DATA = ";
  const std::size_t start = page.find(open);
  ASSERT_NE(start, std::string::npos);
  const std::string json = page.substr(start + open.size(), page.find(";\n</script>", start) - start - open.size());
  EXPECT_THAT(json, HasSubstr("\\u003c!--\\u003cscript\\u003e"));  // the names are there, escaped
  for (const char* c : {"<", ">", "&", "\xE2\x80\xA8", "\xE2\x80\xA9"}) EXPECT_THAT(json, Not(HasSubstr(c)));
  // the page's own four scripts, each opened and closed once
  EXPECT_EQ(Count(page, "<script>"), 4);
  EXPECT_EQ(Count(page, "</script>"), 4);
  EXPECT_EQ(Count(page, "<!--"), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mechflow
