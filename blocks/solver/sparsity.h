#pragma once
// The structural pattern of df/dx for a whole diagram: which continuous
// states each state derivative may read, directly or through signals.
//
// Built once from the blocks' declared sparsity (blocks/framework/block.h; dense when a
// block declares none) and the connections: an output port reads the states
// its block declares for it plus, through every input it feeds through from,
// whatever the driving output reads (feedthrough chains, evaluated to a fixed
// point, so cycles are covered too). A derivative reads its block's declared
// states plus whatever the signals on its declared inputs read. The diagonal
// is always in the pattern (Newton's matrix I - gamma J needs it).
//
// Conservative by construction: an entry the blocks declare may be
// numerically zero, but nothing a block reads is left out.

#include <vector>

#include "blocks/framework/diagram.h"

namespace mechflow::blocks {

// Compressed sparse columns: the rows of column j are
// rows[column_start[j] .. column_start[j + 1]), increasing.
struct SparsityPattern {
  int n = 0;
  std::vector<int> column_start;  // n + 1
  std::vector<int> rows;          // nonzeros
  int nonzeros() const { return static_cast<int>(rows.size()); }
  bool Contains(int row, int column) const;
};

// Pattern of the diagram's continuous states (n = max(1, num_states): a
// stateless diagram has the simulator's one placeholder state).
SparsityPattern DiagramSparsity(const Diagram& diagram);

// True when some input of block b reads a continuous state, directly or
// through signals (structurally, as DiagramSparsity).
bool InputsReadStates(const Diagram& diagram, int b);

// The rate pairs of every block (Block::rate_pairs), as indices into the
// diagram's continuous states: x_position' = x_rate exactly.
std::vector<std::pair<int, int>> DiagramRatePairs(const Diagram& diagram);

// Greedy column colouring (Curtis, Powell and Reid): columns that share no
// row get the same colour, so one difference quotient fills all of them.
// Columns are taken in order, each getting the smallest colour none of its
// row-neighbours has. Returns the colour of each column; colours are 0..k-1.
std::vector<int> ColourColumns(const SparsityPattern& pattern, int* num_colours);

}  // namespace mechflow::blocks
