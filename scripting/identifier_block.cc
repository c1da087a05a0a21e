#include "scripting/identifier_block.h"

#include "blocks/support/suggest.h"
#include "mech/errors.h"
#include "scripting/identifiers.h"

namespace mechflow::scripting {

IdentifierBlock::IdentifierBlock(const std::string& name, int identifier, double initial)
    : Block("identifier", name), identifier_(identifier), initial_(initial) {
  DeclareOutputPort("y");
  DeclareDiscreteStates(1);
}

void RegisterIdentifierBlock(blocks::BlockRegistry* registry, const IdentifierTable* identifiers) {
  blocks::BlockType type;
  type.name = "identifier";
  type.doc = "y = the identifier's current value (a control script may change it with sim:set)";
  type.params = {{"identifier", blocks::ParamKind::kText, true, "", "name of an identifier of the diagram"}};
  type.create = [identifiers](const std::string& name, const blocks::BlockParams& p) {
    const std::string& wanted = p.Text("identifier");
    const int id = identifiers->Find(wanted);
    if (id < 0)
      throw InputError("no identifier named '" + wanted + "'" + blocks::DidYouMean(ToLower(wanted), identifiers->Names()));
    return std::make_unique<IdentifierBlock>(name, id, identifiers->value(id));
  };
  registry->Add(std::move(type));
}

}  // namespace mechflow::scripting
