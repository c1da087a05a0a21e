#pragma once
// The one table of the diagram format's elements: for every tag (and every
// type= of a force, joint, contact, shape, <et>, every kind= of a sensor) the
// attributes it takes, required or with a default, their SI unit and a line
// saying what they mean. The XML reader checks attributes against it, unit
// checks read units from it (diagrams/attribute_units.h), and `mechflow help
// TYPE` prints it.

#include <string>
#include <utility>
#include <vector>

#include "diagrams/description.h"

namespace mechflow::diagrams {

struct AttributeSpec {
  std::string name;
  bool required = false;
  std::string default_text;  // as a user would write it, or a phrase ("the initial length"); "" none
  // The SI unit the identifiers it uses must have; "" unchecked (a unit that
  // depends on more than the attribute, e.g. a joint_force's c).
  std::string unit;
  std::string doc;  // one line
};

// The rows of the table, as its two halves write them.
inline AttributeSpec Req(std::string name, std::string unit, std::string doc) {
  return {std::move(name), true, "", std::move(unit), std::move(doc)};
}
inline AttributeSpec Opt(std::string name, std::string default_text, std::string unit, std::string doc) {
  return {std::move(name), false, std::move(default_text), std::move(unit), std::move(doc)};
}

// One type= (or kind=) of a tag, with the attributes only it takes.
struct ElementVariant {
  std::string name;
  std::string doc;
  std::vector<AttributeSpec> attributes = {};
  std::vector<std::string> children = {};  // child tags only this variant takes
  // Attributes of other variants this one refuses with a reason beyond "it
  // takes no such attribute": {name, why and what to do instead}.
  std::vector<std::pair<std::string, std::string>> refusals = {};
};

struct ElementSpec {
  std::string tag;
  std::string doc;
  std::vector<AttributeSpec> attributes = {};  // every variant takes these
  std::vector<std::string> children = {};      // child tags every variant takes
  std::string selector = "";                   // "type" or "kind" when it has variants
  std::vector<ElementVariant> variants = {};
  // Any further attribute is accepted here and checked later (a block's
  // parameters depend on its type: blocks/framework/block_factory.h).
  bool open_attributes = false;

  const ElementVariant* FindVariant(const std::string& name) const;
  // Every attribute some variant takes (the tag's own first).
  std::vector<const AttributeSpec*> AllAttributes() const;
  std::vector<std::string> AllChildren() const;
  std::vector<std::string> VariantNames() const;
};

// Every element of the format, diagram-level tags and mechanism elements.
const std::vector<ElementSpec>& ElementTable();
// Its two halves (diagrams/diagram_element_table.cc, mechanism_element_table.cc).
std::vector<ElementSpec> DiagramElementSpecs();
std::vector<ElementSpec> MechanismElementSpecs();
// The tag's entry, or null.
const ElementSpec* FindElementSpec(const std::string& tag);

// The attributes `tag` with `selector_value` (its type= or kind=; "" none)
// takes: the tag's own and those of that variant; all of the tag's when the
// value names no variant (the reader that knows the types then says so).
std::vector<const AttributeSpec*> AttributesOf(const std::string& tag, const std::string& selector_value);

// Throws InputError "file:line: <tag> (type linear) 'name' has no attribute
// 'mu'; did you mean ...; valid attributes: ..." for the first attribute of
// `attributes` that element does not take; `loc` is the element's.
void CheckAttributes(const std::string& tag, const std::vector<Attribute>& attributes, const SourceLoc& loc);

// The reference of one tag, its attributes with units, defaults and meaning
// (`mechflow help force`).
std::string ElementHelp(const ElementSpec& spec);

}  // namespace mechflow::diagrams
