#include "diagrams/instances.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>

#include "blocks/framework/block_factory.h"
#include "blocks/support/message_number.h"
#include "blocks/support/suggest.h"
#include "diagrams/evaluator.h"
#include "diagrams/instance_scope.h"
#include "diagrams/loader.h"
#include "mech/errors.h"

namespace mechflow::diagrams {
namespace {

using blocks::MessageNumber;

constexpr int kMaxCount = 100000;

// Attributes of mechanism elements that are words or names, never
// expressions: not rewritten.
const std::set<std::string> kWordAttributes = {"name",   "type",          "kind",          "component", "quantity",
                                               "axes",   "interpolation", "extrapolation", "stick",     "color",
                                               "comment", "part",         "src",           "signal",    "attach",
                                               "first",  "count"};
// Attributes naming a body, and those naming a joint, coordinate or element.
const std::set<std::string> kBodyReferences = {"body", "body1", "body2"};
const std::set<std::string> kOtherReferences = {"joint", "dof", "element"};
// Attributes that are coordinates "x y z" or the name of a point of the body.
const std::set<std::string> kPointAttributes = {"point", "point1", "point2", "centre"};

// Block parameters of kind text or file are words (port names, "cubic", "road.csv"), not expressions, except
// these, which are Lua or name an identifier.
const std::set<std::string> kTextExpressions = {"expr", "identifier"};

// Whether parameter `name` of a block of type `type` is written as an expression (unknown ones are: the
// loader refuses them after flattening).
bool IsExpressionParameter(const std::string& type, const std::string& name) {
  static const blocks::BlockRegistry registry = [] {
    blocks::BlockRegistry r;
    RegisterAllBlocks(&r, nullptr, nullptr);  // for the parameters' kinds only: no block is made
    return r;
  }();
  const blocks::BlockType* t = registry.Find(type);
  const blocks::ParamSpec* spec = t ? t->FindParam(name) : nullptr;
  if (!spec || kTextExpressions.count(name)) return true;
  return spec->kind != blocks::ParamKind::kText && spec->kind != blocks::ParamKind::kPath;
}

// "d[1].inner" -> "d[1]"; "d[1]" -> "" (the diagram)
std::string ParentPath(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(0, dot);
}

void SetContext(SourceLoc* loc, const std::string& context) {
  if (!context.empty()) loc->context = context;
}
void SetContext(std::vector<Attribute>* attributes, const std::string& context) {
  for (Attribute& a : *attributes) SetContext(&a.loc, context);
}
// An element and all its children, as written in an instance's file.
void SetContext(ElementDesc* e, const std::string& context) {
  SetContext(&e->loc, context);
  SetContext(&e->attributes, context);
  for (ElementDesc& child : e->children) SetContext(&child, context);
}

// How a part instance's elements are named in its mechanism: "s[1]." before
// its own names, attach points replaced by bodies of the including scope.
struct PartNaming {
  std::string prefix;                         // "" in the mechanism itself
  std::map<std::string, std::string> attach;  // attach point -> body
  std::string Body(const std::string& name) const {
    if (prefix.empty() || name == "Base0") return name;
    const auto it = attach.find(name);
    return it != attach.end() ? it->second : prefix + name;
  }
  std::string Other(const std::string& name) const { return prefix + name; }
};

class Flattener {
 public:
  Flattener(DiagramDescription* d, const InstanceIdentifiers& ids) : d_(*d), ids_(ids) {}

  void Run() {
    InstanceScope top;
    Content(top, nullptr, d_.mechanisms, d_.blocks, d_.connections);
    d_.mechanisms = std::move(mechanisms_);
    d_.blocks = std::move(blocks_);
    d_.connections = ResolveConnections();
    for (const LogDesc& log : d_.logs) RequireIndex(log.signal, log.loc);
  }

 private:
  // --- subsystems -----------------------------------------------------------

  // The mechanisms, blocks and connections of the diagram (`component`
  // null) or of a subsystem instance, appended flat.
  void Content(InstanceScope& scope, const ComponentDesc* component, const std::vector<ElementDesc>& mechanisms,
               const std::vector<BlockDesc>& blocks, const std::vector<ConnectionDesc>& connections) {
    // blocks, mechanisms and instances share one name space: "d.y" must name one thing
    std::map<std::string, SourceLoc> names;
    const auto claim = [&](const std::string& name, SourceLoc loc, const std::string& what) {
      SetContext(&loc, scope.context());
      if (const std::string problem = WrittenNameProblem(name); !problem.empty())
        throw InputError(loc.str() + ": " + what + " name '" + name + "' " + problem);
      if (component)
        for (const auto* ports : {&component->inputs, &component->outputs})
          for (const PortDesc& p : *ports)
            if (p.name == name)
              throw InputError(loc.str() + ": " + what + " '" + name + "' has the name of a port of " +
                               scope.description() + " (" + p.loc.str() + "); rename one of them");
      if (const auto [first, fresh] = names.emplace(name, loc); !fresh)
        throw InputError(loc.str() + ": " + what + " name '" + name + "' is used twice (first at " +
                         first->second.str() + ")");
    };
    for (const ElementDesc& m : mechanisms) {
      claim(m.Text("name"), m.loc, "mechanism");
      mechanisms_.push_back(Mechanism(scope, m));
    }
    for (const BlockDesc& b : blocks) {
      claim(b.name, b.loc, b.type == "subsystem" ? "subsystem" : "block");
      if (b.type == "subsystem") {
        Subsystem(scope, b);
        continue;
      }
      if (!b.args.empty())
        throw InputError(b.args.front().loc.str() + ": <param> belongs to a subsystem block; block '" + b.name +
                         "' is a " + b.type);
      BlockDesc flat = b;
      flat.name = scope.prefix() + b.name;
      if (!scope.is_diagram()) {
        SetContext(&flat.loc, scope.context());
        SetContext(&flat.text_loc, scope.context());
        SetContext(&flat.params, scope.context());
      }
      const std::string who = flat.loc.str() + ": block '" + b.name + "'";
      for (Attribute& a : flat.params)
        if (IsExpressionParameter(b.type, a.name)) a.value = scope.Rewrite(a.value, who + " parameter '" + a.name + "'");
      flat.text = scope.Rewrite(flat.text, who + " code");
      blocks_.push_back(std::move(flat));
    }
    for (const ConnectionDesc& c : connections) {
      SourceLoc loc = c.loc;
      SetContext(&loc, scope.context());
      for (const auto& [from, to] : EachElement(scope, c, loc))
        edges_.push_back({scope.prefix() + from, scope.prefix() + to, loc, scope.path()});
    }
  }

  // A connection naming every element of a subsystem array with "[*]":
  // element by element when both ends do (d[*].F to s[*].u), one source to
  // every element when only `to` does (v.y to d[*].v).
  std::vector<std::pair<std::string, std::string>> EachElement(const InstanceScope& scope, const ConnectionDesc& c,
                                                               const SourceLoc& loc) const {
    const auto star = [](const std::string& ref) { return ref.find("[*]"); };
    if (star(c.from) == std::string::npos && star(c.to) == std::string::npos) return {{c.from, c.to}};
    const std::string what = loc.str() + ": connection from '" + c.from + "' to '" + c.to + "'";
    if (star(c.to) == std::string::npos)
      throw InputError(what + ": one input cannot be fed by every element of an array; name one element ([0], [1], ...)");
    const auto count = [&](const std::string& ref) {
      const std::string array = scope.prefix() + ref.substr(0, star(ref));
      const auto it = arrays_.find(array);
      if (it == arrays_.end())
        throw InputError(what + ": '" + ref.substr(0, star(ref)) + "' is no array (count=) of this file");
      return it->second;
    };
    const int n = count(c.to);
    if (star(c.from) != std::string::npos && count(c.from) != n)
      throw InputError(what + ": the arrays have " + std::to_string(count(c.from)) + " and " + std::to_string(n) +
                       " elements; element by element needs as many on both ends");
    std::vector<std::pair<std::string, std::string>> out;
    for (int k = 0; k < n; ++k) {
      const std::string index = "[" + std::to_string(k) + "]";
      std::string from = c.from, to = c.to;
      if (star(from) != std::string::npos) from.replace(star(from), 3, index);
      to.replace(star(to), 3, index);
      out.emplace_back(from, to);
    }
    return out;
  }

  // The instance paths of an element with optional count= (in `scope`).
  std::vector<std::pair<std::string, std::optional<int>>> Paths(const InstanceScope& scope, const std::string& base,
                                                                 const Attribute* count, int* total) {
    std::vector<std::pair<std::string, std::optional<int>>> paths;
    *total = 0;
    if (!count) {
      paths.emplace_back(base, std::nullopt);
      return paths;
    }
    const std::string what = count->loc.str() + ": count";
    const double n = ids_.evaluate(scope.Rewrite(count->value, what), what);
    if (!(n >= 1 && n <= kMaxCount && n == std::floor(n)))
      throw InputError(what + " is " + count->value + " = " + MessageNumber(n) +
                       "; expected a whole number from 1 to " + std::to_string(kMaxCount));
    *total = static_cast<int>(n);
    for (int k = 0; k < *total; ++k) paths.emplace_back(base + "[" + std::to_string(k) + "]", k);
    return paths;
  }

  // An instance's scope with its parameters and identifiers declared (and
  // added to the diagram's). `args`: the <param>s where it is used.
  InstanceScope Enter(const InstanceScope& parent, const std::string& path, const ComponentDesc& c,
                      const SourceLoc& loc, std::optional<int> index, int count, const std::vector<Attribute>& args) {
    const std::optional<int> n = index ? std::optional<int>(count) : std::nullopt;
    InstanceScope scope = InstanceScope::Instance(parent, path, c, loc, index, n, ids_.table);
    d_.instances.push_back({path, c.kind, c.file, loc});
    std::vector<std::string> declared;
    for (const ParameterDesc& p : c.parameters) declared.push_back(p.name);
    for (const ParameterDesc& p : c.parameters) scope.DeclareLater(p.name, p.loc.str());
    for (const IdentifierDesc& local : c.identifiers) scope.DeclareLater(local.name, local.loc.str());
    std::set<std::string> given;
    for (const Attribute& a : args) {
      if (std::find(declared.begin(), declared.end(), a.name) == declared.end())
        throw InputError(a.loc.str() + ": " + scope.description() + " has no parameter '" + a.name + "'" +
                         blocks::DidYouMean(a.name, declared) +
                         (declared.empty() ? "; it declares none" : "; its parameters: " + blocks::JoinNames(declared)) +
                         " (" + c.loc.str() + ")");
      if (!given.insert(a.name).second)
        throw InputError(a.loc.str() + ": parameter '" + a.name + "' of " + path + " is given twice");
    }
    for (const ParameterDesc& p : c.parameters) {
      if (p.name == "index" || p.name == "count")
        throw InputError(p.loc.str() + ": parameter name '" + p.name +
                         "' is kept for arrays (count=), where it is the element's index or the count");
      const Attribute* arg = FindAttribute(args, p.name);
      IdentifierDesc id{scope.PathOf(p.name), "", p.comment, p.unit, p.loc};
      if (arg) {
        // written where the instance is used, seeing that scope (and the new instance's index)
        const InstanceScope here = index ? parent.WithIndex(index, n) : parent;
        id.value = here.Rewrite(arg->value, arg->loc.str() + ": parameter '" + p.name + "'");
        id.loc = arg->loc;
      } else if (p.has_default) {
        SetContext(&id.loc, scope.context());
        id.value = scope.Rewrite(p.default_value, id.loc.str() + ": parameter '" + p.name + "' default");
      } else {
        throw InputError(loc.str() + ": " + path + " gives no <param name=\"" + p.name + "\"> and " +
                         scope.description() + " has no default for it (" + p.loc.str() + ")");
      }
      scope.Declare(p.name);
      ids_.add(id);
    }
    for (const IdentifierDesc& local : c.identifiers) {
      IdentifierDesc id = local;
      SetContext(&id.loc, scope.context());
      id.value = scope.Rewrite(local.value, id.loc.str() + ": identifier '" + local.name + "'");
      id.name = scope.PathOf(local.name);
      scope.Declare(local.name);
      ids_.add(id);
    }
    return scope;
  }

  void Subsystem(const InstanceScope& scope, const BlockDesc& written) {
    const ComponentDesc& c = *d_.FindComponent(written.component);
    // its lines in messages carry the instance whose file holds it
    BlockDesc b = written;
    SetContext(&b.loc, scope.context());
    SetContext(&b.text_loc, scope.context());
    SetContext(&b.params, scope.context());
    SetContext(&b.args, scope.context());
    for (const Attribute& a : b.params)
      if (a.name != "src" && a.name != "count")
        throw InputError(a.loc.str() + ": subsystem '" + b.name + "' takes src=, count= and <param> children; give '" +
                         a.name + "' as <param name=\"" + a.name + "\" value=\"...\"/>");
    if (b.text.find_first_not_of(" \t\r\n") != std::string::npos)
      throw InputError(b.text_loc.str() + ": subsystem '" + b.name + "' takes no text content");
    int count = 0;
    const auto paths = Paths(scope, scope.prefix() + b.name, FindAttribute(b.params, "count"), &count);
    if (count > 0) arrays_[scope.prefix() + b.name] = count;
    for (const auto& [path, index] : paths) {
      InstanceScope inner = Enter(scope, path, c, b.loc, index, count, b.args);
      for (const PortDesc& written_port : c.inputs) {
        PortDesc p = written_port;
        SetContext(&p.loc, inner.context());
        virtual_[inner.prefix() + p.name] = {path, true, p.loc, p.name, inner.description()};
        if (!p.width.empty()) {
          double w = 0;
          if (!scripting::ParseNumber(p.width, &w) || !(w >= 1 && w == std::floor(w) && w <= 1e6))
            throw InputError(p.loc.str() + ": input '" + p.name + "' width is '" + p.width + "'; expected a whole number >= 1");
          widths_.push_back({inner.prefix() + p.name, static_cast<int>(w), p.loc});
        }
      }
      for (const PortDesc& p : c.outputs) {
        SourceLoc at = p.loc;
        SetContext(&at, inner.context());
        virtual_[inner.prefix() + p.name] = {path, false, at, p.name, inner.description()};
      }
      Content(inner, &c, c.mechanisms, c.blocks, c.connections);
    }
  }

  // --- connections through ports ---------------------------------------------

  struct Edge {
    std::string from, to;
    SourceLoc loc;
    std::string scope;  // the instance whose file holds it; "" the diagram
  };
  struct Port {
    std::string instance;
    bool input = false;
    SourceLoc loc;
    std::string name, owner;  // as declared; the instance described
  };

  // A reference to an element of an array must say which ("d.F" for d[0..2]).
  void RequireIndex(const std::string& ref, const SourceLoc& loc) const {
    for (const auto& [base, count] : arrays_)
      if (ref.rfind(base + ".", 0) == 0) {
        const std::string port = ref.substr(base.size());
        throw InputError(loc.str() + ": '" + ref + "': " + base + " is an array of " + std::to_string(count) +
                         " (count=); name one element, " + base + "[0]" + port +
                         (count > 1 ? " to " + base + "[" + std::to_string(count - 1) + "]" + port : ""));
      }
  }

  std::vector<ConnectionDesc> ResolveConnections() {
    std::map<std::string, const Edge*> source_of;  // port -> the connection feeding it
    for (const Edge& e : edges_) {
      RequireIndex(e.from, e.loc);
      RequireIndex(e.to, e.loc);
      if (const auto it = virtual_.find(e.to); it != virtual_.end()) {
        const Port& p = it->second;
        if (p.input ? ParentPath(p.instance) != e.scope : p.instance != e.scope)
          throw InputError(e.loc.str() + ": connection to '" + e.to.substr(e.scope.empty() ? 0 : e.scope.size() + 1) +
                           "': " + (p.input ? "an input of a subsystem is fed in the file that uses it"
                                            : "an output of a subsystem is fed from inside it"));
        if (const auto [first, fresh] = source_of.emplace(e.to, &e); !fresh)
          throw InputError(e.loc.str() + ": port '" + e.to + "' is fed twice (first at " + first->second->loc.str() + ")");
      }
      if (const auto it = virtual_.find(e.from);
          it != virtual_.end() && (it->second.input ? it->second.instance != e.scope : ParentPath(it->second.instance) != e.scope))
        throw InputError(e.loc.str() + ": connection from '" + e.from + "': " +
                         (it->second.input ? "an input of a subsystem is read inside it"
                                           : "an output of a subsystem is read in the file that uses it"));
    }
    // an output nothing inside feeds is a mistake in the subsystem's file, read or not
    for (const auto& [name, port] : virtual_)
      if (!port.input && !source_of.count(name))
        throw InputError(port.loc.str() + ": output '" + port.name + "' of " + port.owner +
                         ": nothing inside feeds it; connect a block's output to it (<connect from=\"BLOCK.PORT\" "
                         "to=\"" + port.name + "\"/>) or remove it");
    // a fed input that nothing inside reads: the connection would do nothing
    std::set<std::string> read;
    for (const Edge& e : edges_) read.insert(e.from);
    for (const auto& [name, port] : virtual_)
      if (port.input && source_of.count(name) && !read.count(name))
        throw InputError(source_of.at(name)->loc.str() + ": connection to '" + name + "': nothing inside " +
                         port.instance + " reads its input '" + port.name + "' (" + port.loc.str() +
                         "); connect it to a block there, or remove this connection");
    // the block output behind a port, through any number of ports
    const auto real_source = [&](std::string name, const SourceLoc& loc) {
      std::vector<std::string> passed;
      for (; virtual_.count(name);) {
        if (std::find(passed.begin(), passed.end(), name) != passed.end()) {
          std::string loop;
          for (auto it = std::find(passed.begin(), passed.end(), name); it != passed.end(); ++it) loop += *it + " <- ";
          throw InputError(loc.str() + ": ports joined in a loop with no block between (" + loop + name +
                           "); a signal needs a block's output for its source");
        }
        passed.push_back(name);
        const auto it = source_of.find(name);
        if (it == source_of.end()) {
          const Port& p = virtual_.at(name);
          throw InputError(loc.str() + ": '" + name + "' is " +
                           (p.input ? "an input of " + p.instance + " that nothing feeds; connect it where " +
                                          p.instance + " is used"
                                    : "an output of " + p.instance + " that nothing inside feeds (" + p.loc.str() + ")"));
        }
        name = it->second->from;
      }
      return name;
    };
    std::vector<ConnectionDesc> out;
    for (const Edge& e : edges_)
      if (!virtual_.count(e.to)) out.push_back({real_source(e.from, e.loc), e.to, e.loc});
    for (const auto& [name, port] : virtual_)
      if (!port.input && source_of.count(name)) d_.signal_aliases.emplace_back(name, real_source(name, port.loc));
    for (const auto& w : widths_)
      if (source_of.count(w.signal)) d_.input_widths.push_back({real_source(w.signal, w.loc), w.width, w.loc});
    return out;
  }

  // --- mechanisms and parts ---------------------------------------------------

  ElementDesc Mechanism(const InstanceScope& scope, const ElementDesc& m) {
    ElementDesc flat = m;
    flat.children.clear();
    for (Attribute& a : flat.attributes) {
      SetContext(&a.loc, scope.context());
      if (a.name == "name") a.value = scope.prefix() + a.value;
      else if (!kWordAttributes.count(a.name))
        a.value = scope.Rewrite(a.value, a.loc.str() + ": mechanism '" + m.Text("name") + "' attribute '" + a.name + "'");
    }
    SetContext(&flat.loc, scope.context());
    for (const ElementDesc& e : m.children) {
      if (e.tag != "input") continue;
      ElementDesc input = e;
      SetContext(&input.loc, scope.context());
      for (Attribute& name : input.attributes) {
        SetContext(&name.loc, scope.context());
        if (name.name != "name" || scope.is_diagram()) continue;
        if (!scope.Declares(name.value))
          throw InputError(input.loc.str() + ": input '" + name.value + "' must name a parameter or identifier of " +
                           scope.description());
        name.value = scope.PathOf(name.value);
      }
      flat.children.push_back(std::move(input));
    }
    std::vector<ElementDesc> others;
    for (const ElementDesc& e : m.children)
      if (e.tag != "input") others.push_back(e);
    attach_targets_.clear();
    Elements(scope, others, PartNaming{}, flat.Text("name"), &flat.children);
    // an attach target that is no body is the include's mistake, not the part's
    std::vector<std::string> bodies = {"Base0"};
    for (const ElementDesc& e : flat.children)
      if (e.tag == "body") bodies.push_back(e.Text("name"));
    for (const auto& [body, what] : attach_targets_)
      if (std::find(bodies.begin(), bodies.end(), body) == bodies.end())
        throw InputError(what + ": mechanism '" + flat.Text("name") + "' has no body '" + body + "'" +
                         blocks::DidYouMean(body, bodies));
    return flat;
  }

  // A mechanism's or part's elements, appended to `out` with their names
  // and references as the mechanism knows them.
  void Elements(const InstanceScope& scope, const std::vector<ElementDesc>& in, const PartNaming& naming,
                const std::string& mechanism, std::vector<ElementDesc>* out) {
    std::map<std::string, SourceLoc> includes;  // two of one name would make the same elements
    for (const ElementDesc& e : in) {
      if (e.tag == "include") {
        SourceLoc at = e.loc;
        SetContext(&at, scope.context());
        if (const auto [first, fresh] = includes.emplace(e.Text("name"), at); !fresh)
          throw InputError(at.str() + ": include name '" + e.Text("name") + "' is used twice (first at " +
                           first->second.str() + ")");
        Include(scope, e, naming, mechanism, out);
        continue;
      }
      out->push_back(Element(scope, e, naming, false));
    }
  }

  ElementDesc Element(const InstanceScope& scope, const ElementDesc& e, const PartNaming& naming, bool in_body) {
    ElementDesc flat = e;
    SetContext(&flat.loc, scope.context());
    const std::string who = e.tag + " '" + e.Text("name") + "'";
    for (Attribute& a : flat.attributes) {
      SetContext(&a.loc, scope.context());
      if (a.name == "name") {
        // a point is named within its body, which is prefixed already
        if (!(e.tag == "point" && in_body)) a.value = naming.Other(a.value);
      } else if (kBodyReferences.count(a.name)) {
        a.value = naming.Body(a.value);
      } else if (kOtherReferences.count(a.name)) {
        a.value = naming.Other(a.value);
      } else if (kPointAttributes.count(a.name) && scripting::IsLuaName(Trim(a.value)) &&
                 !scope.Declares(Trim(a.value))) {
        // a point's name: points are named within their body, whatever the diagram's identifiers are
      } else if (!kWordAttributes.count(a.name)) {
        a.value = scope.Rewrite(a.value, a.loc.str() + ": " + who + " attribute '" + a.name + "'");
      }
    }
    for (ElementDesc& child : flat.children) child = Element(scope, child, naming, e.tag == "body");
    return flat;
  }

  // <include part=... name=... [count first] attach=...>: the part's elements, once per instance.
  void Include(const InstanceScope& scope, const ElementDesc& written, const PartNaming& naming,
               const std::string& mechanism, std::vector<ElementDesc>* out) {
    const ComponentDesc& c = *d_.FindComponent(written.component);
    ElementDesc e = written;  // its lines in messages carry the instance whose file holds it
    SetContext(&e, scope.context());
    const std::string name = e.Text("name");
    if (const std::string problem = WrittenNameProblem(name); !problem.empty())
      throw InputError(e.loc.str() + ": include name '" + name + "' " + problem);
    std::vector<Attribute> args;
    for (const ElementDesc& p : e.children) args.push_back({p.Text("name"), p.Text("value"), p.loc});
    const Attribute* first = e.Find("first");
    if (first && !e.Find("count")) throw InputError(first->loc.str() + ": first= gives the attach of name[0] of an array; add count=");
    int count = 0;
    const auto paths = Paths(scope, naming.prefix + name, e.Find("count"), &count);
    if (count > 0) arrays_[mechanism + "." + naming.prefix + name] = count;
    for (const auto& [local, index] : paths) {
      const std::string path = mechanism + "." + local;
      InstanceScope inner = Enter(scope, path, c, e.loc, index, count, args);
      PartNaming inner_naming{local + ".", {}};
      const Attribute* attach = index == 0 && first ? first : e.Find("attach");
      if (attach) {
        const InstanceScope here = index ? scope.WithIndex(index, count) : scope;
        for (const std::string& item : Split(attach->value, " \t\r\n,")) {
          const auto eq = item.find('=');
          const std::string point = Trim(item.substr(0, eq));
          const std::string what = attach->loc.str() + ": " + attach->name + " '" + item + "' of " + path;
          if (eq == std::string::npos) throw InputError(what + ": expected POINT=BODY");
          if (std::none_of(c.attach_points.begin(), c.attach_points.end(), [&](const Attribute& a) { return a.name == point; })) {
            std::vector<std::string> points;
            for (const Attribute& a : c.attach_points) points.push_back(a.name);
            throw InputError(what + ": part '" + c.name + "' (" + c.file +
                             ") has no attach point '" + point + "'" + blocks::DidYouMean(point, points) +
                             (points.empty() ? "; it has none" : "; its attach points: " + blocks::JoinNames(points)));
          }
          attach_targets_.emplace_back(naming.Body(Indexed(here, Trim(item.substr(eq + 1)), what)), what);
          if (!inner_naming.attach.emplace(point, attach_targets_.back().first).second)
            throw InputError(what + ": attach point '" + point + "' is given twice");
        }
      }
      for (const Attribute& a : c.attach_points)
        if (!inner_naming.attach.count(a.name))
          throw InputError(e.loc.str() + ": " + path + " does not say which body its attach point '" + a.name +
                           "' is (" + a.loc.str() + "); add attach=\"" + a.name + "=BODY\"" +
                           (index == 0 ? " (for name[0] of an array: first=\"" + a.name + "=BODY\")" : ""));
      Elements(inner, c.elements, inner_naming, mechanism, out);
    }
  }

  // "s[index-1].Box" with each [expression] evaluated to a whole number >= 0.
  std::string Indexed(const InstanceScope& scope, const std::string& body, const std::string& what) {
    std::string out;
    for (std::size_t i = 0; i < body.size();) {
      const std::size_t open = body.find('[', i);
      if (open == std::string::npos) {
        out += body.substr(i);
        break;
      }
      const std::size_t close = body.find(']', open);
      if (close == std::string::npos) throw InputError(what + ": '[' without ']'");
      const std::string text = body.substr(open + 1, close - open - 1);
      const double k = ids_.evaluate(scope.Rewrite(text, what), what);
      if (!(k >= 0 && k < kMaxCount && k == std::floor(k)))
        throw InputError(what + ": the index [" + text + "] is " + MessageNumber(k) +
                         "; expected a whole number >= 0 (the first element of an array attaches as first= says)");
      out += body.substr(i, open - i) + "[" + std::to_string(static_cast<int>(k)) + "]";
      i = close + 1;
    }
    return out;
  }

  DiagramDescription& d_;
  const InstanceIdentifiers& ids_;
  std::vector<BlockDesc> blocks_;
  std::vector<ElementDesc> mechanisms_;
  std::vector<Edge> edges_;
  std::map<std::string, Port> virtual_;  // the ports of subsystem instances, by path
  std::map<std::string, int> arrays_;    // arrays by path without index ("d", "o[1].s", "m.w") -> count
  // the bodies attach= names in the mechanism being flattened, and where
  std::vector<std::pair<std::string, std::string>> attach_targets_;
  std::vector<DiagramDescription::InputWidth> widths_;
};

}  // namespace

std::string WrittenNameProblem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.find_first_of(".[]") != std::string::npos)
    return "may not contain '.', '[' or ']' (they join the names of instances and their parts)";
  if (name.find("__") != std::string::npos) return "may not contain \"__\"";
  return "";
}

void MakeInstances(DiagramDescription* d, const InstanceIdentifiers& identifiers) {
  Flattener(d, identifiers).Run();
}

}  // namespace mechflow::diagrams
