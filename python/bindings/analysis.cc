// Spectra (analysis/spectrum.h) and force analysis (analysis/force_analysis.h)
// as numpy arrays.

#include "analysis/force_analysis.h"
#include "analysis/spectrum.h"
#include "python/bindings/bindings.h"

namespace mechflow::python {
namespace {

py::dict Psd(const py::array_t<double, py::array::c_style | py::array::forcecast>& samples, double dt, int segment,
             double overlap, const std::string& window, int peaks, bool handle_sigint) {
  if (samples.ndim() != 1) throw py::value_error("psd: samples must be one-dimensional");
  if (!(dt > 0)) throw py::value_error("psd: dt must be > 0 (the sampling interval in seconds)");
  std::vector<double> values(samples.data(), samples.data() + samples.size());
  analysis::WelchOptions options;
  options.segment = segment;
  options.overlap = overlap;
  options.window = analysis::ParseWindow(window, "psd window=");
  analysis::Spectrum spectrum;
  std::vector<analysis::SpectralPeak> found;
  {
    const py::gil_scoped_release unlocked;
    const SigintGuard guard(handle_sigint);
    options.interrupt = guard.flag();
    spectrum = analysis::WelchPsd(values, dt, options);
    found = analysis::FindPeaks(spectrum, peaks);
  }
  py::dict d;
  d["segment"] = spectrum.segment;
  d["segments"] = spectrum.segments;
  d["resolution"] = spectrum.resolution;
  d["frequency"] = ToArray(std::move(spectrum.frequency));
  d["density"] = ToArray(std::move(spectrum.density));
  std::vector<double> peak_frequency, peak_level;
  for (const analysis::SpectralPeak& p : found) {
    peak_frequency.push_back(p.frequency);
    peak_level.push_back(p.level);
  }
  d["peak_frequency"] = ToArray(std::move(peak_frequency));
  d["peak_level"] = ToArray(std::move(peak_level));
  return d;
}

std::vector<double> Values(const py::handle& v) {
  if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return {v.cast<double>()};
  return v.cast<std::vector<double>>();
}

}  // namespace

py::dict ForceAnalysisToPython(const std::string& path, const diagrams::LoadOptions& base, const py::dict& kwargs,
                               bool handle_sigint) {
  analysis::ForceAnalysisRequest request;
  request.file = path;
  request.options = WithSettings(base, ToSettings(kwargs.contains("set") ? py::object(kwargs["set"]) : py::object(py::none())));
  request.element = kwargs["element"].cast<std::string>();
  if (kwargs.contains("component") && !kwargs["component"].is_none())
    request.component = kwargs["component"].cast<std::string>();
  request.amplitudes = Values(kwargs["amplitude"]);
  request.frequencies = Values(kwargs["frequency"]);
  request.cycles = kwargs["cycles"].cast<int>();
  request.samples = kwargs["samples"].cast<int>();
  if (request.cycles < 2) throw py::value_error("force_analysis: cycles must be at least 2");
  if (request.samples < 16) throw py::value_error("force_analysis: samples must be at least 16");
  if (kwargs.contains("vary") && !kwargs["vary"].is_none())
    for (const auto& [names, values] : kwargs["vary"].cast<py::dict>()) {
      std::vector<std::string> split;
      if (py::isinstance<py::str>(names)) split.push_back(names.cast<std::string>());
      else split = names.cast<std::vector<std::string>>();
      request.vary.emplace_back(split, Values(values));
    }
  analysis::ForceAnalysis fa;
  {
    const py::gil_scoped_release unlocked;
    const SigintGuard guard(handle_sigint);
    request.interrupt = guard.flag();
    fa = analysis::RunForceAnalysis(request);
  }
  if (fa.interrupted) throw analysis::Interrupted(fa.interrupted);
  const std::size_t n = fa.cases.size();
  std::vector<double> amplitude, frequency, stiffness, phase, force, energy, x0, error;
  py::list periodic, failure, loops;
  py::array_t<double> varied({n, request.vary.size()});
  auto v = varied.mutable_unchecked<2>();
  for (std::size_t k = 0; k < n; ++k) {
    analysis::ForceAnalysisCase& c = fa.cases[k];
    amplitude.push_back(c.amplitude);
    frequency.push_back(c.frequency);
    stiffness.push_back(c.stiffness);
    phase.push_back(c.phase);
    force.push_back(c.force_amplitude);
    energy.push_back(c.loop_energy);
    x0.push_back(c.x0);
    error.push_back(c.periodic_error);
    periodic.append(c.periodic);
    failure.append(c.failure);
    for (std::size_t i = 0; i < c.varied.size(); ++i) v(k, i) = c.varied[i];
    py::dict loop;
    loop["x"] = ToArray(std::move(c.x));
    loop["v"] = ToArray(std::move(c.v));
    loop["reaction"] = ToArray(std::move(c.reaction));
    loops.append(loop);
  }
  py::dict d;
  d["diagram"] = fa.diagram;
  d["element"] = fa.element_what;
  py::list vary_names;
  for (const auto& entry : request.vary) vary_names.append(entry.first);
  d["vary"] = vary_names;
  d["varied"] = varied;
  d["amplitude"] = ToArray(std::move(amplitude));
  d["frequency"] = ToArray(std::move(frequency));
  d["stiffness"] = ToArray(std::move(stiffness));
  d["phase"] = ToArray(std::move(phase));
  d["force_amplitude"] = ToArray(std::move(force));
  d["loop_energy"] = ToArray(std::move(energy));
  d["x0"] = ToArray(std::move(x0));
  d["periodic_error"] = ToArray(std::move(error));
  d["periodic"] = periodic;
  d["failure"] = failure;
  d["loops"] = loops;
  return d;
}

void BindAnalysis(py::module_& m) {
  m.def("psd", &Psd, py::arg("samples"), py::arg("dt"), py::arg("segment"), py::arg("overlap"), py::arg("window"),
        py::arg("peaks"), py::arg("handle_sigint"), "Welch PSD and its peaks as a dict of arrays (mechflow.psd)");
}

}  // namespace mechflow::python
