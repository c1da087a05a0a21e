#include "blocks/solver/sparsity.h"

#include <algorithm>
#include <numeric>

namespace mechflow::blocks {
namespace {

using IndexSet = std::vector<int>;  // sorted, unique

void Merge(const IndexSet& from, IndexSet* into) {
  IndexSet out;
  out.reserve(from.size() + into->size());
  std::set_union(into->begin(), into->end(), from.begin(), from.end(), std::back_inserter(out));
  into->swap(out);
}

IndexSet Range(int first, int count) {
  IndexSet s(count);
  std::iota(s.begin(), s.end(), first);
  return s;
}

IndexSet Shifted(const std::vector<int>& local, int first) {
  IndexSet s;
  for (const int i : local) s.push_back(first + i);
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

}  // namespace

bool SparsityPattern::Contains(int row, int column) const {
  const auto first = rows.begin() + column_start[column], last = rows.begin() + column_start[column + 1];
  return std::binary_search(first, last, row);
}

std::vector<std::pair<int, int>> DiagramRatePairs(const Diagram& d) {
  std::vector<std::pair<int, int>> pairs;
  for (int b = 0; b < d.num_blocks(); ++b) {
    const int first = d.layout(b).first_state;
    for (const auto& [position, rate] : d.block(b).rate_pairs()) pairs.emplace_back(first + position, first + rate);
  }
  return pairs;
}

namespace {

// the output port that drives each input port
struct Port {
  int block = -1, port = -1;
};

std::vector<std::vector<Port>> Drivers(const Diagram& d) {
  std::vector<std::vector<Port>> driver(d.num_blocks());
  for (int b = 0; b < d.num_blocks(); ++b) driver[b].assign(d.block(b).num_inputs(), Port{});
  for (const Connection& c : d.connections()) driver[c.to_block][c.to_port] = {c.from_block, c.from_port};
  return driver;
}

// The states each output port reads: its own, then along feedthrough to a
// fixed point (sets only grow, so comparing sizes detects change).
std::vector<std::vector<IndexSet>> OutputReads(const Diagram& d, const std::vector<std::vector<Port>>& driver) {
  std::vector<std::vector<IndexSet>> reads(d.num_blocks());
  for (int b = 0; b < d.num_blocks(); ++b) {
    const Block& block = d.block(b);
    const BlockLayout& layout = d.layout(b);
    const BlockSparsity* s = block.sparsity();
    for (int o = 0; o < block.num_outputs(); ++o)
      reads[b].push_back(s ? Shifted(s->output_states[o], layout.first_state)
                           : Range(layout.first_state, layout.num_states));
  }
  auto propagate = [&](int b, int o) {
    const Block& block = d.block(b);
    const std::size_t before = reads[b][o].size();
    for (int in = 0; in < block.num_inputs(); ++in) {
      const Port from = driver[b][in];
      if (from.block < 0 || !block.HasFeedthrough(in, o)) continue;
      Merge(reads[from.block][from.port], &reads[b][o]);
    }
    return reads[b][o].size() != before;
  };
  // sweeps until nothing grows: covers any order and feedthrough cycles
  // (algebraic loops), at a cost paid once per diagram
  for (bool changed = true; changed;) {
    changed = false;
    for (int b = 0; b < d.num_blocks(); ++b)
      for (int o = 0; o < d.block(b).num_outputs(); ++o) changed |= propagate(b, o);
  }
  return reads;
}

}  // namespace

bool InputsReadStates(const Diagram& d, int b) {
  const std::vector<std::vector<Port>> driver = Drivers(d);
  const std::vector<std::vector<IndexSet>> reads = OutputReads(d, driver);
  for (const Port& from : driver[b])
    if (from.block >= 0 && !reads[from.block][from.port].empty()) return true;
  return false;
}

SparsityPattern DiagramSparsity(const Diagram& d) {
  const std::vector<std::vector<Port>> driver = Drivers(d);
  const std::vector<std::vector<IndexSet>> reads = OutputReads(d, driver);

  // rows: what each derivative reads
  const int n = std::max(1, d.num_states());
  std::vector<IndexSet> row_columns(n);
  for (int i = 0; i < n; ++i) row_columns[i] = {i};
  for (int b = 0; b < d.num_blocks(); ++b) {
    const Block& block = d.block(b);
    const BlockLayout& layout = d.layout(b);
    const BlockSparsity* s = block.sparsity();
    for (int i = 0; i < layout.num_states; ++i) {
      IndexSet& row = row_columns[layout.first_state + i];
      Merge(s ? Shifted(s->derivative_states[i], layout.first_state) : Range(layout.first_state, layout.num_states),
            &row);
      for (int in = 0; in < block.num_inputs(); ++in) {
        const bool reads_input = !s || std::binary_search(s->derivative_inputs[i].begin(),
                                                          s->derivative_inputs[i].end(), in);
        const Port from = driver[b][in];
        if (reads_input && from.block >= 0) Merge(reads[from.block][from.port], &row);
      }
    }
  }

  // transpose to compressed columns
  SparsityPattern p;
  p.n = n;
  p.column_start.assign(n + 1, 0);
  for (const IndexSet& row : row_columns)
    for (const int j : row) ++p.column_start[j + 1];
  for (int j = 0; j < n; ++j) p.column_start[j + 1] += p.column_start[j];
  p.rows.resize(p.column_start[n]);
  std::vector<int> next(p.column_start.begin(), p.column_start.end() - 1);
  for (int i = 0; i < n; ++i)  // rows in increasing order, so each column's rows come out sorted
    for (const int j : row_columns[i]) p.rows[next[j]++] = i;
  return p;
}

std::vector<int> ColourColumns(const SparsityPattern& p, int* num_colours) {
  // the columns of each row
  std::vector<int> row_start(p.n + 1, 0), columns(p.nonzeros());
  for (const int i : p.rows) ++row_start[i + 1];
  for (int i = 0; i < p.n; ++i) row_start[i + 1] += row_start[i];
  std::vector<int> next(row_start.begin(), row_start.end() - 1);
  for (int j = 0; j < p.n; ++j)
    for (int k = p.column_start[j]; k < p.column_start[j + 1]; ++k) columns[next[p.rows[k]]++] = j;

  std::vector<int> colour(p.n, -1);
  std::vector<int> taken_by(p.n + 1, -1);  // taken_by[c] == j: colour c is used by a neighbour of j
  int count = 0;
  for (int j = 0; j < p.n; ++j) {
    for (int k = p.column_start[j]; k < p.column_start[j + 1]; ++k) {
      const int i = p.rows[k];
      for (int m = row_start[i]; m < row_start[i + 1]; ++m)
        if (colour[columns[m]] >= 0) taken_by[colour[columns[m]]] = j;
    }
    int c = 0;
    while (taken_by[c] == j) ++c;
    colour[j] = c;
    count = std::max(count, c + 1);
  }
  *num_colours = count;
  return colour;
}

}  // namespace mechflow::blocks
