#pragma once
// What an exported FMU needs to load its diagram as export-fmu loaded it:
// resources/mechflow.txt names the packed diagram, the variants and --set
// values given to export-fmu, and the FMU's GUID (a hash of the diagram's
// text, the files it reads and these settings, so an importer's
// modelDescription.xml from another export is refused).
//
//   diagram stick_slip.xml
//   variant Elastic
//   set mu=0.25
//   set-expression c=2*k
//   library lib/parts
//   guid {0f3e...}
//
// The diagram and the files it reads lie in resources/ by their paths from
// the folder holding them all (fmi/export.h); `library` lines name the
// --library folders parts were found in, from resources/.

#include <string>
#include <utility>
#include <vector>

#include "run/model.h"

namespace mechflow::fmi {

struct PackedSettings {
  std::string diagram;  // its path from resources/
  std::vector<std::string> variants;
  std::vector<std::pair<std::string, double>> overrides;
  std::vector<std::pair<std::string, std::string>> expression_overrides;
  std::string guid;
  std::vector<std::string> library;  // from resources/

  std::string Text() const;  // the file's content
  // How the diagram is loaded from `resources` (the folder): variants and
  // --set values, reading allowed in `resources` only, parts looked up in
  // its library folders.
  run::LoadOptions Options(const std::string& resources) const;
  // From the file's content; throws InputError naming `file`:line for a line it cannot read.
  static PackedSettings Parse(const std::string& text, const std::string& file);
};

// "{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}" from a hash of `text`.
std::string GuidOf(const std::string& text);

}  // namespace mechflow::fmi
