#pragma once
// "Did you mean ...?" for names a user typed.

#include <string>
#include <string_view>
#include <vector>

namespace mechflow::blocks {

// Edit distance (insert, delete, substitute, swap neighbours), case-insensitive.
int EditDistance(std::string_view a, std::string_view b);

// The candidate closest to `name`, or "" when none is close enough to be a
// plausible typo: the distance may be about a third of the typed name's
// length (rounded), at least 1, so names of up to four letters get only
// suggestions one edit away, 5 to 7 letters two, 8 to 10 three.
std::string ClosestName(std::string_view name, const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" or "" — ready to append to a message.
std::string DidYouMean(std::string_view name, const std::vector<std::string>& candidates);

// "a, b, c" for listing what is valid.
std::string JoinNames(const std::vector<std::string>& names);

}  // namespace mechflow::blocks
