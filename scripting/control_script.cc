#include "scripting/control_script.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <lua.hpp>

#include "blocks/framework/block.h"
#include "blocks/support/message_number.h"
#include "blocks/support/suggest.h"
#include "mech/errors.h"
#include "scripting/compiled_expression.h"
#include "scripting/identifier_bindings.h"
#include "scripting/identifier_block.h"
#include "scripting/identifiers.h"
#include "scripting/instance_path.h"
#include "scripting/lua_guards.h"
#include "scripting/lua_state.h"

namespace mechflow::scripting {
namespace {

using blocks::MessageNumber;

// sim:every may keep this many timers: each is looked at whenever the
// integrator stops, and a script registering them in a loop must not grow
// the list without end.
constexpr std::size_t kMaxTimers = 10000;

// Lua allows a function 200 locals; the prologue's binder takes one, and the
// script needs some of its own.
constexpr std::size_t kMaxNamedIdentifiers = 150;

constexpr const char* kBinderKey = "mechflow.control_script_binder";

}  // namespace

bool RunControlScript(LuaState& lua, const IdentifierTable& identifiers, const std::string& code,
                      const std::string& chunk_name, std::string* error) {
  const std::string script = chunk_name.substr(chunk_name[0] == '@' || chunk_name[0] == '=' ? 1 : 0);
  if (std::string problem = CompileCostProblem(code); !problem.empty()) {
    *error = script + ": " + problem;
    return false;
  }
  const IdentifierChunk chunk = IdentifiersAsUpvalues(code, identifiers);
  if (chunk.identifiers.size() > kMaxNamedIdentifiers) {
    *error = script + ": the script names " + std::to_string(chunk.identifiers.size()) +
             " identifiers; it may read at most " + std::to_string(kMaxNamedIdentifiers) +
             " by name: read the others with sim:get('name')";
    return false;
  }
  lua_State* L = lua.get();
  const int top = lua_gettop(L);
  if (!lua_checkstack(L, static_cast<int>(chunk.identifiers.size()) + 4)) {
    *error = script + ": too many identifiers";
    return false;
  }
  const int status = luaL_loadbufferx(L, chunk.code.data(), chunk.code.size(), chunk_name.c_str(), "t");
  if (status != LUA_OK) {
    *error = lua.ErrorText(status);
    lua_settop(L, top);
    // an assignment to an identifier: say what does change one
    const std::string marker = "attempt to assign to const variable '";
    if (const std::size_t at = error->find(marker); at != std::string::npos) {
      const std::size_t start = at + marker.size(), end = error->find('\'', start);
      const std::string name = error->substr(start, end - start);
      if (const int id = identifiers.FindLowerCase(name); id >= 0)
        *error += " ('" + identifiers.spelling(id) + "' is an identifier, which the script reads but cannot assign: " +
                  "change it with sim:set('" + identifiers.spelling(id) + "', value), or declare a local of " +
                  "another name)";
    }
    return false;
  }
  lua_newtable(L);  // the box the prologue puts the binder in
  lua_insert(L, top + 1);
  lua_pushvalue(L, top + 1);
  for (const std::string& name : chunk.identifiers) lua_pushnumber(L, identifiers.Value(name));
  if (!lua.Call(1 + static_cast<int>(chunk.identifiers.size()), 0, error)) {
    lua_settop(L, top);
    return false;
  }
  if (lua_rawgeti(L, top + 1, 1) == LUA_TFUNCTION) {
    BindIdentifiers(L, -1);
    lua_setfield(L, LUA_REGISTRYINDEX, kBinderKey);  // kept alive: the bindings hold it weakly
  }
  lua_settop(L, top);
  return true;
}

ControlScript::ControlScript(LuaState& lua, IdentifierTable& identifiers, const blocks::Diagram& diagram,
                             std::string script_name)
    : lua_(lua), identifiers_(identifiers), diagram_(diagram), name_(std::move(script_name)) {
  lua_State* L = lua_.get();
  int* refs[] = {&init_ref_, &step_ref_, &finish_ref_};
  const char* names[] = {"init", "step", "finish"};
  for (int i = 0; i < 3; ++i) {
    const int type = lua_getglobal(L, names[i]);
    if (type == LUA_TNIL) {
      lua_pop(L, 1);
      continue;
    }
    if (type != LUA_TFUNCTION) {
      lua_pop(L, 1);
      throw InputError(name_ + ": '" + names[i] + "' is a " + lua_typename(L, type) + "; define it as function " +
                       names[i] + "(sim) ... end");
    }
    *refs[i] = luaL_ref(L, LUA_REGISTRYINDEX);
  }

  // sim: a table with the methods, each a closure over this object
  lua_createtable(L, 0, 6);
  const luaL_Reg methods[] = {{"every", &ControlScript::Every}, {"get", &ControlScript::Get},
                              {"set", &ControlScript::Set},     {"stop", &ControlScript::StopRun},
                              {"log", &ControlScript::Log},     {nullptr, nullptr}};
  lua_pushlightuserdata(L, this);
  luaL_setfuncs(L, methods, 1);
  lua_pushnumber(L, 0.0);
  lua_setfield(L, -2, "t");  // the slot exists from now on: setting it later allocates nothing
  sim_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);

  for (int b = 0; b < diagram_.num_blocks(); ++b)
    if (const auto* block = dynamic_cast<const IdentifierBlock*>(&diagram_.block(b)))
      identifier_blocks_.emplace_back(block->identifier(), diagram_.layout(b).first_discrete);
  loaded_values_ = identifiers_.Values();
  before_.reserve(loaded_values_.size());
  // derived identifiers compiled once: sim:set parses nothing
  for (int i = 0; i < identifiers_.size(); ++i)
    if (identifiers_.is_expression(i))
      derived_.emplace_back(i, std::make_unique<CompiledExpression>(
                                   lua_, identifiers_.definition(i), std::vector<std::string>{}, identifiers_,
                                   "=identifier '" + identifiers_.name(i) + "' (" + identifiers_.origin(i) + ")"));
}

ControlScript::~ControlScript() {
  lua_State* L = lua_.get();
  for (int ref : {init_ref_, step_ref_, finish_ref_, sim_ref_}) luaL_unref(L, LUA_REGISTRYINDEX, ref);
  for (const Sampled& timer : timers_) luaL_unref(L, LUA_REGISTRYINDEX, timer.function_ref);
}

std::vector<std::string> ControlScript::functions() const {
  std::vector<std::string> names;
  if (init_ref_ >= 0) names.push_back("init");
  if (step_ref_ >= 0) names.push_back("step");
  if (finish_ref_ >= 0) names.push_back("finish");
  return names;
}

// --- the run -------------------------------------------------------------

void ControlScript::Start(blocks::ControlPoint& point) {
  // a new run starts from the model as loaded, not as the last run left it
  lua_State* L = lua_.get();
  for (const Sampled& timer : timers_) luaL_unref(L, LUA_REGISTRYINDEX, timer.function_ref);
  timers_.clear();
  if (!changes_.empty()) {
    identifiers_.SetValues(loaded_values_);
    RebindIdentifiers(L, identifiers_, identifiers_.Names());
    changes_.clear();
  }
  callbacks_ = 0;
  Call(init_ref_, "init", point);
}

void ControlScript::Output(blocks::ControlPoint& point) { Call(step_ref_, "step", point); }

void ControlScript::Finish(blocks::ControlPoint& point) { Call(finish_ref_, "finish", point); }

double ControlScript::NextTimer() const {
  double next = std::numeric_limits<double>::infinity();
  for (const Sampled& timer : timers_) next = std::min(next, timer.when());
  return next;
}

void ControlScript::Timer(blocks::ControlPoint& point) {
  const double t = point.time();
  // by index: a callback may register more timers; one due at once runs now
  for (std::size_t i = 0; i < timers_.size(); ++i) {
    if (!blocks::SameInstant(timers_[i].when(), t)) continue;
    ++timers_[i].next;
    Call(timers_[i].function_ref, "the function given to sim:every", point);
  }
}

void ControlScript::Call(int ref, const char* what, blocks::ControlPoint& point) {
  if (ref < 0) return;
  lua_State* L = lua_.get();
  lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
  lua_rawgeti(L, LUA_REGISTRYINDEX, sim_ref_);
  lua_pushnumber(L, point.time());
  lua_setfield(L, -2, "t");
  point_ = &point;
  ++callbacks_;
  std::string error;
  const bool ok = lua_.Call(1, 0, &error);
  point_ = nullptr;
  if (!ok)
    throw SimulationError("control script " + name_ + ": " + what + "(sim) at t = " + MessageNumber(point.time()) +
                          " s failed: " + error);
}

// --- sim's methods -------------------------------------------------------

ControlScript& ControlScript::Self(lua_State* L) {
  return *static_cast<ControlScript*>(lua_touserdata(L, lua_upvalueindex(1)));
}

int ControlScript::RaiseError(lua_State* L) {
  luaL_where(L, 1);
  lua_pushstring(L, Self(L).error_.c_str());
  lua_concat(L, 2);
  return lua_error(L);
}

int ControlScript::Every(lua_State* L) {
  ControlScript& self = Self(L);
  const double period = luaL_checknumber(L, 2);
  luaL_checktype(L, 3, LUA_TFUNCTION);
  const double offset = luaL_optnumber(L, 4, 0.0);
  if (!(period > 0.0) || !std::isfinite(period)) return luaL_error(L, "sim:every: the period must be > 0 (s)");
  if (!(offset >= 0.0) || !std::isfinite(offset)) return luaL_error(L, "sim:every: the offset must be >= 0 (s)");
  if (!self.point_) return luaL_error(L, "sim:every: only inside init, step, finish or a sampled callback");
  char problem[256];
  {  // the string is gone before Lua may long-jump
    const std::string text = blocks::SamplePeriodProblem(period, self.point_->time(), self.point_->end_time());
    std::snprintf(problem, sizeof problem, "%s", text.c_str());
  }
  if (problem[0]) return luaL_error(L, "sim:every: %s", problem);
  if (self.timers_.size() >= kMaxTimers)
    return luaL_error(L, "sim:every: a script may have at most %d timers", static_cast<int>(kMaxTimers));
  lua_pushvalue(L, 3);
  const int ref = luaL_ref(L, LUA_REGISTRYINDEX);
  Sampled timer;
  timer.start = self.point_->time() + offset;
  timer.period = period;
  timer.function_ref = ref;
  self.timers_.push_back(timer);  // a trivially destructible value: safe before a Lua error
  return 0;
}

int ControlScript::Get(lua_State* L) {
  const char* name = luaL_checkstring(L, 2);
  const lua_Integer element = luaL_optinteger(L, 3, 0);
  double value = 0.0;
  if (!Self(L).DoGet(name, element, &value)) return RaiseError(L);
  lua_pushnumber(L, value);
  return 1;
}

int ControlScript::Set(lua_State* L) {
  const char* name = luaL_checkstring(L, 2);
  const double value = luaL_checknumber(L, 3);
  if (!Self(L).DoSet(name, value)) return RaiseError(L);
  return 0;
}

int ControlScript::StopRun(lua_State* L) {
  ControlScript& self = Self(L);
  const char* reason = luaL_optstring(L, 2, "stopped by the control script");
  if (self.point_) self.point_->Stop(reason);
  return 0;
}

int ControlScript::Log(lua_State* L) {
  const ControlScript& self = Self(L);
  const int n = lua_gettop(L);
  luaL_Buffer buffer;
  luaL_buffinit(L, &buffer);
  lua_pushfstring(L, "t = %f: ", self.point_ ? self.point_->time() : 0.0);
  luaL_addvalue(&buffer);
  for (int i = 2; i <= n; ++i) {
    if (i > 2) luaL_addchar(&buffer, '\t');
    luaL_tolstring(L, i, nullptr);
    luaL_addvalue(&buffer);
  }
  luaL_addchar(&buffer, '\n');
  luaL_pushresult(&buffer);
  std::fputs(lua_tostring(L, -1), stderr);
  return 0;
}

// --- the work behind get and set -------------------------------------------

bool ControlScript::Resolve(const std::string& name, Target* target) {
  if (const auto found = targets_.find(name); found != targets_.end()) {
    *target = found->second;
    return true;
  }
  Target t;
  // an output port name that one block alone has (a sensor name); its owners
  std::vector<std::string> owners, all;
  const auto find_owner = [&] {
    for (int b = 0; b < diagram_.num_blocks(); ++b)
      for (int p = 0; p < diagram_.block(b).num_outputs(); ++p) {
        const std::string full = diagram_.block(b).name() + "." + diagram_.block(b).output_port(p).name;
        all.push_back(full);
        if (diagram_.block(b).output_port(p).name != name) continue;
        owners.push_back(full);
        t.index = diagram_.layout(b).output_offset[p];
        t.width = diagram_.layout(b).output_width[p];
      }
    return owners.size() == 1;
  };
  // an identifier first: its name may be a path with dots (d[1].mu)
  if (const int id = identifiers_.Find(name); id >= 0) {
    t.is_identifier = true;
    t.index = id;
    // an <input> of a mechanism: what the mechanism receives is the signal
    // that feeds it, not the identifier's value -- unless that signal is an
    // identifier block's, which reads the identifier (set it, and it follows)
    for (const blocks::Connection& c : diagram_.connections()) {
      const blocks::Block& to = diagram_.block(c.to_block);
      const blocks::Block& from = diagram_.block(c.from_block);
      if (to.type() != "mechanism" || from.type() == "identifier" ||
          scripting::ToLower(to.input_port(c.to_port).name) != scripting::ToLower(identifiers_.name(id)))
        continue;
      t.is_identifier = false;
      t.index = diagram_.layout(c.from_block).output_offset[c.from_port];
      t.width = 1;
      t.fed_by = to.name() + "." + to.input_port(c.to_port).name + " <- " + from.name() + "." +
                 from.output_port(c.from_port).name;
    }
  } else if (name.find('.') != std::string::npos) {
    try {
      const blocks::SignalRef ref = diagram_.ResolveSignal(name);
      t.index = ref.offset;
      t.width = ref.width;
    } catch (const InputError& e) {
      // a sensor of a part is named with dots (s[2].x): the one block with
      // that output is meant, as for other sensor names
      if (!find_owner()) {
        error_ = std::string("sim:get: ") + e.what();
        return false;
      }
    }
  } else if (!find_owner()) {
    error_ = "sim:get: '" + name + "' " +
             (owners.empty() ? "is no identifier and no block's output" + blocks::DidYouMean(name, all) +
                                   "; signals are written block.port"
                             : "is an output of several blocks (" + blocks::JoinNames(owners) +
                                   "); write block.port");
    return false;
  }
  targets_.emplace(name, t);
  *target = t;
  return true;
}

bool ControlScript::DoGet(const char* name, long long element, double* value) {
  Target target;
  if (!Resolve(name, &target)) return false;
  if (target.is_identifier) {
    *value = identifiers_.value(target.index);
    return true;
  }
  if (target.width > 1 && (element < 1 || element > target.width)) {
    error_ = "sim:get: '" + std::string(name) + "' has " + std::to_string(target.width) +
             " elements; ask for one: sim:get('" + name + "', i) with 1 <= i <= " + std::to_string(target.width);
    return false;
  }
  if (target.width == 1 && element > 1) {
    error_ = "sim:get: '" + std::string(name) + "' is a scalar; it has no element " + std::to_string(element);
    return false;
  }
  *value = point_->signals()[target.index + (target.width > 1 ? element - 1 : 0)];
  return true;
}

bool ControlScript::DoSet(const char* name, double value) {
  if (!point_) {
    error_ = "sim:set: only inside init, step, finish or a sampled callback";
    return false;
  }
  const int id = identifiers_.Find(name);
  if (Target target; id >= 0 && Resolve(name, &target) && !target.fed_by.empty()) {
    error_ = "sim:set: '" + std::string(name) + "' is a mechanism input fed by a signal (" + target.fed_by +
             "), which decides its value; set what that signal is made from instead";
    return false;
  }
  lua_State* L = lua_.get();
  before_ = identifiers_.Values();
  changed_.clear();
  // restores the values before this set, and every function bound to them
  auto refuse = [&](std::string message) {
    identifiers_.SetValues(before_);
    RebindIdentifiers(L, identifiers_, changed_);
    error_ = "sim:set: " + std::move(message);
    return false;
  };
  try {
    identifiers_.Override(name, value);  // checks: known, defined by a number, finite
  } catch (const InputError& e) {
    return refuse(e.what());
  }
  if (identifiers_.value(id) != before_[id]) changed_.push_back(identifiers_.name(id));
  RebindIdentifiers(L, identifiers_, changed_);
  // derived identifiers, top to bottom, from their compiled definitions: each
  // sees the new values of those above it
  for (const auto& [index, definition] : derived_) {
    double v = 0.0;
    try {
      v = definition->Evaluate(nullptr);
    } catch (const SimulationError& e) {
      return refuse(e.what());
    }
    if (v == identifiers_.value(index)) continue;
    identifiers_.SetValue(index, v);
    changed_.push_back(identifiers_.name(index));
    RebindIdentifiers(L, identifiers_, {identifiers_.name(index)});
  }
  // every change must be able to reach the model
  for (const std::string& changed : changed_) {
    const int i = identifiers_.Find(changed);
    const auto& uses = identifiers_.fixed_uses(i);
    if (uses.empty()) continue;
    return refuse("identifier '" + WithInstancePaths(changed) + "'" +
                  (i == id ? "" : " (defined from '" + WithInstancePaths(identifiers_.name(id)) + "')") +
                  " cannot change during a run: its value was built into " + uses.front() +
                  (uses.size() > 1 ? " and " + std::to_string(uses.size() - 1) + " more place(s)" : "") +
                  " when the diagram was loaded. Identifiers read by expressions, Lua blocks and identifier blocks "
                  "can change; a fixed parameter is changed with --set or a variant");
  }
  const std::span<double> discrete = point_->discrete();
  for (const auto& [identifier, offset] : identifier_blocks_) discrete[offset] = identifiers_.value(identifier);
  changes_.push_back({point_->time(), id, value});
  try {
    point_->Changed();  // evaluates the outputs: no C++ exception may cross Lua's frames
  } catch (const std::exception& e) {
    error_ = "sim:set: the model fails with " + WithInstancePaths(identifiers_.name(id)) + " = " +
             MessageNumber(value) + ": " + e.what();
    return false;
  }
  return true;
}

}  // namespace mechflow::scripting
