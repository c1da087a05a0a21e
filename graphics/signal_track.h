#pragma once
// SignalTrack: the logged signals as the animation's plot draws them, at the
// rate of the output rows (not of the frames: a peak between two frames is
// a peak all the same), in double precision, so the plot's values are the
// results CSV's.
//
// Up to `max_points` rows every row is kept. Past that, the run is cut into
// bins of time (at most max_points / 2; their width doubles, pairs merging,
// as the run goes on) and each bin keeps, per column, its smallest and its
// largest value in the order they came: two points per bin, drawn at the
// times of the bin's first and last row (the same time for a bin of one
// instant, rows at an event). The plot is a few hundred pixels
// wide, so a bin is narrower than a pixel column there, and every extreme of
// the run stays in the curve whatever its length.

#include <cstddef>
#include <vector>

namespace mechflow::graphics {

class SignalTrack {
 public:
  static constexpr std::size_t kMaxPoints = 4096;

  // `columns` values per row; `t_start`, `t_span`: the run's, for the bins.
  SignalTrack(std::size_t columns, double t_start, double t_span, std::size_t max_points = kMaxPoints);

  void Add(double t, const double* values);

  std::size_t columns() const { return columns_; }
  bool binned() const { return binned_; }
  // The points to draw, in time order: their times, and per point the
  // value of every column (point-major).
  std::vector<double> Times() const;
  std::vector<double> Values() const;

 private:
  struct Extreme {
    double low = 0.0, high = 0.0;
    double low_t = 0.0, high_t = 0.0;  // when each came (the first of equal ones)
  };
  struct Bin {
    long long index = 0;  // of width bin_width_ from t_start_
    double t_first = 0.0, t_last = 0.0;
    std::vector<Extreme> extremes;
  };
  void StartBinning();
  void AddToBins(double t, const double* values);
  void MergePairs();

  std::size_t columns_;
  double t_start_, bin_width_;
  std::size_t max_points_;
  bool binned_ = false;
  std::vector<double> times_, values_;  // every row, until binned
  std::vector<Bin> bins_;
};

}  // namespace mechflow::graphics
