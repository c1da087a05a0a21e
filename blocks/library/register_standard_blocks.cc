// The standard block types: parameters (with defaults and units) and the
// checks that turn well-formed but unusable values into clear errors. The
// loader fills every parameter that has a default before calling a factory,
// so p.Has() is false only for optional parameters without one.

#include <charconv>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "blocks/framework/block_factory.h"
#include "blocks/library/abs.h"
#include "blocks/library/clock.h"
#include "blocks/library/constant.h"
#include "blocks/library/dead_zone.h"
#include "blocks/library/first_order_lag.h"
#include "blocks/library/friction_from_normal_force.h"
#include "blocks/library/gain.h"
#include "blocks/library/integrator.h"
#include "blocks/library/lookup.h"
#include "blocks/library/motion.h"
#include "blocks/library/product.h"
#include "blocks/library/ramp.h"
#include "blocks/library/recorder.h"
#include "blocks/library/sample_hold.h"
#include "blocks/library/saturation.h"
#include "blocks/library/sine.h"
#include "blocks/library/step.h"
#include "blocks/library/sum.h"
#include "blocks/library/table.h"
#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

using K = ParamKind;

const ParamSpec kWidth = {"width", K::kNumber, false, "1", "width of the input and output signals (elementwise)"};

// A number as a user would write it (shortest form that reads back exactly).
std::string Format(double v) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return error == std::errc() ? std::string(buffer, end) : std::to_string(v);
}

// One finite number (an expression such as 1/0 evaluates to inf).
double Finite(const BlockParams& p, const std::string& name) {
  const double v = p.Number(name);
  if (!std::isfinite(v)) throw InputError("'" + name + "' must be a finite number, got " + Format(v));
  return v;
}

int Count(const BlockParams& p, const std::string& name, int minimum) {
  const double v = p.Number(name);
  if (!(v == std::floor(v) && v >= minimum && v <= 1e6))
    throw InputError("'" + name + "' must be a whole number >= " + std::to_string(minimum) + ", got " + Format(v));
  return static_cast<int>(v);
}

// A list given for a vector signal: one value (repeated to `width`) or `width` values.
std::vector<double> Values(const BlockParams& p, const std::string& name, int width) {
  std::vector<double> v = p.Numbers(name);
  for (const double x : v)
    if (!std::isfinite(x)) throw InputError("'" + name + "' must hold finite numbers, got " + Format(x));
  if (v.size() == 1 && width > 1) v.assign(width, v[0]);
  if (static_cast<int>(v.size()) != width)
    throw InputError("'" + name + "' has " + std::to_string(v.size()) + " values but the width is " +
                     std::to_string(width));
  return v;
}

// The width of a vector block: `width` if more than 1, else the length of `list`.
int WidthFrom(const BlockParams& p, const std::string& list) {
  const int given = Count(p, "width", 1);
  return given > 1 ? given : static_cast<int>(p.Numbers(list).size());
}

// A string of operator characters, one per input (spaces ignored).
std::string Operators(const BlockParams& p, const std::string& name, const std::string& allowed) {
  const std::string text = p.Text(name);
  std::string out;
  for (const char c : text) {
    if (c == ' ') continue;
    if (allowed.find(c) == std::string::npos)
      throw InputError("'" + name + "' may contain only the characters \"" + allowed + "\", got \"" + text + "\"");
    out += c;
  }
  if (out.empty()) throw InputError("'" + name + "' must name at least one input");
  return out;
}

// The points of a 1-D table: inline `points` rows or a `file`, argument named x.
void CurvePoints(const BlockParams& p, const std::string& x, std::vector<double>* xs, std::vector<double>* ys) {
  if (p.Has("points") == p.Has("file")) throw InputError("give either 'points' or 'file', not both or neither");
  if (p.Has("file"))
    ReadTableCsv(p.FileText("file"), p.Text("file"), xs, ys, x);
  else
    TablePointsFromRows(p.Table("points"), xs, ys, x);
}

Axis MakeAxis(const BlockParams& p, std::vector<double> x, const std::string& what) {
  return Axis(std::move(x), ParseInterpolation(p.Text("interpolation")), ParseExtrapolation(p.Text("extrapolation")),
              what);
}

const ParamSpec kExtrapolation = {"extrapolation", K::kText, false, "hold",
                                  "beyond the ends: hold (end value), linear (end tangent) or error (the run fails)"};

void Add(BlockRegistry* r, std::string name, std::string doc, std::vector<ParamSpec> params,
         decltype(BlockType::create) create) {
  r->Add({std::move(name), std::move(doc), std::move(params), std::move(create)});
}

void RegisterSources(BlockRegistry* r) {
  Add(r, "constant", "y = value (width = number of values)",
      {{"value", K::kNumbers, true, "", "the output value(s), one per element [unit of y]"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<ConstantBlock>(n, Values(p, "value", static_cast<int>(p.Numbers("value").size())));
      });
  Add(r, "clock", "y = t [s]", {},
      [](const std::string& n, const BlockParams&) { return std::make_unique<ClockBlock>(n); });
  Add(r, "step", "y = before for t < time, after from then on (the switch is an event)",
      {{"time", K::kNumber, false, "0", "switching time [s]"},
       {"before", K::kNumber, false, "0", "value before the step [unit of y]"},
       {"after", K::kNumber, false, "1", "value from the step on [unit of y]"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<StepBlock>(n, Finite(p, "time"), Finite(p, "before"), Finite(p, "after"));
      });
  Add(r, "ramp", "y = initial, then initial + slope (t - start) from start on (the corner is an event)",
      {{"slope", K::kNumber, false, "1", "slope [unit of y / s]"},
       {"start", K::kNumber, false, "0", "start time [s]"},
       {"initial", K::kNumber, false, "0", "value before the start [unit of y]"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<RampBlock>(n, Finite(p, "slope"), Finite(p, "start"), Finite(p, "initial"));
      });
  Add(r, "sine", "y = bias + amplitude sin(2 pi frequency t + phase)",
      {{"amplitude", K::kNumber, false, "1", "amplitude [unit of y]"},
       {"frequency", K::kNumber, false, "1", "frequency [Hz]", "Hz"},
       {"phase", K::kNumber, false, "0", "phase [rad]"},
       {"bias", K::kNumber, false, "0", "offset added [unit of y]"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<SineBlock>(n, Finite(p, "amplitude"), Finite(p, "frequency"), Finite(p, "phase"),
                                           Finite(p, "bias"));
      });
  Add(r, "table", "y = piecewise-linear interpolation in t of points, held constant beyond the first and last",
      {{"points", K::kTable, false, "", "inline points \"t0 y0; t1 y1; ...\" [s, unit of y], t strictly increasing"},
       {"file", K::kPath, false, "", "CSV file with columns t [s], y (instead of points)"}},
      [](const std::string& n, const BlockParams& p) {
        if (p.Has("points") == p.Has("file")) throw InputError("give either 'points' or 'file', not both or neither");
        std::vector<double> times, values;
        if (p.Has("file")) {
          ReadTableCsv(p.FileText("file"), p.Text("file"), &times, &values);
        } else {
          TablePointsFromRows(p.Table("points"), &times, &values);
        }
        return std::make_unique<TableBlock>(n, std::move(times), std::move(values));
      });
}

void RegisterTables(BlockRegistry* r) {
  Add(r, "lookup", "y = f(u), a table of u interpolated step, linear or cubic (corners are events)",
      {{"points", K::kTable, false, "", "inline points \"x0 y0; x1 y1; ...\" [unit of u, unit of y], x increasing"},
       {"file", K::kPath, false, "", "CSV file with columns x, y (instead of points)"},
       {"interpolation", K::kText, false, "linear", "step, linear or cubic (not-a-knot spline, smooth)"},
       kExtrapolation},
      [](const std::string& n, const BlockParams& p) {
        std::vector<double> x, y;
        CurvePoints(p, "x", &x, &y);
        return std::make_unique<LookupBlock>(n, MakeAxis(p, std::move(x), "lookup '" + n + "'"), std::move(y));
      });
  Add(r, "lookup_2d", "y = f(u1, u2), a table over x (u1) and y (u2) breakpoints (corners are events)",
      {{"x", K::kNumbers, false, "", "breakpoints of u1, increasing [unit of u1]"},
       {"y", K::kNumbers, false, "", "breakpoints of u2, increasing [unit of u2]"},
       {"values", K::kTable, false, "", "f(x_i, y_j): one row per x_i, one column per y_j [unit of y]"},
       {"file", K::kPath, false, "", "CSV: a line \"label, y1, y2, ...\", then rows \"x_i, f(x_i, y1), ...\""},
       {"interpolation", K::kText, false, "linear", "step, linear (bilinear) or cubic (tensor-product spline)"},
       kExtrapolation},
      [](const std::string& n, const BlockParams& p) {
        std::vector<double> x, y;
        std::vector<std::vector<double>> values;
        const bool inline_table = p.Has("x") || p.Has("y") || p.Has("values");
        if (inline_table == p.Has("file"))
          throw InputError("give either 'x', 'y' and 'values', or 'file', not both or neither");
        std::string where = "lookup_2d '" + n + "'";
        if (p.Has("file")) {
          ReadTable2DCsv(p.FileText("file"), p.Text("file"), &x, &y, &values);
          where = p.Text("file");
        } else {
          if (!p.Has("x") || !p.Has("y") || !p.Has("values"))
            throw InputError("an inline 2-D table needs all of 'x', 'y' and 'values'");
          x = p.Numbers("x");
          y = p.Numbers("y");
          values = p.Table("values");
        }
        return std::make_unique<Lookup2DBlock>(n, MakeAxis(p, std::move(x), where + ", x"),
                                               MakeAxis(p, std::move(y), where + ", y"), values);
      });
}

void RegisterMotions(BlockRegistry* r) {
  Add(r, "motion_sine", "y = (q, q', q'') of q = bias + amplitude sin(2 pi frequency t + phase): drives a joint",
      {{"amplitude", K::kNumber, false, "1", "amplitude [m or rad]"},
       {"frequency", K::kNumber, false, "1", "frequency [Hz]", "Hz"},
       {"phase", K::kNumber, false, "0", "phase [rad]"},
       {"bias", K::kNumber, false, "0", "offset added [m or rad]"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<MotionSineBlock>(n, Finite(p, "amplitude"), Finite(p, "frequency"),
                                                 Finite(p, "phase"), Finite(p, "bias"));
      });
  Add(r, "motion_table", "y = (q, q', q'') of q = f(start + speed t) from a table: drives a joint",
      {{"points", K::kTable, false, "", "inline points \"s0 q0; s1 q1; ...\" [s or m, m or rad], s increasing"},
       {"file", K::kPath, false, "", "CSV file with columns s, q (instead of points)"},
       {"speed", K::kNumber, false, "1", "ds/dt: 1 for a table of time, the travel speed for one of distance"},
       {"start", K::kNumber, false, "0", "s at t = 0 [unit of s]"},
       {"interpolation", K::kText, false, "cubic", "cubic (continuous q''), linear or step"},
       kExtrapolation},
      [](const std::string& n, const BlockParams& p) {
        std::vector<double> s, q;
        CurvePoints(p, "s", &s, &q);
        return std::make_unique<MotionTableBlock>(n, MakeAxis(p, std::move(s), "motion_table '" + n + "'"),
                                                  std::move(q), Finite(p, "start"), Finite(p, "speed"));
      });
  Add(r, "motion_filter", "y = (q, q', q''), q'' = w^2 (u - q) - 2 zeta w q': any signal u made a motion",
      {{"frequency", K::kNumber, true, "", "filter frequency w / (2 pi) [Hz], > 0", "Hz"},
       {"damping", K::kNumber, false, "1", "damping ratio zeta [-], > 0 (1: critical, no overshoot)"}},
      [](const std::string& n, const BlockParams& p) {
        if (!(Finite(p, "frequency") > 0)) throw InputError("'frequency' must be > 0");
        if (!(Finite(p, "damping") > 0)) throw InputError("'damping' must be > 0");
        return std::make_unique<MotionFilterBlock>(n, p.Number("frequency"), p.Number("damping"));
      });
}

void RegisterMath(BlockRegistry* r) {
  Add(r, "gain", "y = k u (elementwise)",
      {{"k", K::kNumber, true, "", "gain [unit of y / unit of u]"}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<GainBlock>(n, Finite(p, "k"), Count(p, "width", 1));
      });
  Add(r, "sum", "y = signed sum of the inputs u1..un (elementwise)",
      {{"signs", K::kText, false, "++", "one + or - per input, e.g. \"+-\" for u1 - u2"}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<SumBlock>(n, Operators(p, "signs", "+-"), Count(p, "width", 1));
      });
  Add(r, "product", "y = product (or quotient) of the inputs u1..un (elementwise)",
      {{"inputs", K::kNumber, false, "", "number of inputs when 'operations' is not given (default 2)"},
       {"operations", K::kText, false, "", "one * or / per input, e.g. \"**/\" for u1 u2 / u3 (default all *)"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        std::string operations(p.Has("inputs") ? Count(p, "inputs", 1) : 2, '*');
        if (p.Has("operations")) {
          operations = Operators(p, "operations", "*/");
          if (p.Has("inputs") && Count(p, "inputs", 1) != static_cast<int>(operations.size()))
            throw InputError("'inputs' is " + std::to_string(Count(p, "inputs", 1)) + " but 'operations' (\"" +
                             operations + "\") names " + std::to_string(operations.size()) +
                             " inputs; give one of the two");
        }
        return std::make_unique<ProductBlock>(n, operations, Count(p, "width", 1));
      });
  Add(r, "abs", "y = |u| (elementwise; the corner at 0 is an event)", {kWidth},
      [](const std::string& n, const BlockParams& p) { return std::make_unique<AbsBlock>(n, Count(p, "width", 1)); });
  Add(r, "saturation", "y = u limited to [lower, upper] (elementwise; the corners are events)",
      {{"lower", K::kNumber, true, "", "lower limit [unit of u]"},
       {"upper", K::kNumber, true, "", "upper limit [unit of u], > lower"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(Finite(p, "lower") < Finite(p, "upper"))) throw InputError("'lower' must be less than 'upper'");
        return std::make_unique<SaturationBlock>(n, p.Number("lower"), p.Number("upper"), Count(p, "width", 1));
      });
  Add(r, "dead_zone", "y = 0 inside [start, end], u - start below, u - end above (elementwise; corners are events)",
      {{"start", K::kNumber, true, "", "lower edge of the dead zone [unit of u]"},
       {"end", K::kNumber, true, "", "upper edge of the dead zone [unit of u], > start"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(Finite(p, "start") < Finite(p, "end"))) throw InputError("'start' must be less than 'end'");
        return std::make_unique<DeadZoneBlock>(n, p.Number("start"), p.Number("end"), Count(p, "width", 1));
      });
}

void RegisterDynamic(BlockRegistry* r) {
  Add(r, "integrator", "x' = u, y = x; optional limits and reset (events); no direct feedthrough",
      {{"initial", K::kNumbers, false, "0", "initial value(s) x(t_start), one or one per element [unit of y]"},
       {"lower", K::kNumber, false, "", "lower limit [unit of y] (optional)"},
       {"upper", K::kNumber, false, "", "upper limit [unit of y] (optional)"},
       {"reset", K::kText, false, "", "rising, falling or either: adds inputs 'reset' (trigger) and 'x0'"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        const int width = WidthFrom(p, "initial");
        std::optional<double> lower, upper;
        if (p.Has("lower")) lower = Finite(p, "lower");
        if (p.Has("upper")) upper = Finite(p, "upper");
        if (lower && upper && !(*lower < *upper)) throw InputError("'lower' must be less than 'upper'");
        const std::vector<double> initial = Values(p, "initial", width);
        for (const double x0 : initial) {
          if (upper && x0 > *upper)
            throw InputError("'initial' (" + Format(x0) + ") is above 'upper' (" + Format(*upper) + ")");
          if (lower && x0 < *lower)
            throw InputError("'initial' (" + Format(x0) + ") is below 'lower' (" + Format(*lower) + ")");
        }
        ResetKind reset = ResetKind::kNone;
        if (p.Has("reset")) {
          const std::string& kind = p.Text("reset");
          if (kind == "rising") reset = ResetKind::kRising;
          else if (kind == "falling") reset = ResetKind::kFalling;
          else if (kind == "either") reset = ResetKind::kEither;
          else throw InputError("'reset' must be rising, falling or either, got '" + kind + "'");
        }
        return std::make_unique<IntegratorBlock>(n, initial, lower, upper, reset);
      });
  Add(r, "first_order_lag", "T y' + y = K u (elementwise); no direct feedthrough",
      {{"time_constant", K::kNumber, true, "", "time constant T [s], > 0"},
       {"gain", K::kNumber, false, "1", "static gain K [unit of y / unit of u]"},
       {"initial", K::kNumbers, false, "0", "initial output y(t_start), one or one per element [unit of y]"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(Finite(p, "time_constant") > 0)) throw InputError("'time_constant' must be > 0");
        const int width = WidthFrom(p, "initial");
        return std::make_unique<FirstOrderLagBlock>(n, p.Number("time_constant"), Finite(p, "gain"),
                                                    Values(p, "initial", width));
      });
}

void RegisterFriction(BlockRegistry* r) {
  Add(r, "friction_from_normal_force",
      "F = -(mu(v) n(N) tanh(v / v_reg) + c_visc v), mu(v) = mu_d + (mu_s - mu_d) exp(-(|v| / v_s)^2), "
      "n(N) = max(N, 0) (unilateral) or |N| (bilateral)",
      {{"normal", K::kText, false, "unilateral",
        "unilateral: a contact that only pushes (a pulling N gives no friction, and a warning); bilateral: a guide "
        "holding the body both ways (friction from |N|)"},
       {"mu_static", K::kNumber, true, "", "static friction coefficient mu_s [-], >= 0"},
       {"mu_dynamic", K::kNumber, true, "", "dynamic (sliding) friction coefficient mu_d [-], >= 0"},
       {"stribeck_velocity", K::kNumber, false, "0.01", "Stribeck velocity v_s [m/s], > 0"},
       {"viscous", K::kNumber, false, "0", "viscous coefficient c_visc [N s/m], >= 0"},
       {"regularisation_velocity", K::kNumber, false, "1e-4", "regularisation velocity v_reg [m/s], > 0"}},
      [](const std::string& n, const BlockParams& p) {
        mech::FrictionLawParams law;
        law.mu_static = Finite(p, "mu_static");
        law.mu_dynamic = Finite(p, "mu_dynamic");
        law.stribeck_velocity = Finite(p, "stribeck_velocity");
        law.viscous = Finite(p, "viscous");
        law.regularisation_velocity = Finite(p, "regularisation_velocity");
        const std::string problem = mech::CheckFrictionLawParams(law);
        if (!problem.empty()) throw InputError(problem);
        const std::string normal = p.Text("normal");
        if (normal != "unilateral" && normal != "bilateral")
          throw InputError("normal must be \"unilateral\" (a contact that only pushes: max(N, 0)) or \"bilateral\" "
                           "(a guide holding the body both ways: |N|), not \"" + normal + "\"");
        return std::make_unique<FrictionFromNormalForceBlock>(n, law, normal == "bilateral");
      });
}

void RegisterSinksAndSampling(BlockRegistry* r) {
  Add(r, "recorder", "logs the signals driving its inputs u1..un (one plot panel); computes nothing",
      {{"inputs", K::kNumber, false, "1", "number of inputs u1..un (u when 1)"}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<RecorderBlock>(n, Count(p, "inputs", 1), Count(p, "width", 1));
      });
  Add(r, "sample_hold", "zero-order hold: y = u sampled at offset + k period; no direct feedthrough",
      {{"period", K::kNumber, true, "", "sample period [s], > 0"},
       {"offset", K::kNumber, false, "0", "first sample time [s], >= 0"},
       {"initial", K::kNumbers, false, "0", "output before the first sample, one or one per element [unit of u]"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(Finite(p, "period") > 0)) throw InputError("'period' must be > 0");
        if (!(Finite(p, "offset") >= 0)) throw InputError("'offset' must be >= 0");
        const int width = WidthFrom(p, "initial");
        return std::make_unique<SampleHoldBlock>(n, p.Number("period"), p.Number("offset"),
                                                 Values(p, "initial", width));
      });
}

}  // namespace

void RegisterStandardBlocks(BlockRegistry* r) {
  RegisterSources(r);
  RegisterTables(r);
  RegisterMotions(r);
  RegisterMath(r);
  RegisterDynamic(r);
  RegisterFriction(r);
  RegisterSinksAndSampling(r);
}

}  // namespace mechflow::blocks
