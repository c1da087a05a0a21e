#pragma once
// The friction line of bench/friction_direct.h written as a mechflow diagram
// (XML text), so the benchmarks P2 and P3 and the tests build the same
// problem for mechflow as the direct program integrates.
//
// Mechanism "m": body M<i> (i = 1..n) on a translational joint along x from
// the ground point (i, 0, 0), coordinate x<i> = x_{i-1} of the direct
// program, starting at (x0, v0). Elements:
//   anchor   (k0 > 0 or d0 > 0) linear force between the anchor and M1: the
//            ground origin when V = 0, otherwise body Leader on a generalized
//            joint (tc 0, tt V t) -- a leader with prescribed motion, no state;
//   s<i>     linear force between M<i-1> and M<i> (k, d), i = 2..n;
//   f<i>     frictional element between the ground point (i-1, 0, 0) and M<i>
//            (length 1 + x<i>);
//   push     applied force A sin(2 pi f t) along x on M<n> (when A != 0).
// Every spring's free length is its initial length (x = 0), so the forces
// are those of the direct program. Sensors x<i>, v<i> are logged in the order
// x1, v1, x2, v2, ... (columns 1.. after time).

#include <string>
#include <vector>

#include "bench/friction_direct.h"

namespace mechflow::bench {

struct DiagramSettings {
  double t_end = 1.0, rtol = 1e-6, atol = 1e-8;
  int num_outputs = 1000;
};

std::string FrictionLineDiagram(const FrictionLine& line, const std::vector<double>& x0, const std::vector<double>& v0,
                                const DiagramSettings& settings);

}  // namespace mechflow::bench
