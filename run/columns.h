#pragma once
// The names of a run's columns, in one place: a logged signal of width n
// gives n columns "name[0]" .. "name[n-1]" (width 1: "name"), after "time";
// a figure or column with a unit is headed "label [unit]" in the tables
// that put the unit into the header (the sweep summary).
// The first rule is blocks::LoggedColumnNames (blocks/outputs/column_names.h),
// which the simulator and the loader use too.

#include <string>
#include <vector>

#include "blocks/framework/diagram.h"

namespace mechflow::run {

// A results column: its name and the unit its values are in ("" unknown).
struct Column {
  std::string name;
  std::string unit;
};

// "time" and one name per logged element, in column order.
std::vector<std::string> ColumnNames(const std::vector<blocks::SignalRef>& logged);

// "label [unit]", or "label" when the unit is empty.
std::string WithUnit(const std::string& label, const std::string& unit);

}  // namespace mechflow::run
