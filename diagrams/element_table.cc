#include "diagrams/element_table.h"

#include <algorithm>
#include <stdexcept>

#include "blocks/support/excerpt.h"
#include "blocks/support/suggest.h"
#include "mech/errors.h"

namespace mechflow::diagrams {
namespace {

bool Contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<std::string> Names(const std::vector<AttributeSpec>& attributes) {
  std::vector<std::string> names;
  for (const AttributeSpec& a : attributes) names.push_back(a.name);
  return names;
}

// "a linear force", "an elastic_friction force", "a box" (a shape's type is its noun).
std::string Kind(const ElementSpec& spec, const ElementVariant& variant) {
  const std::string noun = spec.tag == "shape" ? "" : spec.tag == "et" ? " transformation" : " " + spec.tag;
  const bool vowel = std::string("aeiou").find(variant.name[0]) != std::string::npos;
  return (vowel ? "an " : "a ") + variant.name + noun;
}

// The variants that take `attribute`, as `type="a"` or `type="a", "b"`.
std::string TakenBy(const ElementSpec& spec, const std::string& attribute) {
  std::string out;
  int count = 0;
  for (const ElementVariant& v : spec.variants)
    if (Contains(Names(v.attributes), attribute)) out += std::string(count++ ? ", " : "") + "\"" + v.name + "\"";
  return count == 0 ? "" : spec.selector + "=" + out + (count == 1 ? " takes it" : " take it");
}

std::string AttributeLine(const AttributeSpec& a) {
  std::string line = "  " + a.name;
  line.resize(std::max<std::size_t>(line.size() + 1, 22), ' ');
  std::string detail = a.required ? "required" : a.default_text.empty() ? "optional" : "default " + a.default_text;
  if (!a.unit.empty()) detail += ", [" + a.unit + "]";
  return line + "(" + detail + ") " + a.doc + "\n";
}

}  // namespace

const ElementVariant* ElementSpec::FindVariant(const std::string& name) const {
  for (const ElementVariant& v : variants)
    if (v.name == name) return &v;
  return nullptr;
}

std::vector<const AttributeSpec*> ElementSpec::AllAttributes() const {
  std::vector<const AttributeSpec*> out;
  std::vector<std::string> seen;
  auto add = [&](const std::vector<AttributeSpec>& list) {
    for (const AttributeSpec& a : list)
      if (!Contains(seen, a.name)) {
        seen.push_back(a.name);
        out.push_back(&a);
      }
  };
  add(attributes);
  for (const ElementVariant& v : variants) add(v.attributes);
  return out;
}

std::vector<std::string> ElementSpec::AllChildren() const {
  std::vector<std::string> out = children;
  for (const ElementVariant& v : variants)
    for (const std::string& c : v.children)
      if (!Contains(out, c)) out.push_back(c);
  return out;
}

std::vector<std::string> ElementSpec::VariantNames() const {
  std::vector<std::string> out;
  for (const ElementVariant& v : variants) out.push_back(v.name);
  return out;
}

const std::vector<ElementSpec>& ElementTable() {
  static const std::vector<ElementSpec> table = [] {
    std::vector<ElementSpec> all = DiagramElementSpecs();
    for (ElementSpec& spec : MechanismElementSpecs()) all.push_back(std::move(spec));
    return all;
  }();
  return table;
}

const ElementSpec* FindElementSpec(const std::string& tag) {
  for (const ElementSpec& spec : ElementTable())
    if (spec.tag == tag) return &spec;
  return nullptr;
}

std::vector<const AttributeSpec*> AttributesOf(const std::string& tag, const std::string& selector_value) {
  const ElementSpec* spec = FindElementSpec(tag);
  if (!spec) return {};
  const ElementVariant* variant = spec->FindVariant(selector_value);
  if (!variant) return spec->AllAttributes();
  std::vector<const AttributeSpec*> out;
  for (const AttributeSpec& a : spec->attributes) out.push_back(&a);
  for (const AttributeSpec& a : variant->attributes) out.push_back(&a);
  return out;
}

void CheckAttributes(const std::string& tag, const std::vector<Attribute>& attributes, const SourceLoc& loc) {
  const ElementSpec* spec = FindElementSpec(tag);
  if (!spec) throw std::logic_error("no table entry for element " + tag);
  auto value_of = [&](const std::string& name) -> const Attribute* {
    for (const Attribute& a : attributes)
      if (a.name == name) return &a;
    return nullptr;
  };
  const Attribute* selector = spec->selector.empty() ? nullptr : value_of(spec->selector);
  // An unknown type is for the element's reader to name, with the valid ones.
  const ElementVariant* variant = selector ? spec->FindVariant(selector->value) : nullptr;
  std::vector<std::string> valid;
  for (const AttributeSpec* a : AttributesOf(tag, variant ? variant->name : "")) valid.push_back(a->name);
  const Attribute* name = value_of("name");
  const std::string who = tag + (name ? " '" + name->value + "'" : "");
  for (const Attribute& a : attributes) {
    if (spec->open_attributes || Contains(valid, a.name)) continue;
    if (!variant)
      throw InputError(loc.str() + ": <" + tag + "> has no attribute '" + blocks::Excerpt(a.name) + "'" +
                       blocks::DidYouMean(a.name, valid) +
                       (valid.empty() ? "; it takes no attributes" : "; valid attributes: " + blocks::JoinNames(valid)));
    std::string message = a.loc.str() + ": " + who + " attribute '" + blocks::Excerpt(a.name) + "': " +
                          Kind(*spec, *variant) + " has no '" + blocks::Excerpt(a.name) + "'";
    const std::string taken = TakenBy(*spec, a.name);
    message += taken.empty() ? blocks::DidYouMean(a.name, valid) : " (only " + taken + ")";
    for (const auto& [refused, why] : variant->refusals)
      if (refused == a.name) message += "; " + why;
    const std::vector<std::string> own = Names(variant->attributes);
    message += "; it takes " + (own.empty() ? "only " : blocks::JoinNames(own) + " and ") +
               blocks::JoinNames(Names(spec->attributes));
    throw InputError(message);
  }
  for (const AttributeSpec& r : spec->attributes)
    if (r.required && !value_of(r.name)) throw InputError(loc.str() + ": <" + tag + "> needs the attribute '" + r.name + "'");
  if (variant)
    for (const AttributeSpec& r : variant->attributes)
      if (r.required && !value_of(r.name))
        throw InputError(loc.str() + ": " + who + ": " + Kind(*spec, *variant) + " needs the attribute '" + r.name +
                         "' (" + r.doc + ")");
}

std::string ElementHelp(const ElementSpec& spec) {
  std::string out = "<" + spec.tag + ">: " + spec.doc + "\n";
  if (spec.open_attributes) out += "(its type's parameters besides these: mechflow help TYPE)\n";
  if (!spec.attributes.empty()) out += "\nattributes:\n";
  for (const AttributeSpec& a : spec.attributes) out += AttributeLine(a);
  for (const ElementVariant& v : spec.variants) {
    out += "\n" + spec.selector + "=\"" + v.name + "\": " + v.doc + "\n";
    for (const AttributeSpec& a : v.attributes) out += AttributeLine(a);
    if (!v.children.empty()) out += "  children: <" + blocks::JoinNames(v.children) + ">\n";
  }
  if (!spec.children.empty()) {
    out += "\nchildren:";
    for (const std::string& c : spec.children) out += " <" + c + ">";
    out += "\n";
  }
  return out;
}

}  // namespace mechflow::diagrams
