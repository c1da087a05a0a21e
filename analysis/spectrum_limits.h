#pragma once
// The bound on a power spectral density's work (analysis/spectrum.h), in a
// header of its own so that the diagram loader can check a <spectrum>'s
// overlap before the run without depending on the analysis library.
//
// The overlap is at most kMaxOverlap, and the segments together may cover
// the signal at most kMaxCoverage times over (segments x segment <=
// kMaxCoverage x samples): each sample is transformed about
// 1 / (1 - overlap) times, so an overlap of 0.9999999 would transform a
// million samples in 750,000 segments (hours of FFTs for no better
// estimate than at 0.5).

namespace mechflow::analysis {

inline constexpr double kMaxOverlap = 0.99;
inline constexpr int kMaxCoverage = 100;

}  // namespace mechflow::analysis
