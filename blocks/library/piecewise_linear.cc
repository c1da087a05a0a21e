#include "blocks/library/piecewise_linear.h"

#include <cstdio>

#include "blocks/library/hysteresis.h"

namespace mechflow::blocks {
namespace {

// Mode before the first classification (inputs are not valid in
// Initialize): y follows u on the piece u lies in.
constexpr double kUnclassified = -1.0;

}  // namespace

PiecewiseLinearBlock::PiecewiseLinearBlock(const std::string& type, const std::string& name,
                                           std::vector<double> corners, int width)
    : Block(type, name), corners_(std::move(corners)) {
  DeclareInputPort("u", width);
  DeclareOutputPort("y", width);
  DeclareDiscreteStates(width);
  for (int i = 0; i < width * static_cast<int>(corners_.size()); ++i) DeclareZeroCrossing(CrossingDirection::kEither);
}

int PiecewiseLinearBlock::Classify(double u) const {
  int mode = 0;
  while (mode < static_cast<int>(corners_.size()) && u >= corners_[mode]) ++mode;
  return mode;
}

bool PiecewiseLinearBlock::InsidePiece(int mode, double u) const {
  const int n = static_cast<int>(corners_.size());
  return mode >= 0 && mode <= n && (mode == 0 || u > corners_[mode - 1] - CornerBand(corners_[mode - 1])) &&
         (mode == n || u < corners_[mode] + CornerBand(corners_[mode]));
}

void PiecewiseLinearBlock::DoInitialize(const BlockContext& ctx) const {
  for (double& mode : ctx.discrete()) mode = kUnclassified;
}

void PiecewiseLinearBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto y = ctx.output(0);
  const auto modes = ctx.discrete();
  for (size_t i = 0; i < y.size(); ++i) {
    const int mode = modes[i] == kUnclassified ? Classify(u[i]) : static_cast<int>(modes[i]);
    y[i] = Piece(mode, u[i]);
  }
}

void PiecewiseLinearBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto g = ctx.zero_crossings();
  const auto modes = ctx.discrete();
  const size_t n = corners_.size();
  for (size_t i = 0; i < u.size(); ++i)
    for (size_t k = 0; k < n; ++k) {
      // above corner k: an event once u falls below it by the band; below:
      // once it rises above it by the band
      const double band = CornerBand(corners_[k]);
      g[i * n + k] = u[i] - corners_[k] + (modes[i] > static_cast<double>(k) ? band : -band);
    }
}

std::string PiecewiseLinearBlock::CrossingName(int index, int direction) const {
  const int n = static_cast<int>(corners_.size());
  const std::string u = input_port(0).width > 1 ? "u[" + std::to_string(index / n) + "]" : "u";
  char corner[32];
  std::snprintf(corner, sizeof corner, "%g", corners_[index % n]);
  return u + (direction > 0 ? " rises past " : " falls past ") + corner;
}

void PiecewiseLinearBlock::DoZeroCrossing(int index, int direction, const BlockContext& ctx) const {
  const int n = static_cast<int>(corners_.size());
  const int element = index / n, corner = index % n;
  // rising through corner k enters piece k+1; falling enters piece k
  ctx.discrete()[element] = direction > 0 ? corner + 1 : corner;
}

bool PiecewiseLinearBlock::DoUpdateModes(const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto modes = ctx.discrete();
  bool changed = false;
  for (size_t i = 0; i < u.size(); ++i) {
    const double mode = InsidePiece(static_cast<int>(modes[i]), u[i]) ? modes[i] : Classify(u[i]);
    changed |= mode != modes[i];
    modes[i] = mode;
  }
  return changed;
}

}  // namespace mechflow::blocks
