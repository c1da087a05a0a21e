#pragma once
// Which diagram file wrote which files of an output folder, so that two
// diagram files whose outputs are named alike (a copied file keeps its
// <diagram name>) cannot silently overwrite each other's results in one --out.
//
// A command names its files after a stem: the results d.csv and, beside them,
// d.units.csv, d.report.csv, d.run1.beta=0.1.csv, d.sweep.csv, d.modes.csv;
// the plot d.png with d.png.gp; the animation d.html. The folder keeps the
// text file .mechflow-outputs, a line per stem: STEM, a tab, the absolute
// path of the diagram file that wrote it (a later line for a stem replaces
// an earlier one; '#' starts a comment). Before a command writes anything, its
// stems are checked against that record: a stem another diagram file wrote is
// refused (bad input) unless --overwrite hands it over; the same diagram file
// writing again, the everyday case, passes without a word. The record is
// locked (flock) while it is read and added to, so commands started together
// into one folder see each other's stems.

#include <ostream>
#include <string>
#include <vector>

#include "cli/output_folder.h"

namespace mechflow::cli {

// The record's file name in the output folder.
inline constexpr char kOutputRecordName[] = ".mechflow-outputs";

struct OutputStem {
  std::string stem;    // "d"
  std::string origin;  // where the name comes from, for messages: "<output csv=\"d.csv\">"
};

// The stem of an output file name: d.csv -> d, d.png -> d, d.x.csv -> d.x.
std::string StemOf(const std::string& file_name);

// The absolute path that stands for `diagram_file` in the record (symbolic
// links and ".." resolved, so every spelling of one file is one diagram).
std::string DiagramIdentity(const std::string& diagram_file);

// Checks `stems` against the folder's record and, with `record`, adds the
// ones not yet recorded for `diagram_file`. A stem recorded for another
// diagram file throws InputError naming both files and what to do, unless
// `overwrite`: then it is recorded for `diagram_file` and said on `out`.
// InputError for a record that cannot be read (naming its line); WriteError
// when it cannot be written. `record` false only checks (an MPI process
// other than the one that records).
void ClaimStems(const OutputFolder& folder, const std::string& diagram_file, const std::vector<OutputStem>& stems,
                bool overwrite, bool record, std::ostream& out);

}  // namespace mechflow::cli
