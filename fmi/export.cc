#include "fmi/export.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

#include "blocks/support/input_file.h"
#include "fmi/model_description.h"
#include "fmi/packed_settings.h"
#include "fmi/variables.h"
#include "fmi/zip_writer.h"
#include "mech/errors.h"
#include "run/model.h"

namespace mechflow::fmi {
namespace {

namespace fs = std::filesystem;

// The binary's name: a C identifier (the standard asks for one) from the diagram's name.
std::string ModelIdentifier(const std::string& name) {
  std::string id;
  for (const char c : name) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "m_" + id;
  return id;
}

// A folder of its own under the system's temporary folder, removed with it.
struct TemporaryFolder {
  fs::path path;
  TemporaryFolder() {
    std::random_device random;
    path = fs::temp_directory_path() / ("mechflow-fmu-" + std::to_string(random()) + std::to_string(random()));
    fs::create_directories(path);
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

void ReplaceAll(std::string* text, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; (at = text->find(from, at)) != std::string::npos; at += to.size())
    text->replace(at, from.size(), to);
}

}  // namespace

std::string DefaultRuntimeFolder() {
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  return error ? "fmu" : (program.parent_path() / "fmu").string();
}

ExportSummary ExportFmu(const ExportRequest& request) {
  run::LoadOptions options;
  options.variants = request.variants;
  options.overrides = request.overrides;
  options.expression_overrides = request.expression_overrides;
  // loaded where it is first: its own errors name its own lines
  run::Model original(request.diagram, options);
  const std::string text = blocks::ReadInputFile(request.diagram, "diagram file");

  // then alone, as the FMU will hold it: a file it reads besides itself fails here
  const TemporaryFolder alone;
  const std::string name = fs::path(request.diagram).filename().string();
  const std::string copy = (alone.path / name).string();
  {
    std::ofstream out(copy, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write the temporary copy " + copy);
  }
  std::unique_ptr<run::Model> packed;
  try {
    packed = std::make_unique<run::Model>(copy, options);
  } catch (const InputError& e) {
    std::string message = e.what();
    ReplaceAll(&message, copy, request.diagram);
    throw InputError(message + "\n" + request.diagram +
                     ": export-fmu packs the diagram file alone, and this diagram reads another file; an FMU of it "
                     "cannot be made yet (write tables as points=, scripts and blocks inline)");
  }
  const diagrams::LoadedDiagram& loaded = packed->Loaded();
  std::vector<Variable> variables;
  try {
    variables = CollectVariables(loaded);
  } catch (const InputError& e) {
    std::string message = e.what();  // the lines are the original's
    ReplaceAll(&message, copy, request.diagram);
    throw InputError(message);
  }

  PackedSettings settings{name, request.variants, request.overrides, request.expression_overrides, ""};
  settings.guid = GuidOf(text + "\n" + settings.Text());
  ExportSummary summary;
  summary.model_identifier = ModelIdentifier(loaded.description.name);
  summary.guid = settings.guid;
  for (const Variable& v : variables) {
    if (v.causality == Causality::kOutput) ++summary.outputs;
    if (v.causality == Causality::kInput) ++summary.inputs;
    if (v.causality == Causality::kParameter) ++summary.parameters;
  }

  const fs::path runtime(request.runtime);
  const fs::path binary = runtime / "linux64" / "libmechflow_fmi.so";
  if (!fs::is_regular_file(binary))
    throw std::runtime_error("the FMU's binary " + binary.string() +
                             " is missing: build the target mechflow_fmi (cmake --build build --target mechflow_fmi)");
  std::vector<ZipEntry> entries;
  entries.push_back({"modelDescription.xml", ModelDescriptionXml(loaded, variables, {summary.model_identifier,
                                                                                      summary.guid}), ""});
  entries.push_back({"resources/" + name, text, ""});
  entries.push_back({"resources/mechflow.txt", settings.Text(), ""});
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(runtime / "linux64")) files.push_back(e.path());
  for (const auto& e : fs::directory_iterator(runtime / "udunits")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    const std::string folder = f.parent_path().filename().string();
    if (folder == "udunits") {
      entries.push_back({"resources/udunits/" + f.filename().string(), "", f.string()});
    } else {
      const std::string file = f == binary ? summary.model_identifier + ".so" : f.filename().string();
      entries.push_back({"binaries/linux64/" + file, "", f.string()});
      summary.binaries.push_back(file);
    }
  }
  WriteZip(request.fmu, entries);

  const diagrams::DiagramDescription& d = original.Loaded().description;
  for (const char* attribute : {"csv", "plot", "animation", "gltf"})
    if (const diagrams::Attribute* a = diagrams::FindAttribute(d.output, attribute))
      summary.left_out.push_back(a->loc.str() + ": <output " + attribute + ">");
  for (const auto& [items, tag] : {std::pair{&d.reports, "<report>"}, std::pair{&d.spectra, "<spectrum>"},
                                   std::pair{&d.xy_plots, "<xy>"}})
    for (const diagrams::ReportDesc& r : *items) summary.left_out.push_back(r.loc.str() + ": " + tag);
  return summary;
}

}  // namespace mechflow::fmi
