#include "scripting/expression_block.h"

#include <cctype>
#include <memory>
#include <sstream>

#include "mech/errors.h"
#include "scripting/compiled_expression.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

class ExpressionBlock : public blocks::Block {
 public:
  ExpressionBlock(const std::string& name, const std::string& expr, const std::vector<std::string>& inputs,
                  LuaState& lua, const IdentifierTable& ids)
      : Block("expression", name), arguments_(inputs.size() + 1) {
    for (const auto& input : inputs) DeclareInputPort(input);
    DeclareOutputPort("y");
    std::vector<std::string> names = {"t"};
    names.insert(names.end(), inputs.begin(), inputs.end());
    expression_ = std::make_unique<CompiledExpression>(lua, expr, names, ids, "=block '" + name + "'");
  }

 protected:
  void DoCalcOutput(int, const blocks::BlockContext& ctx) const override {
    arguments_[0] = ctx.time();
    for (int i = 0; i < num_inputs(); ++i) arguments_[i + 1] = ctx.input_scalar(i);
    try {
      ctx.output(0)[0] = expression_->Evaluate(arguments_.data());
    } catch (const SimulationError& e) {
      throw SimulationError(std::string(e.what()) + " (at t = " + std::to_string(ctx.time()) + ")");
    }
  }

 private:
  std::unique_ptr<CompiledExpression> expression_;
  // scratch for the call; a diagram is evaluated by one simulator at a time
  mutable std::vector<double> arguments_;
};

std::vector<std::string> SplitNames(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> names;
  for (std::string name; in >> name;) names.push_back(name);
  return names;
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
    const std::vector<std::string> inputs = p.Has("inputs") ? SplitNames(p.Text("inputs")) : std::vector<std::string>{};
    for (size_t i = 0; i < inputs.size(); ++i) {
      const std::string& in = inputs[i];
      bool valid = !in.empty() && (std::isalpha(static_cast<unsigned char>(in[0])) || in[0] == '_');
      for (const char c : in) valid &= std::isalnum(static_cast<unsigned char>(c)) || c == '_';
      if (!valid || in == "t") throw InputError("input name '" + in + "' must be a Lua name other than t");
      for (size_t j = 0; j < i; ++j)
        if (inputs[j] == in) throw InputError("input name '" + in + "' is given twice");
    }
    return std::make_unique<ExpressionBlock>(name, p.Text("expr"), inputs, *lua, *identifiers);
  };
  registry->Add(std::move(type));
}

}  // namespace mechflow::scripting
