#include "scripting/expression_block.h"

#include <algorithm>
#include <memory>
#include <sstream>

#include "mech/errors.h"
#include "scripting/compiled_expression.h"
#include "scripting/identifiers.h"
#include "scripting/lua_block.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

class ExpressionBlock : public blocks::Block {
 public:
  ExpressionBlock(const std::string& name, const std::string& expr, const std::vector<std::string>& inputs,
                  LuaState& lua, const IdentifierTable& identifiers)
      : Block("expression", name) {
    for (const auto& input : inputs) DeclareInputPort(input);
    DeclareOutputPort("y");  // every input feeds y: the default
    std::vector<std::string> names = {"t"};
    names.insert(names.end(), inputs.begin(), inputs.end());
    expression_ = std::make_unique<CompiledExpression>(lua, expr, std::move(names), identifiers,
                                                       "=block '" + name + "'");
  }

 protected:
  // (t, inputs...) for the call, sized once per run
  struct Scratch final : blocks::BlockScratch {
    explicit Scratch(int n) : arguments(n, 0.0) {}
    std::vector<double> arguments;
  };

  std::unique_ptr<blocks::BlockScratch> MakeScratch() const override {
    return std::make_unique<Scratch>(num_inputs() + 1);
  }

  void DoCalcOutput(int, const blocks::BlockContext& ctx) const override {
    std::vector<double>& arguments = ctx.scratch<Scratch>().arguments;
    arguments[0] = ctx.time();
    for (int i = 0; i < num_inputs(); ++i) arguments[i + 1] = ctx.input_scalar(i);
    ctx.output(0)[0] = expression_->Evaluate(arguments.data());
  }

 private:
  std::unique_ptr<CompiledExpression> expression_;
};

std::vector<std::string> SplitNames(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> names;
  for (std::string name; in >> name;) names.push_back(name);
  return names;
}

// Throws InputError unless `inputs` are usable as ports and as Lua arguments.
void CheckInputNames(const std::vector<std::string>& inputs, const IdentifierTable& identifiers) {
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string& in = inputs[i];
    if (!IsLuaName(in) || in == "t")
      throw InputError("input name '" + in + "' must be a Lua name (letters, digits, '_'; not a keyword) other than t");
    if (std::find(inputs.begin(), inputs.begin() + i, in) != inputs.begin() + i)
      throw InputError("input name '" + in + "' is given twice");
    if (const int id = identifiers.Find(in); id >= 0)
      throw InputError("input name '" + in + "' is also the name of the identifier '" + identifiers.spelling(id) +
                       "' (" + identifiers.origin(id) + "); rename the input");
  }
}

}  // namespace

void RegisterScriptingBlocks(blocks::BlockRegistry* registry, LuaState* lua, const IdentifierTable* identifiers) {
  blocks::BlockType type;
  type.name = "expression";
  type.doc = "y = Lua expression of the inputs and t";
  type.params = {
      {"expr", blocks::ParamKind::kText, true, "", "Lua expression of t, the inputs and identifiers"},
      {"inputs", blocks::ParamKind::kText, false, "u", "space-separated input port names (may be empty)"},
  };
  type.create = [lua, identifiers](const std::string& name, const blocks::BlockParams& p) {
    const std::vector<std::string> inputs = SplitNames(p.Has("inputs") ? p.Text("inputs") : "u");
    CheckInputNames(inputs, *identifiers);
    return std::make_unique<ExpressionBlock>(name, p.Text("expr"), inputs, *lua, *identifiers);
  };
  registry->Add(std::move(type));
  RegisterLuaBlock(registry, lua, identifiers);
}

}  // namespace mechflow::scripting
