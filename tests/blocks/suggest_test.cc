// "Did you mean": swapped letters count once; short names get only close suggestions.
#include "blocks/suggest.h"

#include <gtest/gtest.h>

namespace mechflow::blocks {
namespace {

TEST(SuggestTest, SwappedNeighboursAreOneEdit) {
  EXPECT_EQ(EditDistance("rnu", "run"), 1);
  EXPECT_EQ(EditDistance("Gain", "gian"), 1);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3);
  EXPECT_EQ(ClosestName("rnu", {"run", "check"}), "run");
}

TEST(SuggestTest, ShortNamesGetNoFarFetchedSuggestion) {
  EXPECT_EQ(ClosestName("q", {"xy", "v0"}), "");     // two edits away from a 1-letter name
  EXPECT_EQ(ClosestName("v", {"v0", "q0"}), "v0");    // one edit
  EXPECT_EQ(ClosestName("omga", {"omega", "alpha"}), "omega");
  EXPECT_EQ(DidYouMean("zzzz", {"mass"}), "");
}

}  // namespace
}  // namespace mechflow::blocks
