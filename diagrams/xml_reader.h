#pragma once
// Reads a diagram XML file into a DiagramDescription.
//
// Shape first, values later (as MuJoCo's schema check): every element and
// attribute is checked against the element table (diagrams/element_table.h) before any value
// is kept; an unknown name is an error with the nearest valid name suggested.
// Block parameters are kept as text here: which ones a block accepts depends
// on its type, which the loader checks against the block registry.
// Errors are InputError "file:line: what was found, what was expected".

#include <string>
#include <vector>

#include "diagrams/description.h"

namespace mechflow::diagrams {

// `allow_read`: folders whose trees the files the diagram names (<mechanism
// src>, <script src>) may lie in besides the diagram's own folder tree
// (--allow-read; blocks/support/input_file.h).
// `library` (--library DIR): folders the subsystem and part files it names
// are looked up in when they are not found beside the naming file (they may
// be read from, too). Every such file is read once, into `components`.
DiagramDescription ReadDiagramFile(const std::string& path, const std::vector<std::string>& allow_read = {},
                                   const std::vector<std::string>& library = {});

// Same, from text in memory; `file` is the name used in messages.
DiagramDescription ReadDiagramText(const std::string& text, const std::string& file,
                                   const std::vector<std::string>& allow_read = {},
                                   const std::vector<std::string>& library = {});

}  // namespace mechflow::diagrams
