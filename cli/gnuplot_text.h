#pragma once
// Text for gnuplot scripts.

#include <algorithm>
#include <filesystem>
#include <string>

namespace mechflow::cli {

// A gnuplot single-quoted string, which gnuplot reads without backquote
// substitution or escapes: the quote itself is doubled, and a control
// character (a line break would end the string's line, and the next line
// would be a gnuplot command) becomes '?'. Diagram texts hold none (the
// loader refuses them); this keeps the script safe whatever it is given.
inline std::string GnuplotQuote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    if (c == '\'') out += "''";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) out += '?';
    else out += c;
  }
  return out + "'";
}

// The look of the `curve`-th curve (from 0) of a panel: ten colours (the
// Tableau 10 palette, none too pale on white), then the same ten dashed, then
// dotted, dash-dotted and dash-dot-dotted: fifty curves all look different
// (gnuplot's own order repeats its eight colours, all solid).
inline std::string CurveStyle(int curve) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  static const char* const kDashes[] = {"1", "(12,6)", "(3,4)", "(14,5,3,5)", "(14,5,3,5,3,5)"};
  constexpr int kColourCount = 10, kDashCount = 5;
  curve = std::max(0, curve);
  return "lc rgb '" + std::string(kColours[curve % kColourCount]) + "' dt " +
         kDashes[(curve / kColourCount) % kDashCount];
}

// The head of every plot script: the terminal (PNG, or SVG by the plot's
// extension) sized for `panels` panels of `panel_height` pixels, the CSV
// separator, grid, key and margins (fixed, so that stacked axes align), and
// the stacked layout under `title`.
inline std::string GnuplotPreamble(const std::string& plot_name, int panels, int panel_height, int right_margin,
                                   const std::string& title) {
  const bool svg = std::filesystem::path(plot_name).extension() == ".svg";
  panels = std::max(1, panels);
  return "# drawn by mechflow; edit and run again in this folder with: gnuplot " + GnuplotQuote(plot_name + ".gp") +
         "\nset terminal " + (svg ? "svg" : "pngcairo") + " size 1000," +
         std::to_string(std::min(4000, 120 + panel_height * panels)) + " noenhanced font 'sans,10'" +
         (svg ? " background rgb 'white'" : "") + "\nset output " + GnuplotQuote(plot_name) +
         "\nset datafile separator ','\nset grid\nset key outside right top\nset lmargin 12\nset rmargin " +
         std::to_string(right_margin) + "\nset multiplot layout " + std::to_string(panels) + ",1 title " +
         GnuplotQuote(title) + "\n";
}

}  // namespace mechflow::cli
