// What a diagram asks of a run's outputs, resolved at load so that a run
// looks nothing up: the logged columns with their units, <report>s,
// <spectrum>s and <xy> panels (diagrams/output_requests.h).
#include "diagrams/output_requests.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/spectrum_limits.h"
#include "blocks/outputs/column_names.h"
#include "blocks/support/suggest.h"
#include "diagrams/attribute_units.h"
#include "diagrams/units.h"
#include "mech/errors.h"
#include "scripting/identifier_block.h"

namespace mechflow::diagrams {
namespace {

// The unit of a signal: the block's (a sensor's, an identifier's), else "".
std::string SignalUnit(const LoadedDiagram& loaded, const blocks::SignalRef& s) {
  const blocks::Diagram& diagram = *loaded.diagram;
  for (int b = 0; b < diagram.num_blocks(); ++b)
    for (int p = 0; p < diagram.block(b).num_outputs(); ++p) {
      if (diagram.layout(b).output_offset[p] != s.offset) continue;
      const auto* id = dynamic_cast<const scripting::IdentifierBlock*>(&diagram.block(b));
      return id ? loaded.identifiers->unit(id->identifier()) : diagram.block(b).OutputUnit(p);
    }
  return "";
}

// SI per unit of a <report>'s figure: a figure is SI (the signal's quantity;
// times it for an integral; a time for a crossing or period) and is shown in
// its unit. A unit of another dimension than the figure's known one is bad input.
double ReportUnitToSi(const blocks::ReportRequest& r, const std::string& own_unit, const Attribute& unit) {
  std::string error;
  const std::optional<Unit> wanted = ParseUnit(unit.value, &error);
  if (!wanted) throw InputError(unit.loc.str() + ": <report> of '" + r.signal.name + "': " + error);
  const Dimension second{{0, 0, 1}};
  std::optional<Dimension> figure;
  if (r.kind == blocks::ReportKind::kCrossing || r.kind == blocks::ReportKind::kPeriod) {
    figure = second;
  } else if (const std::optional<Unit> own = Trim(own_unit).empty() ? std::nullopt : ParseUnit(own_unit, &error)) {
    figure = r.kind == blocks::ReportKind::kIntegral ? own->dimension.Times(second) : own->dimension;
  }
  if (figure && !figure->SameAs(wanted->dimension))
    throw InputError(unit.loc.str() + ": <report> of '" + r.signal.name + "': its " +
                     blocks::ReportKindName(r.kind) + " is " + figure->Describe() + " (" + figure->SiUnit() +
                     "), which cannot be shown in " + wanted->text + " (" + wanted->dimension.Describe() + ")");
  return wanted->to_si;
}

// SI per unit of a logged column: signals are SI, a column in `log_unit`
// ("" none: the signal's own unit, SI unless it is an identifier's) shows
// them converted. A <log> unit of another dimension than the signal's own
// is bad input.
double ColumnUnitToSi(const blocks::SignalRef& s, const std::string& log_unit, const std::string& own_unit,
                      const SourceLoc& loc) {
  std::string error;
  const std::optional<Unit> own = Trim(own_unit).empty() ? std::nullopt : ParseUnit(own_unit, &error);
  if (Trim(log_unit).empty()) return own ? own->to_si : 1.0;  // "-" and other labels: as they are
  const std::optional<Unit> wanted = ParseUnit(log_unit, &error);
  if (!wanted) throw InputError(loc.str() + ": <log> of '" + s.name + "': " + error);
  if (own && !own->dimension.SameAs(wanted->dimension))
    throw InputError(loc.str() + ": <log> of '" + s.name + "': the signal is " + own->dimension.Describe() + " (" +
                     own->text + "), which cannot be shown in " + wanted->text + " (" + wanted->dimension.Describe() +
                     "); give a unit of " + own->dimension.Describe() + " or none");
  return wanted->to_si;
}

// Logged signals: <log> elements first, then the inputs of every recorder.
void CollectLoggedSignals(const DiagramDescription& d, LoadedDiagram* out) {
  std::map<std::string, int> group_index;
  std::map<std::string, std::string> column_origin;
  int column = 1;
  out->units = {"s"};
  const auto unit_of = [&](const blocks::SignalRef& s) { return SignalUnit(*out, s); };
  auto add = [&](blocks::SignalRef s, const std::string& group, const SourceLoc& loc, const std::string& unit) {
    if (s.name == "time")
      throw InputError(loc.str() + ": a logged column named 'time', which is the name of the first column (the "
                       "time); give it another label");
    if (column_origin.count(s.name))
      throw InputError(loc.str() + ": a second logged column named '" + s.name + "' (the first is at " +
                       column_origin[s.name] + "); give one a different label");
    column_origin[s.name] = loc.str();
    if (!group_index.count(group)) {
      group_index[group] = static_cast<int>(out->groups.size());
      out->groups.push_back({group, {}, {}});
    }
    // the column's unit: the <log>'s, else the signal's own; values in it
    const std::string column_unit = unit.empty() ? unit_of(s) : Trim(unit);
    s.column_factor = 1.0 / ColumnUnitToSi(s, unit, unit_of(s), loc);
    for (int i = 0; i < s.width; ++i) {
      out->groups[group_index[group]].columns.push_back(column++);
      out->units.push_back(column_unit);
    }
    out->logged.push_back(std::move(s));
  };
  for (const auto& log : d.logs) {
    blocks::SignalRef s;
    try {
      s = out->diagram->ResolveSignal(log.signal);
    } catch (const InputError& e) {
      throw InputError(log.loc.str() + ": <log>: " + e.what());
    }
    const std::string signal_name = s.name;
    if (!log.label.empty()) s.name = log.label;
    add(std::move(s), log.group.empty() ? signal_name : log.group, log.loc, log.unit);
  }
  const blocks::Diagram& diagram = *out->diagram;
  for (int b = 0; b < diagram.num_blocks(); ++b) {
    if (diagram.block(b).type() != "recorder") continue;
    for (const auto& c : diagram.connections()) {
      if (c.to_block != b) continue;
      const blocks::Block& from = diagram.block(c.from_block);
      const auto& layout = diagram.layout(c.from_block);
      blocks::SignalRef s{from.name() + "." + from.output_port(c.from_port).name, layout.output_offset[c.from_port],
                          layout.output_width[c.from_port]};
      add(std::move(s), diagram.block(b).name(), d.blocks[b].loc, "");
    }
  }
  for (PlotGroup& g : out->groups) {
    const std::string& unit = out->units[g.columns.front()];
    bool common = !unit.empty() && unit != "-";
    for (const int c : g.columns) common &= out->units[c] == unit;
    g.axis_label = common && g.name.find('[') == std::string::npos ? g.name + " [" + unit + "]" : g.name;
  }
}

// <report>s: exactly one of peak/min/peak_abs naming a signal, resolved now
// so that a run looks nothing up.
void CollectReports(const DiagramDescription& d, const Evaluator& eval, LoadedDiagram* out) {
  for (const ReportDesc& r : d.reports) {
    blocks::ReportRequest request;
    const Attribute* signal = nullptr;
    for (const auto kind : blocks::kReportKinds) {
      const Attribute* a = FindAttribute(r.attributes, blocks::ReportKindName(kind));
      if (!a) continue;
      if (signal)
        throw InputError(a->loc.str() + ": <report> asks for '" + signal->name + "' and '" + a->name +
                         "'; one figure per <report>");
      signal = a;
      request.kind = kind;
    }
    if (!signal)
      throw InputError(r.loc.str() + ": <report> needs one of peak, min, peak_abs, mean, rms, integral, final, "
                                     "crossing or period =\"signal\"");
    const Attribute* level = FindAttribute(r.attributes, "level");
    const bool crossings = request.kind == blocks::ReportKind::kCrossing || request.kind == blocks::ReportKind::kPeriod;
    if (level && !crossings)
      throw InputError(level->loc.str() + ": <report>: level is for crossing and period, not " +
                       blocks::ReportKindName(request.kind));
    if (!level && request.kind == blocks::ReportKind::kCrossing)
      throw InputError(r.loc.str() + ": <report crossing=...> needs level=\"...\" (the value whose first crossing "
                                     "is timed)");
    if (level) request.level = eval.Number(level->value, level->loc.str() + ": <report> attribute 'level'");
    try {
      request.signal = out->diagram->ResolveSignal(Trim(signal->value));
    } catch (const InputError& e) {
      throw InputError(signal->loc.str() + ": <report>: " + e.what());
    }
    if (const Attribute* index = FindAttribute(r.attributes, "index")) {
      const double i = eval.Number(index->value, index->loc.str() + ": <report> attribute 'index'");
      if (!(i >= 0 && i < request.signal.width && i == std::floor(i)))
        throw InputError(index->loc.str() + ": <report>: index " + index->value + " is not an element of '" +
                         request.signal.name + "' (width " + std::to_string(request.signal.width) + ")");
      request.index = static_cast<int>(i);
    } else if (request.signal.width != 1) {
      throw InputError(signal->loc.str() + ": <report>: signal '" + request.signal.name + "' has width " +
                       std::to_string(request.signal.width) + "; choose an element with index=\"0\" .. \"" +
                       std::to_string(request.signal.width - 1) + "\"");
    }
    const Attribute* label = FindAttribute(r.attributes, "label");
    request.label = label ? label->value : std::string(blocks::ReportKindName(request.kind)) + " of " +
                                               request.signal.name;
    if (const Attribute* unit = FindAttribute(r.attributes, "unit")) {
      request.unit = Trim(unit->value);
      request.signal.column_factor = 1.0 / ReportUnitToSi(request, SignalUnit(*out, request.signal), *unit);
    } else {  // the figure in SI: its unit where the signal's is known
      const std::string own = RawSignalUnit(*out, request.signal);
      request.unit = crossings ? "s"
                     : request.kind == blocks::ReportKind::kIntegral ? (own.empty() ? "" : own + " s")
                                                                     : own;
    }
    out->reports.push_back(std::move(request));
  }
}

// <spectrum>s: a logged column (as the results name it) and the Welch
// options, checked now so that a bad one is bad input before the run.
void CollectSpectra(const DiagramDescription& d, const Evaluator& eval, LoadedDiagram* out) {
  const std::vector<std::string> columns = blocks::LoggedColumnNames(out->logged);
  for (const ReportDesc& r : d.spectra) {
    SpectrumRequest request;
    request.origin = r.loc.str();
    const Attribute* signal = FindAttribute(r.attributes, "signal");
    request.column = Trim(signal->value);
    if (std::find(columns.begin(), columns.end(), request.column) == columns.end())
      throw InputError(signal->loc.str() + ": <spectrum>: '" + request.column + "' is not a logged column" +
                       blocks::DidYouMean(request.column, columns) + "; log it with <log signal=\"...\"/> (columns: " +
                       blocks::JoinNames(columns) + ")");
    const auto number = [&](const char* name, double fallback) {
      const Attribute* a = FindAttribute(r.attributes, name);
      return a ? eval.Number(a->value, a->loc.str() + ": <spectrum> attribute '" + name + "'") : fallback;
    };
    const double segment = number("segment", 0), peaks = number("peaks", 5);
    request.overlap = number("overlap", 0.5);
    request.from = number("from", -1e300);
    request.max_frequency = number("max_frequency", 0.0);
    if (!(segment == 0 || (segment >= 16 && segment <= 1 << 24 && segment == std::floor(segment))))
      throw InputError(r.loc.str() + ": <spectrum>: segment must be a whole number of samples, at least 16");
    if (!(request.overlap >= 0 && request.overlap <= analysis::kMaxOverlap))
      throw InputError(r.loc.str() + ": <spectrum>: overlap must be from 0 to 0.99 (each sample is transformed "
                       "about 1 / (1 - overlap) times); 0.5 is usual");
    if (FindAttribute(r.attributes, "max_frequency") && !(request.max_frequency > 0))
      throw InputError(r.loc.str() + ": <spectrum>: max_frequency must be > 0 Hz (leave it out for the whole range)");
    if (!(peaks >= 0 && peaks <= 1000 && peaks == std::floor(peaks)))
      throw InputError(r.loc.str() + ": <spectrum>: peaks must be a whole number from 0 to 1000");
    request.segment = static_cast<int>(segment);
    request.peaks = static_cast<int>(peaks);
    if (const Attribute* w = FindAttribute(r.attributes, "window")) {
      request.window = Trim(w->value);
      if (request.window != "hann" && request.window != "rectangular")
        throw InputError(w->loc.str() + ": <spectrum>: unknown window '" + request.window +
                         "'; expected hann or rectangular");
    }
    out->spectra.push_back(std::move(request));
  }
}

// <xy>s: curves="X:Y X:Y ..." naming logged columns.
void CollectXYPlots(const DiagramDescription& d, LoadedDiagram* out) {
  std::vector<std::string> columns = blocks::LoggedColumnNames(out->logged);
  columns.insert(columns.begin(), "time");
  auto column = [&](const std::string& name, const Attribute& a) {
    const auto it = std::find(columns.begin(), columns.end(), name);
    if (it == columns.end())
      throw InputError(a.loc.str() + ": <xy>: '" + name + "' is not a logged column" +
                       blocks::DidYouMean(name, columns) + "; log it with <log signal=\"...\"/> (columns: " +
                       blocks::JoinNames(columns) + ")");
    return static_cast<int>(it - columns.begin());
  };
  for (const ReportDesc& r : d.xy_plots) {
    XYPlotRequest request;
    const Attribute* curves = FindAttribute(r.attributes, "curves");
    std::stringstream in(curves->value);
    for (std::string pair; in >> pair;) {
      const auto colon = pair.find(':');
      if (colon == std::string::npos || colon == 0 || colon + 1 == pair.size())
        throw InputError(curves->loc.str() + ": <xy>: curves are X:Y pairs of logged columns, got '" + pair + "'");
      request.curves.emplace_back(column(pair.substr(0, colon), *curves), column(pair.substr(colon + 1), *curves));
    }
    if (request.curves.empty()) throw InputError(curves->loc.str() + ": <xy>: curves=\"X:Y ...\" names no curve");
    const auto text = [&](const char* name, const std::string& fallback) {
      const Attribute* a = FindAttribute(r.attributes, name);
      return a ? a->value : fallback;
    };
    request.x_label = text("x_label", columns[request.curves[0].first]);
    request.y_label = text("y_label", columns[request.curves[0].second]);
    request.title = text("title", request.y_label + " against " + request.x_label);
    out->xy_plots.push_back(std::move(request));
  }
}

}  // namespace

std::string RawSignalUnit(const LoadedDiagram& loaded, const blocks::SignalRef& s) {
  const std::string unit = SignalUnit(loaded, s);
  std::string error;
  const std::optional<Unit> parsed = Trim(unit).empty() ? std::nullopt : ParseUnit(unit, &error);
  return parsed && parsed->to_si == 1.0 ? unit : "";
}

void CollectOutputRequests(const DiagramDescription& d, const Evaluator& eval, LoadedDiagram* out) {
  CollectLoggedSignals(d, out);
  CollectReports(d, eval, out);
  CollectSpectra(d, eval, out);
  CollectXYPlots(d, out);
}

}  // namespace mechflow::diagrams
