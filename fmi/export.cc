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
  std::string name;  // under resources/, '/'-separated (Layout)
  fs::path real;     // where it was read
};

// The folder of `file` as an absolute path without a trailing separator.
fs::path FolderOf(const std::string& file) {
  const fs::path parent = fs::path(file).parent_path();
  fs::path folder = fs::absolute(parent.empty() ? fs::path(".") : parent).lexically_normal();
  return folder.has_filename() ? folder : folder.parent_path();
}

// The deepest folder holding both (absolute, normal paths), component by component.
fs::path CommonFolder(const fs::path& a, const fs::path& b) {
  fs::path common;
  for (auto i = a.begin(), j = b.begin(); i != a.end() && j != b.end() && *i == *j; ++i, ++j) common /= *i;
  return common;
}

bool Inside(const fs::path& path, const fs::path& folder) {
  const fs::path relative = path.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != "..";
}

// Where the diagram and the files it read go under resources/: by their
// paths from the deepest folder holding them all, the diagram's own unless a
// file lies outside it (--allow-read, --library), so that every name the
// diagram and its files use resolves in the FMU as it did here.
struct Layout {
  fs::path root;                     // absolute
  std::string diagram;               // the diagram's path from root, '/'-separated
  std::vector<PackedFile> files;     // each once
  std::vector<std::string> library;  // the --library folders files came from, from root
};

// From the files the loaded diagram read besides itself (the reader's and the loader's record of them).
Layout LayoutOf(const diagrams::LoadedDiagram& loaded, const std::string& diagram,
                const std::vector<std::string>& library) {
  std::vector<blocks::FileRead> reads = loaded.description.files_read;
  if (loaded.reads) reads.insert(reads.end(), loaded.reads->files_read().begin(), loaded.reads->files_read().end());
  std::vector<fs::path> paths;
  for (const blocks::FileRead& r : reads) paths.push_back(fs::absolute(r.path).lexically_normal());
  Layout layout;
  layout.root = FolderOf(diagram);
  std::vector<fs::path> used;  // library folders something was read from
  for (const std::string& l : library) {
    const fs::path folder = FolderOf((fs::path(l) / "x").string());
    if (std::any_of(paths.begin(), paths.end(), [&](const fs::path& p) { return Inside(p, folder); }))
      used.push_back(folder);
  }
  for (const fs::path& p : paths) layout.root = CommonFolder(layout.root, p.parent_path());
  for (const fs::path& l : used) layout.root = CommonFolder(layout.root, l);
  layout.diagram = fs::absolute(diagram).lexically_normal().lexically_relative(layout.root).generic_string();
  for (const fs::path& l : used) {
    const std::string name = l.lexically_relative(layout.root).generic_string();
    layout.library.push_back(name.empty() ? "." : name);
  }
  for (std::size_t k = 0; k < reads.size(); ++k) {
    const std::string name = paths[k].lexically_relative(layout.root).generic_string();
    if (name == "mechflow.txt" || name.rfind("udunits/", 0) == 0 || name == layout.diagram)
      throw InputError(reads[k].where + ": the file '" + reads[k].path + "' would be resources/" + name +
                       " in the FMU, which holds the FMU's own " + (name == layout.diagram ? "diagram" : "settings") +
                       " there: rename it (or move it into another folder)");
    if (std::none_of(layout.files.begin(), layout.files.end(), [&](const PackedFile& f) { return f.name == name; }))
      layout.files.push_back({name, reads[k].real});
  }
  return layout;
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
  options.allow_read = request.allow_read;
  options.library = request.library;
  // loaded where it is first: its own errors name its own lines
  run::Model original(request.diagram, options);
  const std::string text = blocks::ReadInputFile(request.diagram, "diagram file");
  const Layout layout = LayoutOf(original.Loaded(), request.diagram, request.library);
  const std::string fmu_name = original.Loaded().description.name + ".fmu";
  if (const std::string problem = FileNameProblem(fmu_name); !problem.empty())
    throw InputError(request.diagram + ": the FMU is named after the diagram, and '" + fmu_name + "' " + problem +
                     "; give the diagram a plain name (<diagram name=\"...\">)");

  // then alone with the files it read, as the FMU will hold them and load
  // them (reading allowed in its folder only): a file named so that it is
  // not found there (an absolute path) fails here
  const TemporaryFolder alone;
  const std::string name = layout.diagram;
  const std::string copy = (alone.path / name).string();
  const auto write = [](const fs::path& path, const std::string& bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << bytes;
    if (!out.flush()) throw std::runtime_error("cannot write the temporary copy " + path.string());
  };
  write(copy, text);
  for (const PackedFile& f : layout.files)
    write(alone.path / f.name, blocks::ReadInputFile(f.real.string(), "file"));
  const auto in_original = [&](std::string message) {
    ReplaceAll(&message, alone.path.string(), layout.root.string());
    return message;
  };
  PackedSettings settings{name, request.variants, request.overrides, request.expression_overrides, "", layout.library};
  std::unique_ptr<run::Model> packed;
  try {
    packed = std::make_unique<run::Model>(copy, settings.Options(alone.path.string()));
  } catch (const InputError& e) {
    std::string there = e.what();  // the FMU's paths, as its user would see them
    ReplaceAll(&there, alone.path.string(), "resources");
    throw InputError(request.diagram +
                     ": export-fmu loads the diagram as the FMU will (from its resources/ folder, which holds the "
                     "diagram and the files it read by their paths from the folder holding them all), and there it "
                     "fails; name each file by a path relative to the file that names it. There:\n" +
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

  // the GUID covers every packed file: another table is another FMU
  std::string hashed = text + "\n" + settings.Text();
  for (const PackedFile& f : layout.files)
    hashed += "\n" + f.name + "\n" + blocks::ReadInputFile((alone.path / f.name).string(), "file");
  settings.guid = GuidOf(hashed);
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
  for (const PackedFile& f : layout.files) entries.push_back({"resources/" + f.name, "", (alone.path / f.name).string()});
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
  summary.files = static_cast<int>(layout.files.size());
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
