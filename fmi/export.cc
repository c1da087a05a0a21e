#include "fmi/export.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
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

// A file the diagram reads, as the FMU holds it.
struct PackedFile {
  std::string name;  // under resources/: its path from the diagram's folder, '/'-separated
  fs::path real;     // where it was read
};

// The folder of `file` as an absolute path without a trailing separator.
fs::path FolderOf(const std::string& file) {
  const fs::path parent = fs::path(file).parent_path();
  fs::path folder = fs::absolute(parent.empty() ? fs::path(".") : parent).lexically_normal();
  return folder.has_filename() ? folder : folder.parent_path();
}

// Every file the loaded diagram read besides itself (the reader's and the
// loader's record of them), by its path from the diagram's folder; each once.
std::vector<PackedFile> FilesRead(const diagrams::LoadedDiagram& loaded, const std::string& diagram) {
  std::vector<blocks::FileRead> reads = loaded.description.files_read;
  if (loaded.reads) reads.insert(reads.end(), loaded.reads->files_read().begin(), loaded.reads->files_read().end());
  const fs::path folder = FolderOf(diagram);
  const std::string own = fs::path(diagram).filename().string();
  std::vector<PackedFile> files;
  for (const blocks::FileRead& r : reads) {
    const fs::path relative = fs::absolute(r.path).lexically_normal().lexically_relative(folder);
    if (relative.empty() || *relative.begin() == "..")
      throw InputError(r.where + ": the file '" + r.path + "' lies outside the diagram's folder " + folder.string() +
                       "; an FMU holds the files a diagram reads by their paths from its folder: copy the file into "
                       "that folder (or one below it) and name it from there");
    const std::string name = relative.generic_string();
    if (name == "mechflow.txt" || name.rfind("udunits/", 0) == 0 || name == own)
      throw InputError(r.where + ": the file '" + r.path + "' would be resources/" + name +
                       " in the FMU, which holds the FMU's own " + (name == own ? "diagram" : "settings") +
                       " there: rename it (or move it into another folder)");
    if (std::none_of(files.begin(), files.end(), [&](const PackedFile& f) { return f.name == name; }))
      files.push_back({name, r.real});
  }
  return files;
}

// "" when `name` may be the FMU's file name, else why not.
std::string FileNameProblem(const std::string& name) {
  if (name.find('/') != std::string::npos) return "holds a '/'";
  if (name.find_first_of("-+<|") == 0) return "begins with '" + name.substr(0, 1) + "'";
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "holds a control character";
  return "";
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
  const std::vector<PackedFile> reads = FilesRead(original.Loaded(), request.diagram);
  const std::string fmu_name = original.Loaded().description.name + ".fmu";
  if (const std::string problem = FileNameProblem(fmu_name); !problem.empty())
    throw InputError(request.diagram + ": the FMU is named after the diagram, and '" + fmu_name + "' " + problem +
                     "; give the diagram a plain name (<diagram name=\"...\">)");

  // then alone with the files it read, as the FMU will hold them: a file
  // named so that it is not found there (an absolute path) fails here
  const TemporaryFolder alone;
  const std::string name = fs::path(request.diagram).filename().string();
  const std::string copy = (alone.path / name).string();
  const auto write = [](const fs::path& path, const std::string& bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << bytes;
    if (!out.flush()) throw std::runtime_error("cannot write the temporary copy " + path.string());
  };
  write(copy, text);
  for (const PackedFile& f : reads)
    write(alone.path / f.name, blocks::ReadInputFile(f.real.string(), "file"));
  const std::string folder = FolderOf(request.diagram).string();
  const auto in_original = [&](std::string message) {
    ReplaceAll(&message, alone.path.string(), folder);
    return message;
  };
  std::unique_ptr<run::Model> packed;
  try {
    packed = std::make_unique<run::Model>(copy, options);
  } catch (const InputError& e) {
    std::string there = e.what();  // the FMU's paths, as its user would see them
    ReplaceAll(&there, alone.path.string(), "resources");
    throw InputError(request.diagram +
                     ": export-fmu loads the diagram as the FMU will (from its resources/ folder, which holds the "
                     "diagram and the files it read by their paths from its folder), and there it fails; name each "
                     "file by a path relative to the file that names it, inside the diagram's folder. There:\n" +
                     there);
  }
  const diagrams::LoadedDiagram& loaded = packed->Loaded();
  std::vector<Variable> variables;
  try {
    variables = CollectVariables(loaded);
  } catch (const InputError& e) {
    std::string message = e.what();  // the lines are the original's
    ReplaceAll(&message, copy, request.diagram);
    throw InputError(in_original(message));
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
  for (const PackedFile& f : reads) entries.push_back({"resources/" + f.name, "", (alone.path / f.name).string()});
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
  summary.fmu = (fs::path(request.folder) / fmu_name).string();
  summary.files = static_cast<int>(reads.size());
  WriteZip(summary.fmu, entries);

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
