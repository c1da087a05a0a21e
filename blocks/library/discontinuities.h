#pragma once
// Piecewise-linear maps with corners, each corner an event (as Simulink does):
//
//   abs         y = |u|
//   saturation  y = lower if u < lower, upper if u > upper, u between
//   dead_zone   y = u - start if u < start, 0 in [start, end], u - end above
//
// Every element keeps a mode (which linear piece is active) in a discrete
// state. Zero crossings of u - corner change the mode at the located instant;
// inside a step the output follows the frozen mode, so the right-hand side is
// smooth there. After any event the modes are re-classified from u.
//
// Ports: input u, output y (both of width `width`); u feeds y directly.
//
// Ties: when u sits exactly on a corner at an event (or at the start), the
// mode is 'exact': y is the piecewise function of u itself (both pieces agree
// on the corner). A frozen piece would be wrong there, because CVODE ignores
// a crossing function that is exactly zero where an integration starts (after
// every event): an input that leaves the corner then gives no event. The next
// crossing, or any later event, puts the block back on a frozen piece.

#include "blocks/block.h"

namespace mechflow::blocks {

// y = piece(mode, u) with corners c_0 < c_1 < ...; mode k means u lies between
// corner k-1 and corner k (mode 0: below every corner).
class PiecewiseLinearBlock : public Block {
 public:
  PiecewiseLinearBlock(const std::string& type, const std::string& name, std::vector<double> corners, int width);

 protected:
  // The output of element value `u` on piece `mode`.
  virtual double Piece(int mode, double u) const = 0;
  void DoInitialize(const BlockContext& ctx) const override;
  void DoCalcOutput(int port, const BlockContext& ctx) const override;
  void DoCalcZeroCrossings(const BlockContext& ctx) const override;
  void DoZeroCrossing(int index, int direction, const BlockContext& ctx) const override;
  bool DoUpdateModes(const BlockContext& ctx) const override;

 private:
  // The piece holding u (a corner itself goes to the piece above it).
  int Classify(double u) const;
  // True when u lies strictly inside piece `mode`.
  bool InsidePiece(int mode, double u) const;
  std::vector<double> corners_;
};

class AbsBlock : public PiecewiseLinearBlock {
 public:
  AbsBlock(const std::string& name, int width);

 protected:
  double Piece(int mode, double u) const override { return mode == 0 ? -u : u; }
};

class SaturationBlock : public PiecewiseLinearBlock {
 public:
  SaturationBlock(const std::string& name, double lower, double upper, int width);

 protected:
  double Piece(int mode, double u) const override;

 private:
  double lower_, upper_;
};

class DeadZoneBlock : public PiecewiseLinearBlock {
 public:
  DeadZoneBlock(const std::string& name, double start, double end, int width);

 protected:
  double Piece(int mode, double u) const override;

 private:
  double start_, end_;
};

}  // namespace mechflow::blocks
