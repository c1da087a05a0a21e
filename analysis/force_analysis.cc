#include "analysis/force_analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "analysis/element_drive_block.h"
#include "blocks/framework/diagram_builder.h"
#include "blocks/library/mechanism_block.h"
#include "blocks/solver/simulator.h"
#include "blocks/support/message_number.h"
#include "blocks/support/suggest.h"
#include "mech/errors.h"
#include "run/model.h"

namespace mechflow::analysis {
namespace {

using blocks::MessageNumber;

constexpr double kPeriodicTolerance = 1e-6;
constexpr double kMaxRowsPerCase = 1e7;

struct FoundElement {
  const mech::Mechanism* mechanism = nullptr;
  int index = -1;
};

FoundElement FindElement(const diagrams::LoadedDiagram& loaded, const std::string& name) {
  std::vector<std::string> names;
  for (int b = 0; b < loaded.diagram->num_blocks(); ++b) {
    const auto* block = dynamic_cast<const blocks::MechanismBlock*>(&loaded.diagram->block(b));
    if (!block) continue;
    const mech::Mechanism& m = block->mechanism();
    const int index = m.FindElement(name);
    if (index >= 0) return {&m, index};
    for (int e = 0; e < m.num_elements(); ++e) names.push_back(m.element(e).name());
  }
  throw InputError("force analysis: no force element '" + name + "'" + blocks::DidYouMean(name, names) +
                   (names.empty() ? "; the diagram has none" : "; elements: " + blocks::JoinNames(names)));
}

// Rows [first, first + samples] of a column.
std::vector<double> Period(const std::vector<double>& column, std::size_t first, int samples) {
  return std::vector<double>(column.begin() + first, column.begin() + first + samples + 1);
}

// A case whose numbers overflowed: no figures, no loop, and why.
ForceAnalysisCase Failed(ForceAnalysisCase c, const std::string& what) {
  ForceAnalysisCase out;
  out.amplitude = c.amplitude;
  out.frequency = c.frequency;
  out.x0 = c.x0;
  out.failure = what + " is not a finite number (an amplitude of " + MessageNumber(c.amplitude) +
                " is more than the element's geometry or force law can represent; give a smaller one)";
  return out;
}

ForceAnalysisCase RunCase(const diagrams::LoadedDiagram& loaded, const FoundElement& found,
                          const ForceAnalysisRequest& request, double amplitude, double frequency) {
  ForceAnalysisCase out;
  out.amplitude = amplitude;
  out.frequency = frequency;
  blocks::DiagramBuilder builder;
  // Half a row of phase: the turning points fall between rows, so a force
  // that jumps there (dry friction) is never sampled on its jump.
  const double phase = 2.0 * std::numbers::pi / (2.0 * request.samples);
  auto block = std::make_unique<ElementDriveBlock>("drive", *found.mechanism, found.index, request.component,
                                                   HarmonicDrive{amplitude, frequency, phase});
  out.x0 = block->initial_coordinate();
  builder.AddBlock(std::move(block));
  const std::unique_ptr<blocks::Diagram> diagram = builder.Build();
  blocks::SolverOptions solver;
  solver.rtol = loaded.solver.rtol;
  solver.atol = loaded.solver.atol;
  solver.t_end = request.cycles / frequency;
  solver.output_interval = 1.0 / (frequency * request.samples);
  // a step never spans more than a tenth of a period: the drive is known
  // ahead, the integrator must not step over its turns
  solver.max_step = 0.1 / frequency;
  std::vector<blocks::SignalRef> logged;
  for (const char* port : {"drive.x", "drive.v", "drive.reaction"}) logged.push_back(diagram->ResolveSignal(port));
  blocks::Simulator sim(*diagram, solver, logged);
  sim.SetInterruptFlag(request.interrupt);
  const blocks::RunOutcome outcome = sim.Run();
  if (outcome.interrupted) throw Interrupted(outcome.interrupted);
  if (!outcome.ok) {
    out.failure = outcome.failure;
    return out;
  }
  const blocks::Results& r = sim.results();
  const int samples = request.samples;
  const std::size_t rows = r.num_rows();
  if (rows < static_cast<std::size_t>(2 * samples + 1)) {
    out.failure = "too few rows for two periods";
    return out;
  }
  const std::size_t last = rows - 1 - samples, before = last - samples;
  for (std::size_t k = before; k < rows; ++k)
    for (int c = 1; c <= 3; ++c)
      if (!std::isfinite(r.at(static_cast<int>(k), c)))
        return Failed(std::move(out), std::string(c == 3   ? "the reaction"
                                                  : c == 1 ? "x"
                                                           : "v") +
                                          " at t = " + MessageNumber(r.at(static_cast<int>(k), 0)) + " s");
  const std::vector<double> reaction = r.Column(3);
  out.x = Period(r.Column(1), last, samples);
  out.v = Period(r.Column(2), last, samples);
  out.reaction = Period(reaction, last, samples);
  const std::vector<double> previous = Period(reaction, before, samples);
  double largest = 0.0, difference = 0.0;
  for (int k = 0; k <= samples; ++k) {
    largest = std::max(largest, std::abs(out.reaction[k]));
    difference = std::max(difference, std::abs(out.reaction[k] - previous[k]));
  }
  out.periodic_error = largest > 0.0 ? difference / largest : difference;
  const std::vector<double> one_period(out.reaction.begin(), out.reaction.end() - 1);
  const auto [rs, rc] = FirstHarmonic(one_period, phase);
  out.force_amplitude = std::hypot(rs, rc);
  out.stiffness = amplitude != 0.0 ? out.force_amplitude / std::abs(amplitude) : 0.0;
  out.phase = std::atan2(rc, rs);
  double work = 0.0;
  for (int k = 0; k < samples; ++k) work += out.reaction[k] * out.v[k];
  out.loop_energy = work / (frequency * samples);
  // finite rows can still give figures that overflow (R v near 1e300)
  for (const auto& [name, value] : {std::pair<const char*, double>{"the force amplitude", out.force_amplitude},
                                    {"K", out.stiffness}, {"the phase", out.phase},
                                    {"the loop energy", out.loop_energy}, {"the periodicity error", out.periodic_error}})
    if (!std::isfinite(value)) return Failed(std::move(out), name);
  out.periodic = difference <= kPeriodicTolerance * largest + 1e-300;
  return out;
}

void RunCases(const ForceAnalysisRequest& request, const std::vector<std::vector<double>>& combinations,
              ForceAnalysis* analysis) {
  run::Model model(request.file, request.options);  // read once; rebuilt with each combination's values
  for (const auto& values : combinations) {
    for (std::size_t i = 0; i < values.size(); ++i)
      for (const std::string& name : request.vary[i].first) model.Set(name, values[i]);
    const diagrams::LoadedDiagram& loaded = model.Loaded();
    const FoundElement found = FindElement(loaded, request.element);
    analysis->diagram = loaded.description.name;
    analysis->element_what = "element '" + request.element + "'" +
                             (request.component.empty() ? "" : " component " + request.component);
    for (double a : request.amplitudes)
      for (double f : request.frequencies) {
        StopIfInterrupted(request.interrupt);
        ForceAnalysisCase c = RunCase(loaded, found, request, a, f);
        c.varied = values;
        analysis->cases.push_back(std::move(c));
      }
  }
}

}  // namespace

std::pair<double, double> FirstHarmonic(const std::vector<double>& values, double phase0) {
  const int n = static_cast<int>(values.size());
  double s = 0.0, c = 0.0;
  for (int k = 0; k < n; ++k) {
    const double phase = 2.0 * std::numbers::pi * k / n + phase0;
    s += values[k] * std::sin(phase);
    c += values[k] * std::cos(phase);
  }
  return {2.0 * s / n, 2.0 * c / n};
}

ForceAnalysis RunForceAnalysis(const ForceAnalysisRequest& request) {
  if (request.amplitudes.empty()) throw InputError("force analysis: give at least one amplitude");
  if (request.frequencies.empty()) throw InputError("force analysis: give at least one frequency");
  for (double a : request.amplitudes)
    if (!(a > 0.0) || !std::isfinite(a)) throw InputError("force analysis: an amplitude must be > 0");
  for (double f : request.frequencies)
    if (!(f > 0.0) || !std::isfinite(f)) throw InputError("force analysis: a frequency must be > 0 Hz");
  // the drive's velocity a w and acceleration a w^2 must be numbers
  for (double a : request.amplitudes)
    for (double f : request.frequencies)
      if (const double w = 2.0 * std::numbers::pi * f; !std::isfinite(a * w * w) || !std::isfinite(a * w))
        throw InputError("force analysis: amplitude " + MessageNumber(a) + " at " + MessageNumber(f) +
                         " Hz: the drive's acceleration a (2 pi f)^2 overflows; give a smaller amplitude or frequency");
  if (request.cycles < 2) throw InputError("force analysis: --cycles must be at least 2 (two periods to compare)");
  if (request.samples < 16) throw InputError("force analysis: at least 16 samples per period");
  // every case keeps its rows in memory
  if (double(request.cycles) * request.samples > kMaxRowsPerCase)
    throw InputError("force analysis: --cycles " + std::to_string(request.cycles) + " times --samples " +
                     std::to_string(request.samples) + " rows per case is more than " + MessageNumber(kMaxRowsPerCase) +
                     "; fewer cycles or samples per period");

  // every combination of the varied values, last one fastest
  std::vector<std::vector<double>> combinations = {{}};
  for (const auto& [names, values] : request.vary) {
    if (values.empty()) throw InputError("force analysis: --vary " + names.front() + " has no values");
    std::vector<std::vector<double>> next;
    for (const auto& c : combinations)
      for (double v : values) {
        next.push_back(c);
        next.back().push_back(v);
      }
    combinations = std::move(next);
  }
  ForceAnalysis analysis;
  analysis.planned = combinations.size() * request.amplitudes.size() * request.frequencies.size();
  try {
    RunCases(request, combinations, &analysis);
  } catch (const Interrupted& e) {  // the cases finished so far stand
    analysis.interrupted = e.signal();
  }
  return analysis;
}

}  // namespace mechflow::analysis
