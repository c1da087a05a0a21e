#pragma once
// The steps of one mechanism evaluation that mechanism.cc and the exact-stick
// holds (mechanism_holds.cc) share. Not for other code: mech/mechanism.h is
// the interface.

#include <span>

#include "mech/mechanism.h"

namespace mechflow::mech {

// Element e's loads, state rates and sensors; with its work tracked, also the
// work's rate (the power of its loads) and its work sensors.
void EvaluateElement(const Mechanism& mechanism, int e, double t, std::span<const double> x,
                     std::span<const double> modes, MechanismWorkspace* ws, std::span<double> all_rates);
void SetParameterArgs(double t, std::span<const double> inputs, MechanismWorkspace* ws);
// Accelerations for the current loads: ws->vdot, and the segments' in ws->dyn
// (which PointAcceleration reads). `final`: also the transmitted forces that
// reaction sensors read.
void SolveDynamics(const Mechanism& mechanism, MechanismWorkspace* ws, bool final);

// The holds whose modes say they stick, into ws->stick.stuck, and their
// elements into ws->holding; every holding force starts at zero.
void FindStuck(const Mechanism& mechanism, double t, std::span<const double> x, std::span<const double> modes,
               MechanismWorkspace* ws);
// The elements' loads as EvaluateElements, those with a stuck hold last
// (their holding forces at zero), keeping the loads before them.
void EvaluateElementsHoldingLast(const Mechanism& mechanism, double t, std::span<const double> x,
                                 std::span<const double> inputs, std::span<const double> modes,
                                 MechanismWorkspace* ws, std::span<double> all_rates);
// After EvaluateElementsHoldingLast: solves for the holding forces
// (mech/exact_stick.h) and lets the holding elements apply them.
void HoldStuckElements(const Mechanism& mechanism, double t, std::span<const double> x,
                       std::span<const double> modes, MechanismWorkspace* ws, std::span<double> all_rates);

}  // namespace mechflow::mech
