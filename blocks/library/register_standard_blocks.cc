// The standard block types: parameters (with defaults and units) and the
// checks that turn well-formed but unusable values into clear errors.

#include <charconv>
#include <cmath>

#include "blocks/block_factory.h"
#include "blocks/library/discontinuities.h"
#include "blocks/library/first_order_lag.h"
#include "blocks/library/friction_from_normal_force.h"
#include "blocks/library/integrator.h"
#include "blocks/library/math_blocks.h"
#include "blocks/library/sinks.h"
#include "blocks/library/sources.h"
#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

using K = ParamKind;

const ParamSpec kWidth = {"width", K::kNumber, false, "1", "width of the input and output signals"};

// A number as a user would write it (shortest form that reads back exactly).
std::string Format(double v) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return error == std::errc() ? std::string(buffer, end) : std::to_string(v);
}

int Count(const BlockParams& p, const std::string& name, int minimum) {
  const double v = p.Number(name);
  if (v != std::floor(v) || v < minimum || v > 1e6)
    throw InputError("'" + name + "' must be a whole number >= " + std::to_string(minimum) + ", got " + Format(v));
  return static_cast<int>(v);
}

// A list given for a vector signal: one value (repeated to `width`) or `width` values.
std::vector<double> Values(const BlockParams& p, const std::string& name, int width) {
  std::vector<double> v = p.Numbers(name);
  if (v.size() == 1 && width > 1) v.assign(width, v[0]);
  if (static_cast<int>(v.size()) != width)
    throw InputError("'" + name + "' has " + std::to_string(v.size()) + " values but the width is " +
                     std::to_string(width));
  return v;
}

// The width of a vector block: `width` if given, else the length of `list`.
int WidthFrom(const BlockParams& p, const std::string& list) {
  const int given = Count(p, "width", 1);
  return given > 1 ? given : static_cast<int>(p.Numbers(list).size());
}

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

void Add(BlockRegistry* r, std::string name, std::string doc, std::vector<ParamSpec> params,
         decltype(BlockType::create) create) {
  r->Add({std::move(name), std::move(doc), std::move(params), std::move(create)});
}

}  // namespace

void RegisterStandardBlocks(BlockRegistry* r) {
  // sources
  Add(r, "constant", "y = value", {{"value", K::kNumbers, true, "", "the output value(s)"}},
      [](const std::string& n, const BlockParams& p) { return std::make_unique<ConstantBlock>(n, p.Numbers("value")); });
  Add(r, "clock", "y = t", {}, [](const std::string& n, const BlockParams&) { return std::make_unique<ClockBlock>(n); });
  Add(r, "step", "y = before until time, after from then on",
      {{"time", K::kNumber, false, "0", "switching time [s]"},
       {"before", K::kNumber, false, "0", "value before the step"},
       {"after", K::kNumber, false, "1", "value from the step on"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<StepBlock>(n, p.Number("time"), p.Number("before"), p.Number("after"));
      });
  Add(r, "ramp", "y = initial + slope (t - start) from start on",
      {{"slope", K::kNumber, false, "1", "slope [unit/s]"},
       {"start", K::kNumber, false, "0", "start time [s]"},
       {"initial", K::kNumber, false, "0", "value before the start"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<RampBlock>(n, p.Number("slope"), p.Number("start"), p.Number("initial"));
      });
  Add(r, "sine", "y = bias + amplitude sin(2 pi frequency t + phase)",
      {{"amplitude", K::kNumber, false, "1", "amplitude"},
       {"frequency", K::kNumber, false, "1", "frequency [Hz]"},
       {"phase", K::kNumber, false, "0", "phase [rad]"},
       {"bias", K::kNumber, false, "0", "offset added"}},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<SineBlock>(n, p.Number("amplitude"), p.Number("frequency"), p.Number("phase"),
                                           p.Number("bias"));
      });
  Add(r, "table", "y = piecewise-linear interpolation in t of points, held beyond the ends",
      {{"points", K::kTable, false, "", "inline points \"t0 y0; t1 y1; ...\""},
       {"file", K::kPath, false, "", "CSV file with columns t, y (instead of points)"}},
      [](const std::string& n, const BlockParams& p) {
        if (p.Has("points") == p.Has("file")) throw InputError("give either 'points' or 'file', not both or neither");
        std::vector<double> times, values;
        if (p.Has("file")) {
          ReadTableCsv(p.Text("file"), &times, &values);
        } else {
          const auto& rows = p.Table("points");
          for (size_t i = 0; i < rows.size(); ++i) {
            if (rows[i].size() != 2)
              throw InputError("points row " + std::to_string(i + 1) + " has " + std::to_string(rows[i].size()) +
                               " numbers; expected two (t y)");
            times.push_back(rows[i][0]);
            values.push_back(rows[i][1]);
          }
          CheckTableTimes(times, "points");
        }
        return std::make_unique<TableBlock>(n, times, values);
      });

  // math
  Add(r, "gain", "y = k u", {{"k", K::kNumber, true, "", "gain"}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<GainBlock>(n, p.Number("k"), Count(p, "width", 1));
      });
  Add(r, "sum", "y = signed sum of the inputs u1..un",
      {{"signs", K::kText, false, "++", "one + or - per input, e.g. \"+-\""}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<SumBlock>(n, Operators(p, "signs", "+-"), Count(p, "width", 1));
      });
  Add(r, "product", "y = product (or quotient) of the inputs u1..un",
      {{"operations", K::kText, false, "**", "one * or / per input, e.g. \"**/\""}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<ProductBlock>(n, Operators(p, "operations", "*/"), Count(p, "width", 1));
      });
  Add(r, "abs", "y = |u| (the corner is an event)", {kWidth},
      [](const std::string& n, const BlockParams& p) { return std::make_unique<AbsBlock>(n, Count(p, "width", 1)); });
  Add(r, "saturation", "y = u limited to [lower, upper] (the corners are events)",
      {{"lower", K::kNumber, true, "", "lower limit"}, {"upper", K::kNumber, true, "", "upper limit"}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(p.Number("lower") < p.Number("upper"))) throw InputError("'lower' must be less than 'upper'");
        return std::make_unique<SaturationBlock>(n, p.Number("lower"), p.Number("upper"), Count(p, "width", 1));
      });
  Add(r, "dead_zone", "y = 0 inside [start, end], u - start below, u - end above (corners are events)",
      {{"start", K::kNumber, true, "", "lower edge of the dead zone"},
       {"end", K::kNumber, true, "", "upper edge of the dead zone"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(p.Number("start") < p.Number("end"))) throw InputError("'start' must be less than 'end'");
        return std::make_unique<DeadZoneBlock>(n, p.Number("start"), p.Number("end"), Count(p, "width", 1));
      });

  // dynamic
  Add(r, "integrator", "x' = u, y = x; optional limits and reset (events)",
      {{"initial", K::kNumbers, false, "0", "initial value(s) x(t_start)"},
       {"lower", K::kNumber, false, "", "lower limit (optional)"},
       {"upper", K::kNumber, false, "", "upper limit (optional)"},
       {"reset", K::kText, false, "", "rising, falling or either: adds inputs 'reset' and 'x0'"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        const int width = WidthFrom(p, "initial");
        std::optional<double> lower, upper;
        if (p.Has("lower")) lower = p.Number("lower");
        if (p.Has("upper")) upper = p.Number("upper");
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
  Add(r, "first_order_lag", "T y' + y = K u",
      {{"time_constant", K::kNumber, true, "", "time constant T [s], > 0"},
       {"gain", K::kNumber, false, "1", "static gain K"},
       {"initial", K::kNumbers, false, "0", "initial output y(t_start)"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(p.Number("time_constant") > 0)) throw InputError("'time_constant' must be > 0");
        const int width = WidthFrom(p, "initial");
        return std::make_unique<FirstOrderLagBlock>(n, p.Number("time_constant"), p.Number("gain"),
                                                    Values(p, "initial", width));
      });

  // friction
  Add(r, "friction_from_normal_force", "F = -(mu(v) max(N,0) tanh(v/v_reg) + c_visc v), Stribeck mu(v)",
      {{"mu_static", K::kNumber, true, "", "static friction coefficient mu_s"},
       {"mu_dynamic", K::kNumber, true, "", "dynamic (sliding) friction coefficient mu_d"},
       {"stribeck_velocity", K::kNumber, false, "0.01", "Stribeck velocity v_s [m/s]"},
       {"viscous", K::kNumber, false, "0", "viscous coefficient c_visc [N s/m]"},
       {"regularisation_velocity", K::kNumber, false, "1e-4", "regularisation velocity v_reg [m/s]"}},
      [](const std::string& n, const BlockParams& p) {
        mech::FrictionLawParams law;
        law.mu_static = p.Number("mu_static");
        law.mu_dynamic = p.Number("mu_dynamic");
        law.stribeck_velocity = p.Number("stribeck_velocity");
        law.viscous = p.Number("viscous");
        law.regularisation_velocity = p.Number("regularisation_velocity");
        const std::string problem = mech::CheckFrictionLawParams(law);
        if (!problem.empty()) throw InputError(problem);
        return std::make_unique<FrictionFromNormalForceBlock>(n, law);
      });

  // sinks and sampling
  Add(r, "recorder", "logs the signals driving its inputs (one plot panel)",
      {{"inputs", K::kNumber, false, "1", "number of inputs u1..un"}, kWidth},
      [](const std::string& n, const BlockParams& p) {
        return std::make_unique<RecorderBlock>(n, Count(p, "inputs", 1), Count(p, "width", 1));
      });
  Add(r, "sample_hold", "zero-order hold sampled at offset + k period",
      {{"period", K::kNumber, true, "", "sample period [s], > 0"},
       {"offset", K::kNumber, false, "0", "first sample time [s], >= 0"},
       {"initial", K::kNumbers, false, "0", "output before the first sample"},
       kWidth},
      [](const std::string& n, const BlockParams& p) {
        if (!(p.Number("period") > 0)) throw InputError("'period' must be > 0");
        if (!(p.Number("offset") >= 0)) throw InputError("'offset' must be >= 0");
        const int width = WidthFrom(p, "initial");
        return std::make_unique<SampleHoldBlock>(n, p.Number("period"), p.Number("offset"),
                                                 Values(p, "initial", width));
      });
}

}  // namespace mechflow::blocks
