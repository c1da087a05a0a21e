#include "blocks/library/piecewise_linear.h"

namespace mechflow::blocks {
namespace {

// Mode of an element whose input is on a corner (and before the first
// classification, as inputs are not valid in Initialize): y follows u exactly.
constexpr double kExact = -1.0;

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
  return mode >= 0 && mode <= n && (mode == 0 || u > corners_[mode - 1]) && (mode == n || u < corners_[mode]);
}

void PiecewiseLinearBlock::DoInitialize(const BlockContext& ctx) const {
  // inputs are not valid yet: UpdateModes classifies once they are
  for (double& mode : ctx.discrete()) mode = kExact;
}

void PiecewiseLinearBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto y = ctx.output(0);
  const auto modes = ctx.discrete();
  for (size_t i = 0; i < y.size(); ++i) {
    const int mode = modes[i] == kExact ? Classify(u[i]) : static_cast<int>(modes[i]);
    y[i] = Piece(mode, u[i]);
  }
}

void PiecewiseLinearBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  const auto u = ctx.input(0);
  const auto g = ctx.zero_crossings();
  const size_t n = corners_.size();
  for (size_t i = 0; i < u.size(); ++i)
    for (size_t k = 0; k < n; ++k) g[i * n + k] = u[i] - corners_[k];
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
    const int piece = Classify(u[i]);
    // on a corner: exact, since leaving it might give no event
    const bool on_corner = piece > 0 && u[i] == corners_[piece - 1];
    const double mode = on_corner ? kExact : InsidePiece(static_cast<int>(modes[i]), u[i]) ? modes[i] : piece;
    changed |= mode != modes[i];
    modes[i] = mode;
  }
  return changed;
}

}  // namespace mechflow::blocks
