#pragma once
// A small FMI 2.0 co-simulation importer for the tests: unpacks an .fmu
// (libzip), loads its binary with dlopen, looks up the fmi2 functions by
// name and drives them in the standard's order. Declarations are ours
// (fmi/fmi2_api.h), as an importer would write them from the standard.

#include <dlfcn.h>
#include <zip.h>

#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "fmi/fmi2_api.h"

namespace mechflow::fmu_harness {

namespace fs = std::filesystem;

// Every entry of the zip file `fmu` under `folder`.
inline void Unzip(const std::string& fmu, const fs::path& folder) {
  int error = 0;
  zip_t* z = zip_open(fmu.c_str(), ZIP_RDONLY, &error);
  if (!z) throw std::runtime_error("cannot open " + fmu);
  for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0); ++i) {
    const std::string name = zip_get_name(z, i, 0);
    zip_stat_t st;
    zip_stat_index(z, i, 0, &st);
    std::string bytes(st.size, '\0');
    zip_file_t* f = zip_fopen_index(z, i, 0);
    if (!f || zip_fread(f, bytes.data(), st.size) != static_cast<zip_int64_t>(st.size))
      throw std::runtime_error("cannot read " + name + " of " + fmu);
    zip_fclose(f);
    fs::create_directories((folder / name).parent_path());
    std::ofstream(folder / name, std::ios::binary) << bytes;
  }
  zip_close(z);
}

// What the FMU logged, one line per message: "STATUS CATEGORY: message".
inline std::vector<std::string>& LogLines() {
  static std::vector<std::string> lines;
  return lines;
}

inline void Logger(fmi2ComponentEnvironment, fmi2String, fmi2Status status, fmi2String category, fmi2String message,
                   ...) {
  char text[4096];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message, args);
  va_end(args);
  LogLines().push_back(std::to_string(status) + " " + category + ": " + text);
}

// The unpacked FMU: its folder, model description and binary's functions.
class Fmu {
 public:
  Fmu(const std::string& fmu_file, const fs::path& folder) : folder_(folder) {
    fs::remove_all(folder);
    Unzip(fmu_file, folder);
    if (description_.LoadFile((folder / "modelDescription.xml").c_str()) != tinyxml2::XML_SUCCESS)
      throw std::runtime_error("no modelDescription.xml in " + fmu_file);
    const tinyxml2::XMLElement* root = description_.RootElement();
    guid_ = root->Attribute("guid");
    identifier_ = root->FirstChildElement("CoSimulation")->Attribute("modelIdentifier");
    for (const tinyxml2::XMLElement* v = root->FirstChildElement("ModelVariables")->FirstChildElement(); v;
         v = v->NextSiblingElement())
      references_[v->Attribute("name")] = v->UnsignedAttribute("valueReference");
    handle_ = dlopen(binary().c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle_) throw std::runtime_error(std::string("dlopen: ") + dlerror());
  }
  ~Fmu() {
    if (handle_) dlclose(handle_);
  }
  Fmu(const Fmu&) = delete;
  Fmu& operator=(const Fmu&) = delete;

  fs::path binary() const { return folder_ / "binaries" / "linux64" / (identifier_ + ".so"); }
  const tinyxml2::XMLDocument& description() const { return description_; }
  fmi2ValueReference Ref(const std::string& name) const { return references_.at(name); }
  void* Symbol(const char* name) const { return dlsym(handle_, name); }

  template <typename F>
  F* Function(const char* name) const {
    void* f = Symbol(name);
    if (!f) throw std::runtime_error(std::string("the FMU lacks ") + name);
    return reinterpret_cast<F*>(f);
  }

  // (guid: the model description's unless given)
  fmi2Component Instantiate(const std::string& name, const std::string& guid = "") {
    callbacks_ = {Logger, nullptr, nullptr, nullptr, nullptr};
    const std::string resources = "file://" + (folder_ / "resources").string();
    return Function<decltype(fmi2Instantiate)>("fmi2Instantiate")(name.c_str(), fmi2CoSimulation,
                                                                  (guid.empty() ? guid_ : guid).c_str(),
                                                                  resources.c_str(), &callbacks_, fmi2False,
                                                                  fmi2False);
  }
  // SetupExperiment (the default experiment's start, stopTime t_end), then
  // through initialisation mode, with `parameters` set before
  // (tolerance > 0: the relative tolerance, else the diagram's)
  fmi2Status Initialize(fmi2Component c, double t_end, const std::map<std::string, double>& parameters = {},
                        double tolerance = 0.0) {
    if (fmi2Status s = Function<decltype(fmi2SetupExperiment)>("fmi2SetupExperiment")(
            c, tolerance > 0.0 ? fmi2True : fmi2False, tolerance, Start(), fmi2True, t_end);
        s != fmi2OK)
      return s;
    for (const auto& [name, value] : parameters)
      if (fmi2Status s = Set(c, name, value); s != fmi2OK) return s;
    if (fmi2Status s = Function<decltype(fmi2EnterInitializationMode)>("fmi2EnterInitializationMode")(c); s != fmi2OK)
      return s;
    return Function<decltype(fmi2ExitInitializationMode)>("fmi2ExitInitializationMode")(c);
  }
  double Start() const {
    return description_.RootElement()->FirstChildElement("DefaultExperiment")->DoubleAttribute("startTime");
  }
  double Get(fmi2Component c, const std::string& name) {
    const fmi2ValueReference vr = Ref(name);
    double v = 0.0;
    if (Function<decltype(fmi2GetReal)>("fmi2GetReal")(c, &vr, 1, &v) != fmi2OK)
      throw std::runtime_error("fmi2GetReal " + name + " failed");
    return v;
  }
  fmi2Status Set(fmi2Component c, const std::string& name, double value) {
    const fmi2ValueReference vr = Ref(name);
    return Function<decltype(fmi2SetReal)>("fmi2SetReal")(c, &vr, 1, &value);
  }
  fmi2Status DoStep(fmi2Component c, double t, double h) {
    return Function<decltype(fmi2DoStep)>("fmi2DoStep")(c, t, h, fmi2True);
  }
  void Free(fmi2Component c) {
    Function<decltype(fmi2Terminate)>("fmi2Terminate")(c);
    Function<decltype(fmi2FreeInstance)>("fmi2FreeInstance")(c);
  }

 private:
  fs::path folder_;
  tinyxml2::XMLDocument description_;
  std::string guid_, identifier_;
  std::map<std::string, fmi2ValueReference> references_;
  fmi2CallbackFunctions callbacks_{};
  void* handle_ = nullptr;
};

}  // namespace mechflow::fmu_harness
