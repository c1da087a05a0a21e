#pragma once
// What `mechflow fit` prints and writes: what it printed (NAME.fit.txt), the
// parameter table (NAME.fit.csv),
// the fitted values as --set lines (NAME.fit.set, for `mechflow run
// --set-file`), the correlation matrix (NAME.fit.correlation.csv), the cost
// history (NAME.fit.history.csv), per experiment the measured and simulated
// signals at the measured times (NAME.fit.dataK.csv), and the plot of those
// over one another with the cost history (NAME.fit.png).

#include <ostream>
#include <string>
#include <vector>

#include "analysis/fit/fit.h"
#include "cli/output_folder.h"

namespace mechflow::cli {

struct FitReport {
  std::string stem;     // NAME
  std::string diagram;  // the diagram file
  const analysis::fit::Setup* setup = nullptr;
  const analysis::fit::FitResult* result = nullptr;
};

// The table of parameters, the correlations, the cost before and after.
void PrintFit(const FitReport& report, std::ostream& out);

// Writes the files; returns their names in the order written. The plot is
// drawn last: "" or a warning why not (gnuplot missing) in `plot_warning`.
// `summary`: what was printed (the table, correlations, costs, runs), as NAME.fit.txt.
std::vector<std::string> WriteFit(const FitReport& report, const std::string& summary, const OutputFolder& folder, bool plot,
                                  std::string* plot_warning);

}  // namespace mechflow::cli
