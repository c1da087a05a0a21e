#pragma once
// CrossingSearch: watches the diagram's zero-crossing functions g_i(t) at the
// points the simulator checks them (every step end and every output time)
// and locates the first crossing between two such points.
//
// The simulator steps CVODE one step at a time and writes each step's rows
// from its interpolant, so the checks at output times are made here rather
// than by CVODE's root finding (which, called once per output time, cost
// more per row than the row itself: P1 in bench/README.md). The rules are
// CVODE's (cvode.c, cvRcheck1/3 and cvRootfind), so events are found where
// they were:
//   - a function exactly zero where the search starts is inactive until a
//     later check sees it nonzero (a contact starting exactly closed does not
//     fire at once);
//   - a crossing counts where g changes sign, or becomes exactly zero, in a
//     direction the function allows (rising, falling or either);
//   - between two checks the crossing is located by the Illinois method, a
//     secant method that halves the weight of an end kept twice
//     (K. L. Hiebert, L. F. Shampine, Implicitly defined output points for
//     solutions of ODEs, SAND80-0180, 1980), to within a tolerance ttol; the
//     crossing time returned is the end of the last bracket past the root, so
//     the state there is already across it;
//   - of several functions crossing in one bracket, the one whose secant
//     estimate lies nearest the lower end leads.

#include <functional>
#include <span>
#include <vector>

namespace mechflow::blocks {

class CrossingSearch {
 public:
  // Per function: +1 only rising crossings count, -1 only falling, 0 both.
  explicit CrossingSearch(std::vector<int> directions);

  int size() const { return static_cast<int>(directions_.size()); }

  // A new start at t with the values g there (after CVodeInit / ReInit).
  void Start(double t, std::span<const double> g);
  // Functions that were exactly zero at the start, not yet seen nonzero.
  bool AnyInactive() const;
  // A look just after the start (CVODE's probe a tenth of the first step
  // on): functions inactive since the start that are nonzero there become
  // active, with these values as their lower end.
  void Probe(std::span<const double> g);

  // Whether g (at a check after the last accepted one) shows a crossing.
  bool Crosses(std::span<const double> g) const;
  // No crossing up to t: (t, g) becomes the lower end of the next check.
  void Accept(double t, std::span<const double> g);

  // g changed at t_hi (Crosses was true): locates the first crossing in
  // (t_lo, t_hi], evaluating `g_at(t, out)` inside, to within `ttol`.
  // Returns the crossing time; directions_found() then says, per function,
  // +1 (rose through zero there), -1 (fell) or 0. Throws what g_at throws.
  double Locate(double t_hi, std::span<const double> g_hi, double ttol,
                const std::function<void(double, std::span<double>)>& g_at);
  const std::vector<int>& directions_found() const { return found_; }

  double lower_time() const { return t_lo_; }
  int evaluations() const { return evaluations_; }  // g_at calls made by Locate, in all

 private:
  // The leading function between lower values lo and upper values hi: the
  // one with the largest |hi/(hi - lo)| among those changing sign. -1 if
  // none; `zero` tells whether one became exactly zero.
  int Leader(std::span<const double> lo, std::span<const double> hi, bool* zero) const;
  bool Counts(int i, double lo) const { return directions_[i] * lo <= 0.0; }

  std::vector<int> directions_;
  std::vector<char> active_;
  int inactive_ = 0;  // functions not active
  std::vector<double> g_lo_;                            // at the last accepted check
  std::vector<double> bracket_lo_, bracket_hi_, trial_;  // Locate's
  std::vector<int> found_;
  double t_lo_ = 0.0;
  int evaluations_ = 0;
};

}  // namespace mechflow::blocks
