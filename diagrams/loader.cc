#include "diagrams/loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <tuple>

#include "blocks/framework/block_factory.h"
#include "blocks/framework/diagram_builder.h"
#include "blocks/library/held_input.h"
#include "blocks/solver/analytic_jacobian.h"
#include "blocks/support/suggest.h"
#include "diagrams/attribute_units.h"
#include "diagrams/evaluator.h"
#include "diagrams/instances.h"
#include "diagrams/mechanism_loader.h"
#include "diagrams/output_requests.h"
#include "diagrams/unit_check.h"
#include "diagrams/units.h"
#include "diagrams/xml_reader.h"
#include "mech/errors.h"
#include "scripting/expression_block.h"
#include "scripting/identifier_block.h"
#include "scripting/instance_path.h"

namespace mechflow::diagrams {
namespace {

blocks::BlockParams EvaluateParams(const BlockDesc& b, const blocks::BlockType& type, const Evaluator& eval,
                                   const std::string& folder, const blocks::ReadPolicy& reads) {
  const std::string who = b.loc.str() + ": block '" + b.name + "' (" + b.type + ")";
  std::vector<std::string> names = {"type", "name"};
  for (const auto& p : type.params) names.push_back(p.name);
  for (const auto& a : b.params)
    if (!type.FindParam(a.name))
      throw InputError(a.loc.str() + ": block '" + b.name + "' (" + b.type + ") has no parameter '" + a.name + "'" +
                       blocks::DidYouMean(a.name, names) + "; valid: " + blocks::JoinNames(names));

  blocks::BlockParams params;
  for (const auto& spec : type.params) {
    const Attribute* a = FindAttribute(b.params, spec.name);
    if (!a && spec.required)
      throw InputError(who + " needs the parameter '" + spec.name + "' (" + spec.doc + ")");
    if (!a && spec.default_value.empty()) continue;
    const std::string text = a ? a->value : spec.default_value;
    const std::string what = (a ? a->loc.str() : b.loc.str()) + ": block '" + b.name + "' parameter '" + spec.name + "'";
    if (a && spec.kind == blocks::ParamKind::kNumber) eval.CheckUnit(text, false, spec.name, spec.unit, what);
    switch (spec.kind) {
      case blocks::ParamKind::kNumber:
        params.SetNumbers(spec.name, {eval.Number(text, what)});
        break;
      case blocks::ParamKind::kNumbers:
        params.SetNumbers(spec.name, eval.Numbers(text, what));
        break;
      case blocks::ParamKind::kTable:
        params.SetTable(spec.name, eval.Table(text, what));
        break;
      case blocks::ParamKind::kText:
        params.SetText(spec.name, text);
        break;
      case blocks::ParamKind::kPath: {
        // code from a file is not rewritten to see an instance's parameters
        // (diagrams/instance_scope.h): it would read the diagram's names instead
        if (type.takes_text && !b.loc.context.empty())
          throw InputError(what + ": inside a subsystem the code is written as the block's text, where the "
                                  "subsystem's parameters are visible; a file would not see them");
        // read here, where the diagram's folder and --allow-read are known
        blocks::NamedFile file = blocks::ReadNamedFile(text, folder, reads, what);
        params.SetFile(spec.name, std::move(file.path), std::move(file.text));
        break;
      }
    }
  }
  return params;
}

// "" when `name` is a plain file name that stays inside the output folder;
// else why not. A diagram may come from someone else: it names files, the
// command line (--out) says where they go.
std::string OutputNameProblem(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return "is not a file name";
  if (name.find_first_of("/\\") != std::string::npos)
    return "must be a plain file name (no folders: results go into the folder given by --out)";
  if (name.size() > 200) return "is longer than 200 characters";
  // gnuplot, which reads the CSV and writes the plot, takes these for an option, a pseudo-file or a command
  if (name.find_first_of("-+<|") == 0) return "may not begin with '-', '+', '<' or '|'";
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "holds a control character";
  return "";
}

void BuildSolverOptions(const DiagramDescription& d, const Evaluator& eval, const LoadOptions& options,
                        blocks::SolverOptions* solver) {
  for (const auto& a : d.solver) {
    const std::string what = a.loc.str() + ": solver setting '" + a.name + "'";
    if (a.name == "linear_solver") {
      if (a.value == "auto") solver->linear_solver = blocks::LinearSolverKind::kAuto;
      else if (a.value == "dense") solver->linear_solver = blocks::LinearSolverKind::kDense;
      else if (a.value == "sparse") solver->linear_solver = blocks::LinearSolverKind::kSparse;
      else if (a.value == "krylov") solver->linear_solver = blocks::LinearSolverKind::kKrylov;
      else throw InputError(what + " is '" + a.value + "'; expected auto, dense, sparse or krylov");
      continue;
    }
    if (a.name == "jacobian") {
      if (a.value == "auto") solver->jacobian = blocks::JacobianKind::kAuto;
      else if (a.value == "analytic") solver->jacobian = blocks::JacobianKind::kAnalytic;
      else if (a.value == "difference") solver->jacobian = blocks::JacobianKind::kDifferenceQuotient;
      else throw InputError(what + " is '" + a.value + "'; expected auto, analytic or difference");
      continue;
    }
    eval.CheckUnit(a.value, false, a.name, AttributeUnit("solver", "", a.name), what);
    const double v = eval.Number(a.value, what);
    if (a.name == "t_start") solver->t_start = v;
    else if (a.name == "t_end") solver->t_end = v;
    else if (a.name == "rtol") solver->rtol = v;
    else if (a.name == "atol") solver->atol = v;
    else if (a.name == "max_step") solver->max_step = v;
    else if (a.name == "initial_step") solver->initial_step = v;
    else if (a.name == "max_steps") {
      // checked before the cast: a double out of long's range has no defined conversion
      if (!(v >= 1 && v <= 1e12 && v == std::floor(v)))
        throw InputError(what + " is " + a.value + "; expected a whole number from 1 to 1e12");
      solver->max_steps = static_cast<long>(v);
    }
  }
  const blocks::SolverOptions from_file = *solver;  // before the run's own values
  if (options.t_end) solver->t_end = *options.t_end;
  if (options.rtol) solver->rtol = *options.rtol;
  if (options.atol) solver->atol = *options.atol;
  if (options.interval) {
    solver->output_interval = *options.interval;
    if (!(*options.interval > 0.0) || !std::isfinite(*options.interval))
      throw InputError("--interval: expected a time > 0 s");
  } else if (const Attribute* a = FindAttribute(d.output, "interval")) {
    eval.CheckUnit(a->value, false, "interval", AttributeUnit("output", "", "interval"),
                   a->loc.str() + ": output setting 'interval'");
    solver->output_interval = eval.Number(a->value, a->loc.str() + ": output setting 'interval'");
    // 0 is the default's internal meaning, not a value a user writes
    if (!(solver->output_interval > 0.0) || !std::isfinite(solver->output_interval))
      throw InputError(a->loc.str() + ": output setting 'interval' is " + a->value +
                       "; expected a time > 0 s (leave it out for 1000 rows)");
  }
  if (const std::string problem = solver->Problem(); !problem.empty()) {
    // the file's own settings first, at its line; else the run's values are to blame
    if (const std::string own = from_file.Problem(); !own.empty()) throw InputError(d.solver_loc.str() + ": " + own);
    throw InputError("the run's own solver settings (--t-end, --rtol, --atol; run()'s t_end, rtol, atol): " + problem);
  }
  if (solver->output_interval > 0.0) {
    const std::string rows = blocks::SamplePeriodProblem(solver->output_interval, solver->t_start, solver->t_end);
    if (!rows.empty()) throw InputError(d.output_loc.str() + ": output interval: " + rows);
  }
}

// A value for an identifier given as a number (--set, a variant) is in the
// identifier's own unit, as the number of its definition is. `context`
// starts the message when it cannot be given.
struct NumberOverride {
  std::string name;
  double value = 0.0;
  std::string context;  // "--set m: ", "d.xml:7: variant 'heavy': "

  void Apply(scripting::IdentifierTable* ids) const {
    try {
      const int i = ids->Find(name);
      ids->Override(name, i >= 0 ? value * ids->to_si(i) : value);
    } catch (const InputError& e) {
      throw InputError(context + e.what());
    }
  }
};

// --variant NAME: the named sets of identifier values, in the order given. A
// name is the variant's own, or "group/variant" when two groups share it.
void CollectVariants(const DiagramDescription& d, const std::vector<std::string>& selected,
                     std::vector<NumberOverride>* out) {
  std::vector<std::string> names;
  for (const auto& v : d.variants) names.push_back(v.name);
  for (const std::string& wanted : selected) {
    std::vector<const VariantDesc*> matches;
    for (const auto& v : d.variants)
      if (v.name == wanted || v.group + "/" + v.name == wanted) matches.push_back(&v);
    if (matches.empty())
      throw InputError("--variant " + wanted + ": " + d.file + " has no such variant" +
                       blocks::DidYouMean(wanted, names) +
                       (names.empty() ? " (it defines none)" : "; variants: " + blocks::JoinNames(names)));
    if (matches.size() > 1)
      throw InputError("--variant " + wanted + ": ambiguous (" + matches[0]->loc.str() + " and " +
                       matches[1]->loc.str() + "); write it as group/variant, e.g. '" + matches[0]->group + "/" +
                       wanted + "'");
    for (const Attribute& a : matches[0]->assignments) {
      double value = 0.0;
      if (!scripting::ParseNumber(a.value, &value))
        throw InputError(a.loc.str() + ": variant '" + wanted + "': the value of '" + a.name +
                         "' must be a number (got '" + a.value + "')");
      out->push_back({a.name, value, a.loc.str() + ": variant '" + wanted + "': "});
    }
  }
}

}  // namespace

void RegisterAllBlocks(blocks::BlockRegistry* registry, scripting::LuaState* lua,
                       const scripting::IdentifierTable* identifiers) {
  blocks::RegisterStandardBlocks(registry);
  scripting::RegisterScriptingBlocks(registry, lua, identifiers);
  scripting::RegisterIdentifierBlock(registry, identifiers);
}

namespace {

LoadedDiagram Load(DiagramDescription d, const LoadOptions& options) {
  LoadedDiagram out;
  out.lua = std::make_unique<scripting::LuaState>(scripting::LuaState::Options{.unsafe = options.unsafe_lua});
  out.identifiers = std::make_unique<scripting::IdentifierTable>();
  scripting::IdentifierTable& ids = *out.identifiers;

  // identifiers: definitions (numbers taken to SI from their units), then
  // variants and command-line overrides, then top-to-bottom evaluation. An
  // override of an instance's parameter waits until flattening has made it.
  std::vector<std::optional<Unit>> units;
  std::vector<NumberOverride> overrides;
  CollectVariants(d, options.variants, &overrides);
  for (const auto& [name, value] : options.overrides) overrides.push_back({name, value, "--set " + name + ": "});
  std::vector<bool> applied(overrides.size(), false);
  const auto add_identifier = [&](const IdentifierDesc& id) {
    std::optional<Unit> unit;
    if (!Trim(id.unit).empty()) {
      std::string error;
      unit = ParseUnit(id.unit, &error);
      if (!unit) throw InputError(id.loc.str() + ": identifier '" + id.name + "': " + error);
    }
    ids.Add(id.name, id.value, id.loc.str(), id.comment, unit ? unit->text : "", unit ? unit->to_si : 1.0);
    units.push_back(std::move(unit));
    const int added = ids.size() - 1;
    for (std::size_t k = 0; k < overrides.size(); ++k) {
      const std::string& name = overrides[k].name;
      // "d[*].k": every element's
      if (scripting::IsInstancePattern(name) ? scripting::MatchesInstancePattern(name, ids.spelling(added))
                                                : !applied[k] && ids.Find(name) == added) {
        NumberOverride{ids.spelling(added), overrides[k].value, overrides[k].context}.Apply(&ids);
        applied[k] = true;
      }
    }
  };
  for (const auto& id : d.identifiers) add_identifier(id);
  ids.Evaluate(*out.lua);
  // --set NAME=EXPR: each evaluated over the identifiers as they are then;
  // the diagram's own before the instances are made (a count may follow
  // them), an instance's after
  const auto set_expressions = [&](bool diagram_level) {
    for (const auto& [name, text] : options.expression_overrides) {
      if (diagram_level != (ids.Find(name) >= 0 && !scripting::IsInstancePath(name))) continue;
      try {
        ids.Override(name, ids.EvaluateExpression(*out.lua, text, "--set " + name + "=" + text));
      } catch (const InputError& e) {
        const std::string message = e.what();
        throw InputError(message.rfind("--set", 0) == 0 ? message : "--set " + name + ": " + message);
      }
      ids.Evaluate(*out.lua);
    }
  };
  set_expressions(true);
  MakeInstances(&d, {add_identifier,
                     [&](const std::string& text, const std::string& what) {
                       double number = 0.0;
                       if (scripting::ParseNumber(text, &number)) return number;
                       ids.Evaluate(*out.lua);
                       return ids.EvaluateExpression(*out.lua, text, what);
                     },
                     &ids});
  for (std::size_t k = 0; k < overrides.size(); ++k) {
    if (applied[k]) continue;
    if (scripting::IsInstancePattern(overrides[k].name))
      throw InputError(overrides[k].context + "no identifier matches '" + overrides[k].name +
                       "' ([*] stands for the index of every element of an array)");
    overrides[k].Apply(&ids);  // names nothing: says so
  }
  ids.Evaluate(*out.lua);
  set_expressions(false);
  const UnitCheck unit_check(out.identifiers.get(), std::move(units));
  unit_check.CheckDefinitions();
  const Evaluator eval(out.lua.get(), out.identifiers.get(), &unit_check);

  // the control script runs first: expressions may call functions it defines
  if (d.script.present()) {
    std::string error;
    if (!scripting::RunControlScript(*out.lua, ids, d.script.code, d.script.chunk_name, &error))
      throw InputError(d.script.loc.str() + ": control script: " + error);
  }

  // blocks and connections
  blocks::BlockRegistry registry;
  RegisterAllBlocks(&registry, out.lua.get(), out.identifiers.get());
  out.reads.emplace(d.file, options.allow_read);
  blocks::DiagramBuilder builder;
  std::vector<std::string> mechanism_warnings;
  for (const auto& m : d.mechanisms) builder.AddBlock(BuildMechanismBlock(m, eval, &mechanism_warnings), m.loc.str());
  for (const auto& b : d.blocks) {
    const blocks::BlockType* type = registry.Find(b.type);
    if (!type)
      throw InputError(b.loc.str() + ": block '" + b.name + "' has unknown type '" + b.type + "'" +
                       blocks::DidYouMean(b.type, registry.Names()) + "; known types: " +
                       blocks::JoinNames(registry.Names()));
    // a file a block names lies beside the file the block is written in
    const std::string folder = std::filesystem::path(b.loc.file).parent_path().string();
    blocks::BlockParams params = EvaluateParams(b, *type, eval, folder, *out.reads);
    if (b.text.find_first_not_of(" \t\r\n") != std::string::npos) {
      if (!type->takes_text)
        throw InputError(b.text_loc.str() + ": block '" + b.name + "' (" + b.type + ") takes no text content");
      params.SetText("#text", b.text);
      params.SetText("#text_file", b.text_loc.file);
      params.SetNumbers("#text_line", {static_cast<double>(b.text_loc.line)});
    }
    std::unique_ptr<blocks::Block> block;
    try {
      block = type->create(b.name, params);
    } catch (const InputError& e) {
      throw InputError(b.loc.str() + ": block '" + b.name + "' (" + b.type + "): " + e.what());
    }
    builder.AddBlock(std::move(block), b.loc.str());
  }
  for (const auto& in : d.inputs) {
    const std::string what = in.loc.str() + ": input '" + in.name + "'";
    // a plain name: it is a block's and an FMU variable's
    const bool plain = !in.name.empty() && !std::isdigit(static_cast<unsigned char>(in.name[0])) &&
                       in.name.find("__") == std::string::npos &&
                       std::all_of(in.name.begin(), in.name.end(), [](char c) {
                         return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                       });
    if (!plain)
      throw InputError(what + ": the name must be letters, digits and '_' (not first a digit, no '__')");
    DiagramInput input{in.name, -1, Trim(in.unit), 1.0, 0.0, in.comment, in.loc.str()};
    if (!input.unit.empty()) {
      std::string error;
      const std::optional<Unit> unit = ParseUnit(input.unit, &error);
      if (!unit) throw InputError(what + ": " + error);
      input.to_si = unit->to_si;
    }
    input.start = eval.Number(in.start, what + " start") * input.to_si;
    builder.AddBlock(std::make_unique<blocks::HeldInputBlock>(in.name, input.start), in.loc.str());
    out.inputs.push_back(std::move(input));
  }
  for (const auto& c : d.connections) builder.Connect(c.from, c.to, c.loc.str());
  // a subsystem's output is reached by its path too (logs, reports, sim:get)
  for (const auto& [alias, target] : d.signal_aliases) builder.AddSignalAlias(alias, target, "output '" + alias + "'");
  if (out.lua->has_run_time_code() || d.script.present())  // one Lua state: one thread at a time runs it
    builder.SetRunClaim([lua = out.lua.get()]() -> std::unique_ptr<blocks::BlockScratch> {
      struct Claim final : blocks::BlockScratch {
        explicit Claim(scripting::LuaState::RunClaim held) : claim(std::move(held)) {}
        scripting::LuaState::RunClaim claim;
      };
      return std::make_unique<Claim>(lua->ClaimForRun());
    });
  out.diagram = builder.Build();
  for (DiagramInput& input : out.inputs) input.block = out.diagram->FindBlock(input.name);
  for (const auto& w : d.input_widths)
    if (const int width = out.diagram->ResolveSignal(w.signal).width; width != w.width)
      throw InputError(w.loc.str() + ": this input carries " + std::to_string(w.width) + " value(s), but '" +
                       w.signal + "', which feeds it, has width " + std::to_string(width));
  if (d.script.present())
    out.control = std::make_unique<scripting::ControlScript>(*out.lua, ids, *out.diagram,
                                                             d.script.chunk_name.substr(1));

  // solver and output settings
  BuildSolverOptions(d, eval, options, &out.solver);
  if (out.solver.jacobian == blocks::JacobianKind::kAnalytic) {
    std::string why = "the krylov linear solver uses no Jacobian";
    if (out.solver.linear_solver == blocks::LinearSolverKind::kKrylov ||
        blocks::AnalyticJacobian::FindBlock(*out.diagram, &why) < 0)
      throw InputError(FindAttribute(d.solver, "jacobian")->loc.str() + ": " +
                       blocks::AnalyticJacobian::Refusal(why));
  }
  CollectOutputRequests(d, eval, &out);
  const Attribute* csv = FindAttribute(d.output, "csv");
  out.csv_file = options.results                     ? *options.results
                 : csv && !Trim(csv->value).empty() ? Trim(csv->value)
                                                    : d.name + ".csv";
  if (options.results) {
    if (const std::string problem = OutputNameProblem(out.csv_file); !problem.empty())
      throw InputError("--results: '" + out.csv_file + "' " + problem);
  }
  if (const std::string problem = OutputNameProblem(out.csv_file); !problem.empty())
    throw InputError(csv ? csv->loc.str() + ": csv file '" + out.csv_file + "' " + problem
                         : d.output_loc.str() + ": the results file '" + out.csv_file + "' named after the diagram " +
                               problem + "; name it with <output csv=\"...\">");
  if (const Attribute* plot = FindAttribute(d.output, "plot")) {
    out.plot_file = Trim(plot->value);
    const std::string ext = std::filesystem::path(out.plot_file).extension().string();
    if (!out.plot_file.empty() && ext != ".png" && ext != ".svg")
      throw InputError(plot->loc.str() + ": plot file '" + out.plot_file + "' must end in .png or .svg");
    if (const std::string problem = OutputNameProblem(out.plot_file); !out.plot_file.empty() && !problem.empty())
      throw InputError(plot->loc.str() + ": plot file '" + out.plot_file + "' " + problem);
  }
  // the animation as HTML and as glTF binary
  for (const auto& [attribute, extension, file] :
       {std::tuple{"animation", ".html", &out.animation_file}, std::tuple{"gltf", ".glb", &out.gltf_file}}) {
    const Attribute* a = FindAttribute(d.output, attribute);
    if (!a) continue;
    *file = Trim(a->value);
    if (std::filesystem::path(*file).extension() != extension)
      throw InputError(a->loc.str() + ": " + attribute + " file '" + *file + "' must end in " + extension);
    if (const std::string problem = OutputNameProblem(*file); !problem.empty())
      throw InputError(a->loc.str() + ": " + attribute + " file '" + *file + "' " + problem);
  }
  if (!d.xy_plots.empty() && out.plot_file.empty())
    throw InputError(d.xy_plots.front().loc.str() + ": <xy> is a panel of the plot, and there is none: name it with "
                                                    "<output plot=\"NAME.png\">");
  out.warnings = unit_check.warnings();
  out.warnings.insert(out.warnings.end(), mechanism_warnings.begin(), mechanism_warnings.end());
  out.description = std::move(d);
  return out;
}

}  // namespace

LoadedDiagram LoadDiagramDescription(DiagramDescription d, const LoadOptions& options) {
  try {
    return Load(std::move(d), options);
  } catch (const SimulationError& e) {
    // nothing runs yet: a value the diagram cannot give when it is loaded (a
    // time function not finite at the start) is bad input; the message names file:line
    throw InputError(e.what());
  }
}

LoadedDiagram LoadDiagram(const std::string& path, const LoadOptions& options) {
  return LoadDiagramDescription(ReadDiagramFile(path, options.allow_read, options.library), options);
}

}  // namespace mechflow::diagrams
