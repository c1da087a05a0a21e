#include "diagrams/attribute_units.h"

#include "diagrams/element_table.h"

namespace mechflow::diagrams {

// Read from the element table (diagrams/element_table.h), the one place
// attributes are declared. A type the table does not know has only the
// tag's own attributes (its reader refuses the type).
std::string AttributeUnit(const std::string& tag, const std::string& type, const std::string& attribute) {
  const ElementSpec* spec = FindElementSpec(tag);
  if (!spec) return "";
  for (const AttributeSpec& a : spec->attributes)
    if (a.name == attribute) return a.unit;
  if (const ElementVariant* variant = spec->FindVariant(type))
    for (const AttributeSpec& a : variant->attributes)
      if (a.name == attribute) return a.unit;
  return "";
}

}  // namespace mechflow::diagrams
