#pragma once
// Lookup tables of signals: y = f(u) (1-D) and y = f(u1, u2) (2-D), with the
// interpolation and extrapolation of blocks/library/interpolation.h.
//
//   lookup     input u, output y (width 1); u feeds y directly
//   lookup_2d  inputs u1 (along the rows' breakpoints x) and u2 (along the
//              columns' breakpoints y), output y; 2-D interpolation is the
//              1-D one along x within every column, then along y across
//              them (bilinear for linear, the tensor-product not-a-knot
//              spline for cubic)
//   states:    one mode per input whose axis has corners, two crossings
//              each (interpolation.h: AxisModes); none for smooth tables
//
// Run time: a binary search per input and, for 2-D, one 1-D evaluation per
// column (a cubic 2-D table also solves the spline across the columns, into
// the run's buffers, sized when its Context is prepared).

#include <array>
#include <memory>
#include <vector>

#include "blocks/framework/block.h"
#include "blocks/library/interpolation.h"

namespace mechflow::blocks {

class LookupBlock final : public Block {
 public:
  LookupBlock(const std::string& name, Axis axis, std::vector<double> values);

  std::string CrossingName(int index, int) const override { return modes_.CrossingName(index, {"u"}); }
 private:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;

  Axis axis_;
  Curve curve_;
  AxisModes modes_;
};

class Lookup2DBlock final : public Block {
 public:
  // values[i][j] = f(x_i, y_j)
  Lookup2DBlock(const std::string& name, Axis x, Axis y, const std::vector<std::vector<double>>& values);

  std::string CrossingName(int index, int) const override { return modes_.CrossingName(index, {"u1", "u2"}); }
 private:
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;
  std::unique_ptr<BlockScratch> MakeScratch() const override;
  std::array<double, 2> Inputs(const BlockContext& ctx) const;
  struct Scratch;  // the run's buffers across the columns

  Axis x_, y_;
  std::vector<Curve> columns_;  // along x, one per y_j
  AxisModes modes_;
};

// The rows of a 2-D table file: a first line with the column breakpoints y_j
// (its first field, a corner label, is ignored), then one line per row: x_i,
// f(x_i, y_1), ... Commas, semicolons, tabs or spaces separate; '#' starts a
// comment. `text` is the file's, read by the loader. InputError naming path:line.
void ReadTable2DCsv(const std::string& text, const std::string& path, std::vector<double>* x, std::vector<double>* y,
                    std::vector<std::vector<double>>* values);

}  // namespace mechflow::blocks
