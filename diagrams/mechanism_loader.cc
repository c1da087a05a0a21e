#include "diagrams/mechanism_loader.h"

#include <set>

#include "blocks/library/mechanism_block.h"
#include "diagrams/follow_inputs.h"
#include "diagrams/mechanism_reader.h"

namespace mechflow::diagrams {

std::unique_ptr<blocks::Block> BuildMechanismBlock(const ElementDesc& written, const Evaluator& eval,
                                                   std::vector<std::string>* warnings) {
  const ElementDesc m = FollowInputs(written, *eval.identifiers());
  const MechanismReader r(m, eval);
  mech::ModelBuilder builder;
  builder.SetGravity(r.Vector(m, "gravity", Vec3(0, 0, -9.81)));
  std::map<std::string, mech::BodySpec> bodies;  // by name, for the joints' frames
  for (const ElementDesc& e : m.children)
    if (e.tag == "body") {
      mech::BodySpec body = ReadBody(r, e);
      builder.AddBody(body);
      bodies.emplace(body.name, std::move(body));
    }
  for (const ElementDesc& e : m.children)
    if (e.tag == "joint") builder.AddJoint(ReadJoint(r, e, bodies, eval));
  const std::shared_ptr<const mech::Model> model = builder.Build();
  mech::Kinematics kin0(*model);
  const std::vector<double> v0(model->nv(), 0.0);
  mech::UpdateKinematics(*model, 0.0, model->initial_q(), v0, &kin0);
  std::vector<std::unique_ptr<mech::ForceElement>> elements;
  std::set<std::string> element_names;
  for (const ElementDesc& e : m.children) {
    if (e.tag != "force" && e.tag != "joint_force" && e.tag != "bushing" && e.tag != "applied_force" &&
        e.tag != "contact" && e.tag != "gearing")
      continue;
    if (!element_names.insert(e.Text("name")).second) r.Fail(e, "a second element with this name");
    elements.push_back(ReadElement(r, e, *model, kin0));
  }
  // Work and dissipation sensors need a state in their element, an energy
  // balance in every element (found by name through an index: a sensor per
  // element would otherwise search them all).
  std::map<std::string, mech::ForceElement*, std::less<>> element_by_name;
  for (auto& element : elements) element_by_name.emplace(element->name(), element.get());
  bool every_element_tracked = false;
  for (const ElementDesc& e : m.children) {
    if (e.tag != "sensor") continue;
    const std::string kind = e.Text("kind"), quantity = e.Text("quantity", "force");
    const bool balance = kind == "energy_balance";
    if (!balance && !(kind == "element" && (quantity == "work" || quantity == "dissipated"))) continue;
    if (balance) {
      if (!every_element_tracked)
        for (auto& element : elements) element->TrackWork();
      every_element_tracked = true;
    } else if (const auto it = element_by_name.find(e.Text("element")); it != element_by_name.end()) {
      it->second->TrackWork();
    }
  }
  std::vector<std::string> input_names;
  for (const ElementDesc& e : m.children)
    if (e.tag == "input") {
      // the port is named as the subsystem holding the mechanism names the
      // identifier: "F", not its path "d[1].F"
      const std::string name = e.Text("name");
      input_names.push_back(name.substr(name.find_last_of('.') + 1));
    }
  auto mechanism = std::make_shared<mech::Mechanism>(model, std::move(elements), input_names);
  const bool prescribed = std::any_of(model->segments().begin(), model->segments().end(),
                                      [](const mech::Segment& s) { return s.drive == mech::SegmentDrive::kTime; });
  for (const ElementDesc& e : m.children)
    if (e.tag == "sensor" && e.Text("kind") == "energy_balance" && prescribed) mechanism->TrackDriveWork();
  std::vector<mech::SensorSpec> sensors;
  for (const ElementDesc& e : m.children)
    if (e.tag == "sensor") sensors.push_back(ReadSensor(r, e, *mechanism));
  // Assemble once now, so that a loop that cannot close is bad input (exit 2)
  // rather than a failed run -- unless signals drive segments: their values
  // are known only once the diagram runs (the block assembles then).
  if (model->drive_signals().empty()) {
    mech::MechanismWorkspace ws(*mechanism);
    std::vector<double> x(mechanism->num_states()), modes(mechanism->num_modes());
    std::vector<double> inputs(mechanism->num_inputs(), 0.0);
    mech::InitialState(*mechanism, inputs, x, modes, &ws);
    // what the start says to check (a contact already beyond its bound
    // never crosses it, so the run would not warn)
    for (int e = 0; e < mechanism->num_elements(); ++e) {
      const mech::ForceElement& element = mechanism->element(e);
      const std::string warning = element.StartWarning(mech::MakeElementContext(*mechanism, 0.0, x, modes, ws, e));
      if (!warning.empty()) warnings->push_back(element.origin() + ": warning: " + warning);
    }
  }
  return std::make_unique<blocks::MechanismBlock>(m.Text("name"), mechanism, std::move(sensors));
}

}  // namespace mechflow::diagrams

