#include "cli/run_outputs.h"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "blocks/outputs/csv.h"
#include "blocks/support/suggest.h"
#include "cli/interrupt.h"
#include "cli/plot.h"
#include "cli/psd_output.h"
#include "cli/report.h"

namespace mechflow::cli {

std::unique_ptr<ResultsFile> OpenResults(const diagrams::LoadedDiagram& loaded, const blocks::Simulator& sim,
                                         const RunOutputPlan& plan, std::uint64_t max_bytes, PlotEnvelope* envelope) {
  std::unique_ptr<ResultsFile> file;
  try {
    file = plan.results_fd >= 0 ? std::make_unique<ResultsFile>(plan.results_fd, sim.results().columns())
                                : std::make_unique<ResultsFile>(*plan.folder, loaded.csv_file, sim.results().columns());
  } catch (const WriteError& e) {
    throw InputError(e.what());
  }
  file->SetByteLimit(max_bytes);
  if (envelope) envelope->set_next(file.get());
  return file;
}

std::string ResultsNameOrigin(const diagrams::LoadedDiagram& loaded, const std::optional<std::string>& results_option) {
  const auto& output = loaded.description.output;
  const bool csv_attribute =
      std::find_if(output.begin(), output.end(), [](const auto& a) { return a.name == "csv"; }) != output.end();
  return results_option && *results_option != "-" ? "--results " + loaded.csv_file
         : csv_attribute                          ? "<output csv=\"" + loaded.csv_file + "\">"
                                                  : "the diagram's name \"" + loaded.description.name + "\"";
}

std::vector<OutputStem> RunStems(const diagrams::LoadedDiagram& loaded, const RunOutputPlan& plan,
                                 const std::optional<std::string>& results_option) {
  if (!plan.folder) return {};
  // the results' stem names every file beside them (units, report, spectra), written with or without --results -
  std::vector<OutputStem> stems = {{StemOf(loaded.csv_file), ResultsNameOrigin(loaded, results_option)}};
  if (plan.plot && !loaded.plot_file.empty())
    stems.push_back({StemOf(loaded.plot_file), "<output plot=\"" + loaded.plot_file + "\">"});
  return stems;
}

void SayWhatStandardOutputLeavesOut(const diagrams::LoadedDiagram& loaded, const RunOutputPlan& plan, bool no_plot,
                                    std::ostream& out) {
  const std::string stem = StemOf(loaded.csv_file);
  if (!plan.folder) {
    std::vector<std::string> files = {stem + ".units.csv"};
    if (!loaded.reports.empty()) files.push_back(stem + ".report.csv");
    if (loaded.control) files.push_back(stem + ".changes.csv (if the script changes identifiers)");
    for (const diagrams::SpectrumRequest& s : loaded.spectra) files.push_back(stem + "." + s.column + ".psd.csv");
    for (const std::string& file : {loaded.animation_file, loaded.gltf_file})
      if (!file.empty()) files.push_back(file);
    out << "note: --results - without --out writes the results only, not " << blocks::JoinNames(files)
        << " (give --out DIR for them)\n";
  }
  std::vector<std::string> plots;
  if (!loaded.plot_file.empty()) plots.push_back(loaded.plot_file);
  for (const diagrams::SpectrumRequest& s : loaded.spectra) plots.push_back(stem + "." + s.column + ".psd.png");
  if (!no_plot && !plots.empty())
    out << "note: --results - draws no plot (gnuplot draws from files): not " << blocks::JoinNames(plots)
        << " (--no-plot says so and leaves this note out)\n";
}

bool WriteRunOutputs(const diagrams::LoadedDiagram& loaded, const blocks::Simulator& sim,
                     const std::vector<run::Column>& columns, const RunOutputPlan& plan, ResultsFile* results_file,
                     std::ostream& out, std::ostream& err, int* stopped_by, const PlotEnvelope* envelope) {
  const bool to_stdout = plan.results_fd >= 0;
  if (!plan.folder) {  // --results - without --out: the results are all
    if (const std::string problem = results_file->Close(); !problem.empty()) {
      err << problem << "\n";
      return false;
    }
    out << "wrote the results to standard output (" << results_file->rows() << " rows)\n";
    return true;
  }
  const OutputFolder& folder = *plan.folder;
  std::vector<std::string> written, failed, cut;
  const auto write = [&](const std::string& name, const std::string& bytes, const std::string& note) {
    try {
      folder.Write(name, bytes);
      written.push_back(name);
      out << "wrote " << folder.PathOf(name) << note << "\n";
    } catch (const WriteError& e) {
      err << e.what() << "\n";
      failed.push_back(name);
    }
  };
  // a signal while gnuplot draws: that plot and every later one not drawn, said on `err`
  const auto stopped = [&](const Interrupted& e) {
    err << e.what() << "\n";
    *stopped_by = e.signal();
  };
  const auto text = [](const auto& write_to) {
    std::ostringstream s;
    write_to(s);
    return s.str();
  };
  const std::string& csv = loaded.csv_file;
  const std::string results_name = to_stdout ? "the results on standard output" : csv;
  if (const std::string problem = results_file->Close(); problem.empty()) {
    written.push_back(results_name);
    out << "wrote " << (to_stdout ? "the results to standard output" : folder.PathOf(csv)) << " ("
        << results_file->rows() << " rows)\n";
  } else {
    err << problem << "\n";
    // kept: the rows before the cut are what the run computed
    cut.push_back(results_name + " (" + results_file->cut_reason() + ": its rows before the cut are kept)");
  }
  // beside the results: tension_mechanism.csv -> tension_mechanism.report.csv
  const std::string stem = std::filesystem::path(csv).replace_extension().string();
  // the unit of every column (STEM.units.csv: column,unit), where known
  write(stem + ".units.csv", text([&](std::ostream& s) {
          s << "column,unit\n";
          for (const run::Column& c : columns) s << blocks::CsvField(c.name) << ',' << blocks::CsvField(c.unit) << '\n';
        }),
        "");
  if (!sim.results().figures().empty())
    write(stem + ".report.csv", text([&](std::ostream& s) { sim.results().WriteFiguresCsv(s); }), "");
  if (loaded.control && !loaded.control->changes().empty())
    write(stem + ".changes.csv",
          text([&](std::ostream& s) { WriteScriptChanges(*loaded.control, *loaded.identifiers, s); }), "");
  if (!plan.plot) {
    // --no-plot or --results -: gnuplot draws nothing
  } else if (!loaded.plot_file.empty() && sim.results().num_rows() < 2) {
    err << "warning: no plot: the run left " << sim.results().num_rows() << " row"
        << (sim.results().num_rows() == 1 ? "" : "s") << ", nothing to draw\n";
  } else if (!loaded.plot_file.empty()) {
    // a long run's plot draws from its envelope, beside the plot
    EnvelopeFiles files;
    if (envelope && envelope->worthwhile()) {
      files = {envelope, loaded.plot_file + ".envelope.csv", loaded.plot_file + ".xy.csv"};
      write(files.name, envelope->Csv(sim.results().columns()), "");
      if (!loaded.xy_plots.empty()) write(files.xy_name, envelope->XYCsv(sim.results().columns()), "");
    }
    const std::string script = GnuplotScript(sim.results(), loaded.groups, loaded.description.name, csv,
                                             loaded.plot_file, loaded.xy_plots, files);
    try {
      const std::string problem = DrawPlot(script, folder, loaded.plot_file);
      if (problem.empty()) {
        written.push_back(loaded.plot_file);
        out << "wrote " << folder.PathOf(loaded.plot_file) << "\n";
      } else {
        err << "warning: no plot: " << problem << "\n";
      }
    } catch (const WriteError& e) {
      err << e.what() << "\n";
      failed.push_back(loaded.plot_file);
    } catch (const Interrupted& e) {
      stopped(e);
    }
  }
  // <spectrum>s: STEM.COLUMN.psd.csv and .png
  for (const diagrams::SpectrumRequest& s : loaded.spectra) {
    const blocks::Results& r = sim.results();
    PsdRequest request;
    request.time = r.Column(0);
    request.signals.push_back({s.column, r.Column(r.FindColumn(s.column))});
    request.options = {s.segment, s.overlap,
                       s.window == "hann" ? analysis::Window::kHann : analysis::Window::kRectangular};
    request.from = s.from;
    request.peaks = s.peaks;
    request.max_frequency = s.max_frequency;
    request.stem = stem + "." + s.column;
    request.title = loaded.description.name + ": " + s.column;
    request.plot = plan.plot;
    request.options.interrupt = InterruptFlag();  // Ctrl-C: no spectrum (mechflow psd computes it from the results)
    try {
      const std::string problem = WritePsd(request, folder, out);
      if (!problem.empty()) err << "warning: no plot: " << problem << "\n";
      written.push_back(request.stem + ".psd.csv");
    } catch (const analysis::Interrupted& e) {
      err << s.origin << ": <spectrum>: not computed, " << e.what() << "; mechflow psd " << folder.PathOf(csv)
          << " --signal " << s.column << " computes it\n";
      failed.push_back(request.stem + ".psd.csv");
    } catch (const InputError& e) {
      err << s.origin << ": <spectrum>: " << e.what() << "\n";
      failed.push_back(request.stem + ".psd.csv");
    } catch (const WriteError& e) {
      err << e.what() << "\n";
      failed.push_back(request.stem + ".psd.csv");
    } catch (const Interrupted& e) {
      stopped(e);  // the spectrum's CSV was written before its plot
      written.push_back(request.stem + ".psd.csv");
    }
  }
  if (failed.empty() && cut.empty()) return true;
  err << "in " << folder.path() << ": written " << (written.empty() ? "nothing" : blocks::JoinNames(written));
  if (!cut.empty()) err << "; cut " << blocks::JoinNames(cut);
  if (!failed.empty()) err << "; not written " << blocks::JoinNames(failed);
  err << "\n";
  return false;
}

}  // namespace mechflow::cli
