#include "blocks/library/dead_zone.h"

namespace mechflow::blocks {

DeadZoneBlock::DeadZoneBlock(const std::string& name, double start, double end, int width)
    : PiecewiseLinearBlock("dead_zone", name, {start, end}, width), start_(start), end_(end) {}

double DeadZoneBlock::Piece(int mode, double u) const { return mode == 0 ? u - start_ : mode == 2 ? u - end_ : 0.0; }

}  // namespace mechflow::blocks
