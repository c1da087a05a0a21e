// "Did you mean": swapped letters count once; the distance allowed is about a
// third of the typed name, so short names get only close suggestions.
#include "blocks/support/suggest.h"

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

TEST(SuggestTest, DistanceAllowedGrowsWithAThirdOfTheName) {
  // one letter: only one edit
  EXPECT_EQ(ClosestName("k", {"c"}), "c");
  EXPECT_EQ(ClosestName("k", {"mu", "xy"}), "");
  // up to four letters: one edit
  EXPECT_EQ(ClosestName("rmap", {"ramp"}), "ramp");  // a swap
  EXPECT_EQ(ClosestName("step", {"sine", "stop"}), "stop");
  EXPECT_EQ(ClosestName("mass", {"max"}), "");       // two edits
  EXPECT_EQ(ClosestName("tabl", {"abs"}), "");
  // five to seven letters: two edits
  EXPECT_EQ(ClosestName("sinus", {"sine"}), "sine");
  EXPECT_EQ(ClosestName("stifnes", {"stiffness"}), "stiffness");
  EXPECT_EQ(ClosestName("offst", {"output"}), "");   // four edits
  // eight to ten letters: three edits
  EXPECT_EQ(ClosestName("dampng_k", {"damping"}), "damping");
  EXPECT_EQ(ClosestName("tme_cnst", {"time_constant"}), "");  // five edits
  EXPECT_EQ(ClosestName("time_const", {"time_constant"}), "time_constant");
}

}  // namespace
}  // namespace mechflow::blocks
