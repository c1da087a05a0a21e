#include "cli/plot_envelope.h"

#include <algorithm>
#include <cmath>

#include "blocks/outputs/csv.h"

namespace mechflow::cli {
namespace {

// the first bins are this much narrower than a kBins-th of the run, so that
// a run ending early still fills at least kBins / 2 of them
constexpr double kFirstWidthDivisor = 1024.0;

void AppendNumbers(const std::vector<double>& values, std::string* line) {
  for (const double v : values) *line += "," + blocks::CsvNumber(v);
}

}  // namespace

PlotEnvelope::PlotEnvelope(std::vector<int> columns, std::vector<int> xy_columns, double t_span,
                           blocks::RowSink* next)
    : columns_(std::move(columns)),
      xy_columns_(std::move(xy_columns)),
      next_(next),
      width_(t_span > 0 && std::isfinite(t_span) ? t_span / kBins / kFirstWidthDivisor : 1e-9),
      count_(kBins, 0),
      t_first_(kBins),
      t_last_(kBins),
      min_(static_cast<std::size_t>(kBins) * columns_.size()),
      max_(min_.size()),
      picks_(static_cast<std::size_t>(kBins) * 2 * xy_columns_.size()) {}

void PlotEnvelope::WriteRow(const double* values, int count) {
  if (next_) next_->WriteRow(values, count);
  if (rows_ == 0) {
    first_.assign(values, values + count);
    t0_ = values[0];
  } else {
    if (rows_ >= 2) Fold(pending_.data(), rows_ - 1);
    pending_.assign(values, values + count);
  }
  ++rows_;
}

void PlotEnvelope::Fold(const double* values, long long row) {
  const double t = values[0];
  double x = std::isfinite(t) ? (t - t0_) / width_ : 0.0;
  while (!(x < kBins)) {
    Halve();
    x = (t - t0_) / width_;
  }
  // rows in time order; a bin holds consecutive rows whatever the times do
  const int b = std::max(last_bin_, x > 0 ? static_cast<int>(x) : 0);
  last_bin_ = b;
  const std::size_t n = columns_.size();
  double* lo = &min_[b * n];
  double* hi = &max_[b * n];
  if (count_[b] == 0) {
    t_first_[b] = t;
    for (std::size_t k = 0; k < n; ++k) lo[k] = hi[k] = values[columns_[k]];
  } else {
    for (std::size_t k = 0; k < n; ++k) {
      lo[k] = std::min(lo[k], values[columns_[k]]);
      hi[k] = std::max(hi[k], values[columns_[k]]);
    }
  }
  ++count_[b];
  t_last_[b] = t;
  const std::size_t m = xy_columns_.size();
  for (std::size_t j = 0; j < m; ++j) {
    const double v = values[xy_columns_[j]];
    for (int side = 0; side < 2; ++side) {
      Pick& p = picks_[(b * m + j) * 2 + side];
      if (p.row >= 0 && !(side == 0 ? v < p.values[1 + j] : v > p.values[1 + j])) continue;
      p.row = row;
      p.values.assign(1, t);
      for (const int c : xy_columns_) p.values.push_back(values[c]);
    }
  }
}

void PlotEnvelope::Halve() {
  const std::size_t n = columns_.size(), m = xy_columns_.size();
  for (int to = 0; to < kBins / 2; ++to) {
    const int a = 2 * to, b = a + 1;  // a before b; either may be empty (`to` may be a)
    const bool both = count_[a] && count_[b];
    const int first = count_[a] ? a : b, last = count_[b] ? b : a;
    count_[to] = count_[a] + count_[b];
    t_first_[to] = t_first_[first];
    t_last_[to] = t_last_[last];
    for (std::size_t k = 0; k < n; ++k) {
      const double lo = both ? std::min(min_[a * n + k], min_[b * n + k]) : min_[first * n + k];
      const double hi = both ? std::max(max_[a * n + k], max_[b * n + k]) : max_[first * n + k];
      min_[to * n + k] = lo;
      max_[to * n + k] = hi;
    }
    for (std::size_t j = 0; j < m; ++j)
      for (int side = 0; side < 2; ++side) {
        Pick pa = picks_[(a * m + j) * 2 + side], pb = picks_[(b * m + j) * 2 + side];
        const bool take_b = pa.row < 0 || (pb.row >= 0 && (side == 0 ? pb.values[1 + j] < pa.values[1 + j]
                                                                     : pb.values[1 + j] > pa.values[1 + j]));
        picks_[(to * m + j) * 2 + side] = take_b ? std::move(pb) : std::move(pa);
      }
  }
  std::fill(count_.begin() + kBins / 2, count_.end(), 0);
  for (auto p = picks_.begin() + static_cast<std::ptrdiff_t>(kBins / 2 * m * 2); p != picks_.end(); ++p) *p = {};
  last_bin_ /= 2;
  width_ *= 2;
}

std::string PlotEnvelope::Csv(const std::vector<std::string>& names) const {
  std::string s = "rows,t_first,t_last,time";
  for (const int c : columns_) s += "," + blocks::CsvField(names[c] + " min") + "," + blocks::CsvField(names[c] + " max");
  s += '\n';
  // the first and last rows: bins of one row each
  const auto single = [&](const std::vector<double>& row) {
    const std::string t = blocks::CsvNumber(row[0]);
    s += "1," + t + "," + t + "," + t;
    for (const int c : columns_) s += "," + blocks::CsvNumber(row[c]) + "," + blocks::CsvNumber(row[c]);
    s += '\n';
  };
  if (rows_ >= 1) single(first_);
  const std::size_t n = columns_.size();
  for (int b = 0; b < kBins; ++b) {
    if (!count_[b]) continue;
    s += std::to_string(count_[b]) + "," + blocks::CsvNumber(t_first_[b]) + "," + blocks::CsvNumber(t_last_[b]) +
         "," + blocks::CsvNumber(0.5 * (t_first_[b] + t_last_[b]));
    for (std::size_t k = 0; k < n; ++k) s += "," + blocks::CsvNumber(min_[b * n + k]) + "," + blocks::CsvNumber(max_[b * n + k]);
    s += '\n';
  }
  if (rows_ >= 2) single(pending_);
  return s;
}

std::vector<int> PlottedColumns(const std::vector<diagrams::PlotGroup>& groups) {
  std::vector<int> columns;
  for (const diagrams::PlotGroup& g : groups)
    for (const int c : g.columns)
      if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.push_back(c);
  return columns;
}

int EnvelopeMinColumn(const std::vector<int>& columns, int column) {
  return 5 + 2 * static_cast<int>(std::find(columns.begin(), columns.end(), column) - columns.begin());
}

std::string PlotEnvelope::XYCsv(const std::vector<std::string>& names) const {
  std::string s = "time";
  for (const int c : xy_columns_) s += "," + blocks::CsvField(names[c]);
  s += '\n';
  const auto row = [&](const std::vector<double>& values) {
    s += blocks::CsvNumber(values[0]);
    for (const int c : xy_columns_) s += "," + blocks::CsvNumber(values[c]);
    s += '\n';
  };
  if (rows_ >= 1) row(first_);
  const std::size_t m = xy_columns_.size();
  std::vector<const Pick*> bin;
  for (int b = 0; b < kBins; ++b) {
    bin.clear();
    for (std::size_t k = 0; k < 2 * m; ++k)
      if (picks_[b * 2 * m + k].row >= 0) bin.push_back(&picks_[b * 2 * m + k]);
    std::sort(bin.begin(), bin.end(), [](const Pick* a, const Pick* b) { return a->row < b->row; });
    for (std::size_t i = 0; i < bin.size(); ++i) {
      if (i && bin[i]->row == bin[i - 1]->row) continue;
      s += blocks::CsvNumber(bin[i]->values[0]);
      std::vector<double> rest(bin[i]->values.begin() + 1, bin[i]->values.end());
      AppendNumbers(rest, &s);
      s += '\n';
    }
  }
  if (rows_ >= 2) row(pending_);
  return s;
}

int PlotEnvelope::XYColumn(int column) const {
  return 2 + static_cast<int>(std::find(xy_columns_.begin(), xy_columns_.end(), column) - xy_columns_.begin());
}

}  // namespace mechflow::cli
