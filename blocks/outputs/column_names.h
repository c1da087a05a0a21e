#pragma once
// The one rule naming a run's results columns: a logged signal of width 1
// gives the column "name", of width n the columns "name[0]" .. "name[n-1]".
// The simulator's results, the loader's checks of <spectrum> and <xy>
// columns and run/ (which puts "time" first) all name columns through it.

#include <string>
#include <vector>

#include "blocks/framework/diagram.h"

namespace mechflow::blocks {

// The column names of `logged`, in column order (without "time").
std::vector<std::string> LoggedColumnNames(const std::vector<SignalRef>& logged);

}  // namespace mechflow::blocks
