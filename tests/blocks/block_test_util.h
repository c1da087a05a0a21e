#pragma once
// Helpers for the block library tests: make blocks through the registry the
// way the XML loader does (defaults filled from the ParamSpecs, unknown or
// missing parameters rejected), wire them with DiagramBuilder and run them.
//
// Parameter text is read with std::from_chars only (no identifiers or Lua
// expressions), so these tests depend on blocks/ alone, not on the loader.

#include <charconv>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "blocks/framework/block_factory.h"
#include "blocks/framework/diagram_builder.h"
#include "blocks/framework/evaluation.h"
#include "blocks/solver/simulator.h"
#include "blocks/support/input_file.h"
#include "mech/errors.h"

namespace mechflow::blocks::testing {

inline const BlockRegistry& StandardRegistry() {
  static const BlockRegistry registry = [] {
    BlockRegistry r;
    RegisterStandardBlocks(&r);
    return r;
  }();
  return registry;
}

// A context at the diagram's initial state with its modes settled, as
// blocks::Simulator starts a run; the state lives in *x (at least one).
inline Context SettledContext(const Diagram& d, std::vector<double>* x) {
  Context ctx;
  ctx.signals.assign(d.num_signals(), 0.0);
  ctx.discrete.assign(d.num_discrete_states(), 0.0);
  x->assign(std::max(1, d.num_states()), 0.0);
  ctx.x = x->data();
  InitializeStates(d, &ctx);
  SettleModes(d, &ctx);
  return ctx;
}

// "1 2, 3" -> {1, 2, 3}; throws InputError on anything that is not a number.
inline std::vector<double> ParseNumbers(const std::string& text) {
  std::vector<double> values;
  size_t pos = 0;
  while (true) {
    pos = text.find_first_not_of(" ,\t", pos);
    if (pos == std::string::npos) break;
    size_t end = text.find_first_of(" ,\t", pos);
    if (end == std::string::npos) end = text.size();
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data() + pos, text.data() + end, v);
    if (ec != std::errc() || ptr != text.data() + end)
      throw InputError("test helper: '" + text.substr(pos, end - pos) + "' is not a number");
    values.push_back(v);
    pos = end;
  }
  return values;
}

// A number as parameter text, to full precision.
inline std::string Num(double v) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, end);
}

using ParamTexts = std::map<std::string, std::string>;

// Makes a block of `type` from parameter texts, like the loader: every
// parameter not given takes its default text; a required one must be given.
inline std::unique_ptr<Block> MakeBlock(const std::string& type, const std::string& name,
                                        const ParamTexts& given = {}) {
  const BlockType* t = StandardRegistry().Find(type);
  if (!t) throw std::logic_error("no block type '" + type + "'");
  for (const auto& [param, text] : given)
    if (!t->FindParam(param)) throw InputError("block '" + name + "' has no parameter '" + param + "'");
  BlockParams params;
  for (const ParamSpec& spec : t->params) {
    const auto it = given.find(spec.name);
    if (it == given.end() && spec.required) throw InputError("needs the parameter '" + spec.name + "'");
    if (it == given.end() && spec.default_value.empty()) continue;
    const std::string& text = it != given.end() ? it->second : spec.default_value;
    switch (spec.kind) {
      case ParamKind::kNumber:
      case ParamKind::kNumbers:
        params.SetNumbers(spec.name, ParseNumbers(text));
        break;
      case ParamKind::kTable: {
        std::vector<std::vector<double>> rows;
        size_t start = 0;
        while (start <= text.size()) {
          size_t end = text.find(';', start);
          if (end == std::string::npos) end = text.size();
          rows.push_back(ParseNumbers(text.substr(start, end - start)));
          start = end + 1;
        }
        params.SetTable(spec.name, std::move(rows));
        break;
      }
      case ParamKind::kText:
        params.SetText(spec.name, text);
        break;
      case ParamKind::kPath:  // the test's own file: not confined as a diagram's are
        params.SetFile(spec.name, text, ReadInputFile(text, "table file"));
        break;
    }
  }
  return t->create(name, params);
}

// The message of the InputError that making the block throws, or "".
inline std::string MakeError(const std::string& type, const ParamTexts& given = {}) {
  try {
    MakeBlock(type, "b", given);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct Run {
  std::unique_ptr<Diagram> diagram;
  std::unique_ptr<Simulator> sim;
  RunOutcome outcome;

  const Results& results() const { return sim->results(); }
  // The logged column `signal` ("block.port", or "block.port[i]").
  std::vector<double> Column(const std::string& signal) const {
    const int c = results().FindColumn(signal);
    if (c < 0) throw std::logic_error("no logged column '" + signal + "'");
    return results().Column(c);
  }
  std::vector<double> Time() const { return results().Column(0); }
  // Times of the handled zero crossings of one block.
  std::vector<double> EventTimes(const std::string& block) const {
    std::vector<double> times;
    const int b = diagram->FindBlock(block);
    for (const EventRecord& e : sim->events())
      if (e.block == b) times.push_back(e.time);
    return times;
  }
};

// Tight tolerances by default: most answers here are exact or closed form.
inline SolverOptions Options(double t_end, double output_interval, double rtol = 1e-10, double atol = 1e-12) {
  SolverOptions o;
  o.t_end = t_end;
  o.output_interval = output_interval;
  o.rtol = rtol;
  o.atol = atol;
  return o;
}

// Builds the blocks and connections ({from, to}) and runs them, logging `logged`.
inline Run Simulate(std::vector<std::unique_ptr<Block>> blocks,
                    const std::vector<std::pair<std::string, std::string>>& connections,
                    const std::vector<std::string>& logged, const SolverOptions& options) {
  DiagramBuilder builder;
  for (auto& b : blocks) builder.AddBlock(std::move(b));
  for (const auto& [from, to] : connections) builder.Connect(from, to);
  Run run;
  run.diagram = builder.Build();
  std::vector<SignalRef> refs;
  for (const auto& s : logged) refs.push_back(run.diagram->ResolveSignal(s));
  run.sim = std::make_unique<Simulator>(*run.diagram, options, refs);
  run.outcome = run.sim->Run();
  return run;
}

// Collects blocks for Simulate in one expression.
template <typename... B>
std::vector<std::unique_ptr<Block>> Blocks(B... blocks) {
  std::vector<std::unique_ptr<Block>> v;
  (v.push_back(std::move(blocks)), ...);
  return v;
}

}  // namespace mechflow::blocks::testing
