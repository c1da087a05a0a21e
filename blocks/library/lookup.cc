#include "blocks/library/lookup.h"

#include <cmath>

#include "blocks/library/table.h"
#include "mech/errors.h"

namespace mechflow::blocks {

LookupBlock::LookupBlock(const std::string& name, Axis axis, std::vector<double> values)
    : Block("lookup", name), axis_(std::move(axis)), curve_(axis_, std::move(values)), modes_({&axis_}) {
  DeclareInputPort("u");
  DeclareOutputPort("y");
  DeclareDiscreteStates(modes_.num_modes());
  for (int i = 0; i < modes_.num_crossings(); ++i)
    DeclareZeroCrossing(AxisModes::CrossingRises(i) ? CrossingDirection::kRising : CrossingDirection::kFalling);
}

void LookupBlock::DoInitialize(const BlockContext& ctx) const { modes_.Initialize(ctx.discrete()); }

void LookupBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const double u = ctx.input_scalar(0);
  ctx.output(0)[0] = curve_.At(axis_, u, modes_.Segment(0, u, ctx.discrete())).value;
}

void LookupBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  modes_.Crossings(ctx.input(0), ctx.discrete(), ctx.zero_crossings());
}

void LookupBlock::DoZeroCrossing(int index, int, const BlockContext& ctx) const {
  modes_.Cross(index, ctx.input(0), ctx.discrete());
}

bool LookupBlock::DoUpdateModes(const BlockContext& ctx) const { return modes_.Settle(ctx.input(0), ctx.discrete()); }

Lookup2DBlock::Lookup2DBlock(const std::string& name, Axis x, Axis y, const std::vector<std::vector<double>>& values)
    : Block("lookup_2d", name),
      x_(std::move(x)),
      y_(std::move(y)),
      modes_({&x_, &y_}) {
  if (static_cast<int>(values.size()) != x_.size())
    throw InputError("'values' has " + std::to_string(values.size()) + " rows for " + std::to_string(x_.size()) +
                     " breakpoints in 'x'");
  for (int j = 0; j < y_.size(); ++j) {
    std::vector<double> column;
    for (int i = 0; i < x_.size(); ++i) {
      if (static_cast<int>(values[i].size()) != y_.size())
        throw InputError("'values' row " + std::to_string(i + 1) + " has " + std::to_string(values[i].size()) +
                         " numbers for " + std::to_string(y_.size()) + " breakpoints in 'y'");
      column.push_back(values[i][j]);
    }
    columns_.emplace_back(x_, std::move(column));
  }
  DeclareInputPort("u1");
  DeclareInputPort("u2");
  DeclareOutputPort("y");
  DeclareDiscreteStates(modes_.num_modes());
  for (int i = 0; i < modes_.num_crossings(); ++i)
    DeclareZeroCrossing(AxisModes::CrossingRises(i) ? CrossingDirection::kRising : CrossingDirection::kFalling);
}

std::array<double, 2> Lookup2DBlock::Inputs(const BlockContext& ctx) const {
  return {ctx.input_scalar(0), ctx.input_scalar(1)};
}

// The values across the columns at u1 and their spline's work arrays, sized once.
struct Lookup2DBlock::Scratch final : BlockScratch {
  explicit Scratch(int n) : across(n), across_m(n), work(n) {}
  std::vector<double> across, across_m, work;
};

std::unique_ptr<BlockScratch> Lookup2DBlock::MakeScratch() const { return std::make_unique<Scratch>(y_.size()); }

void Lookup2DBlock::DoInitialize(const BlockContext& ctx) const { modes_.Initialize(ctx.discrete()); }

void Lookup2DBlock::DoCalcOutput(int, const BlockContext& ctx) const {
  const std::array<double, 2> u = Inputs(ctx);
  Scratch& s = ctx.scratch<Scratch>();
  const int along_x = modes_.Segment(0, u[0], ctx.discrete());
  const int along_y = modes_.Segment(1, u[1], ctx.discrete());
  for (int j = 0; j < y_.size(); ++j) s.across[j] = columns_[j].At(x_, u[0], along_x).value;
  if (y_.interpolation() == Interpolation::kCubic)
    SplineCurvatures(y_.x(), s.across.data(), s.across_m.data(), s.work.data());
  ctx.output(0)[0] = Curve::CurveAt(y_, s.across.data(), s.across_m.data(), u[1], along_y).value;
}

void Lookup2DBlock::DoCalcZeroCrossings(const BlockContext& ctx) const {
  const std::array<double, 2> u = Inputs(ctx);
  modes_.Crossings(u, ctx.discrete(), ctx.zero_crossings());
}

void Lookup2DBlock::DoZeroCrossing(int index, int, const BlockContext& ctx) const {
  const std::array<double, 2> u = Inputs(ctx);
  modes_.Cross(index, u, ctx.discrete());
}

bool Lookup2DBlock::DoUpdateModes(const BlockContext& ctx) const {
  const std::array<double, 2> u = Inputs(ctx);
  return modes_.Settle(u, ctx.discrete());
}

void ReadTable2DCsv(const std::string& text, const std::string& path, std::vector<double>* x, std::vector<double>* y,
                    std::vector<std::vector<double>>* values) {
  const std::vector<NumberRow> rows = ReadNumberRows(text, path, "numbers (x_i, then one value per column)");
  if (rows.empty() || !rows[0].header)
    throw InputError(path + ": a 2-D table starts with a line of the column breakpoints after a corner label "
                            "(\"x\\y, y1, y2, ...\"), then one line per row: x_i, f(x_i, y1), ...");
  y->assign(rows[0].values.begin() + 1, rows[0].values.end());
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const NumberRow& row = rows[r];
    if (row.values.size() != y->size() + 1)
      throw InputError(path + ":" + std::to_string(row.line) + ": expected " + std::to_string(y->size() + 1) +
                       " numbers (x_i and one value per column), found " + std::to_string(row.values.size()));
    x->push_back(row.values[0]);
    values->emplace_back(row.values.begin() + 1, row.values.end());
  }
}

}  // namespace mechflow::blocks
