#pragma once
// PiecewiseLinearBlock: the common part of abs, saturation and dead_zone, an
// elementwise piecewise-linear map whose corners are events (as Simulink does).
//
//   ports:   input u, output y (both of width `width`); u feeds y directly
//   states:  one discrete mode per element: the active piece (k: u between
//            corner k-1 and corner k; 0: below every corner)
//   events:  one zero crossing u - c_k per element and corner (either way)
//
// Inside a solver step y follows the frozen piece, so the right-hand side is
// smooth there even when a trial step overshoots a corner; the crossing of
// u - c_k switches the piece at the located instant (rising through c_k
// enters piece k+1, falling enters piece k), with the hysteresis of
// blocks/library/hysteresis.h: a piece is left only once u is past its
// corner by the band, so no crossing function is ever exactly zero where
// integration starts (CVODE ignores such a crossing) and a signal resting on
// a corner does not chatter. After every event and at the start the modes
// are re-classified from u, which handles an input that jumped across
// corners at another block's event.

#include <string>
#include <vector>

#include "blocks/framework/block.h"

namespace mechflow::blocks {

class PiecewiseLinearBlock : public Block {
 public:
  // `corners` strictly increasing (checked by the factories).
  PiecewiseLinearBlock(const std::string& type, const std::string& name, std::vector<double> corners, int width);

 protected:
  // The output for input `u` on piece `mode` (0 .. number of corners).
  virtual double Piece(int mode, double u) const = 0;
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  std::string CrossingName(int index, int direction) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;

 private:
  // The piece holding u (a corner itself goes to the piece above it).
  int Classify(double u) const;
  // True when u lies inside piece `mode` widened by the hysteresis band.
  bool InsidePiece(int mode, double u) const;

  std::vector<double> corners_;
};

}  // namespace mechflow::blocks
