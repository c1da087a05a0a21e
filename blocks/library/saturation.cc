#include "blocks/library/saturation.h"

namespace mechflow::blocks {

SaturationBlock::SaturationBlock(const std::string& name, double lower, double upper, int width)
    : PiecewiseLinearBlock("saturation", name, {lower, upper}, width), lower_(lower), upper_(upper) {}

double SaturationBlock::Piece(int mode, double u) const { return mode == 0 ? lower_ : mode == 2 ? upper_ : u; }

}  // namespace mechflow::blocks
