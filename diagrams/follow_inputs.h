#pragma once
// An identifier defined by an expression of a mechanism's <input>s (F = 2*u,
// or a part's parameter given the input's value) is evaluated once, at load;
// a force written with it would stay at that value while the input changes.
// So within the mechanism such an identifier is replaced by its definition,
// written out down to the inputs, and the force follows the input as it
// would written with the input itself.

#include "diagrams/description.h"
#include "scripting/identifiers.h"

namespace mechflow::diagrams {

// `m` with every identifier that depends on one of its inputs replaced, in
// its elements' attributes, by its definition in parentheses.
ElementDesc FollowInputs(const ElementDesc& m, const scripting::IdentifierTable& identifiers);

}  // namespace mechflow::diagrams
