// `mechflow check` as data: what cli/report.cc PrintCheck prints, in dicts
// and lists.

#include "blocks/solver/analytic_jacobian.h"
#include "python/bindings/bindings.h"
#include "scripting/instance_path.h"

namespace mechflow::python {

py::dict CheckToPython(const diagrams::LoadedDiagram& loaded) {
  const blocks::Diagram& d = *loaded.diagram;
  const scripting::IdentifierTable& ids = *loaded.identifiers;
  py::dict out;
  out["name"] = loaded.description.name;
  out["blocks"] = d.num_blocks();
  out["connections"] = d.connections().size();
  out["num_states"] = d.num_states();
  out["num_zero_crossings"] = d.num_zero_crossings();

  py::list identifiers;
  for (int i = 0; i < ids.size(); ++i) {
    py::dict e;
    e["name"] = ids.spelling(i);
    e["value"] = ids.value(i) / ids.to_si(i);
    e["unit"] = ids.unit(i);
    e["si_value"] = ids.value(i);
    e["definition"] = ids.is_expression(i) ? py::object(py::str(scripting::WithInstancePaths(ids.definition(i))))
                                           : py::object(py::none());
    e["comment"] = ids.comment(i);
    identifiers.append(e);
  }
  out["identifiers"] = identifiers;

  py::list variants;
  for (const auto& v : loaded.description.variants) {
    py::dict e, assignments;
    e["group"] = v.group;
    e["name"] = v.name;
    for (const auto& a : v.assignments) assignments[py::str(a.name)] = a.value;
    e["assignments"] = assignments;
    variants.append(e);
  }
  out["variants"] = variants;

  // the evaluation order: an output port, or an algebraic loop solved as one step
  py::list schedule;
  for (const auto& node : d.schedule()) {
    py::dict e;
    if (node.loop >= 0) {
      e["kind"] = "loop";
      e["loop"] = node.loop;
      e["description"] = d.loops()[node.loop].description();
    } else {
      const blocks::Block& b = d.block(node.block);
      e["kind"] = "output";
      e["port"] = b.name() + "." + b.output_port(node.port).name;
      e["type"] = b.type();
    }
    schedule.append(e);
  }
  out["schedule"] = schedule;

  py::list loops;
  for (const blocks::AlgebraicLoop& loop : d.loops()) {
    py::dict e;
    py::list tears;
    for (const blocks::OutputNode& tear : loop.tears())
      tears.append(d.block(tear.block).name() + "." + d.block(tear.block).output_port(tear.port).name);
    e["through"] = loop.port();
    e["tears"] = tears;
    e["unknowns"] = loop.num_unknowns();
    e["tolerance"] = blocks::AlgebraicLoop::kRelativeTolerance;
    e["description"] = loop.description();
    loops.append(e);
  }
  out["algebraic_loops"] = loops;

  py::list states;
  for (const int bi : d.stateful_blocks()) {
    const blocks::Block& b = d.block(bi);
    for (int i = 0; i < b.num_states(); ++i) states.append(b.name() + "." + b.state_name(i));
  }
  out["states"] = states;  // in state order: x[0], x[1], ...

  std::string why;
  const bool analytic = blocks::AnalyticJacobian::FindBlock(d, &why) >= 0;
  out["jacobian"] = analytic ? "analytic" : "difference quotients";
  out["jacobian_why"] = analytic ? "" : why;

  py::list crossings;
  static const char* kDirection[] = {"rising", "falling", "either"};
  for (const int bi : d.crossing_blocks()) {
    const blocks::Block& b = d.block(bi);
    for (int i = 0; i < b.num_zero_crossings(); ++i) {
      py::dict e;
      e["index"] = d.layout(bi).first_crossing + i;
      e["block"] = b.name();
      e["number"] = i;
      e["direction"] = kDirection[static_cast<int>(b.crossing_direction(i))];
      crossings.append(e);
    }
  }
  out["zero_crossings"] = crossings;

  py::list sampled;
  for (const int bi : d.periodic_blocks()) {
    py::dict e;
    e["block"] = d.block(bi).name();
    e["period"] = d.block(bi).sample_time().period;
    e["offset"] = d.block(bi).sample_time().offset;
    sampled.append(e);
  }
  out["sampled_blocks"] = sampled;

  if (loaded.control) {
    py::dict e;
    e["name"] = loaded.control->name();
    e["functions"] = loaded.control->functions();
    out["control_script"] = e;
  } else {
    out["control_script"] = py::none();
  }
  const auto& s = loaded.solver;
  py::dict solver;
  solver["t_start"] = s.t_start;
  solver["t_end"] = s.t_end;
  solver["rtol"] = s.rtol;
  solver["atol"] = s.atol;
  solver["interval"] = s.output_interval;
  out["solver"] = solver;
  out["logged_columns"] = loaded.logged.size();
  py::list instances;
  for (const diagrams::InstanceDesc& i : loaded.description.instances) {
    py::dict e;
    e["path"] = i.path;
    e["kind"] = i.kind;
    e["component"] = i.component;
    instances.append(e);
  }
  out["instances"] = instances;
  out["warnings"] = loaded.warnings;
  return out;
}

}  // namespace mechflow::python
