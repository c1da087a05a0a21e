#include "blocks/framework/diagram_builder.h"

#include <algorithm>
#include <map>

#include "blocks/support/suggest.h"
#include "mech/errors.h"

namespace mechflow::blocks {
namespace {

std::string Where(const std::string& origin) { return origin.empty() ? "" : origin + ": "; }

std::string PortName(const Block& b, const PortSpec& p) { return b.name() + "." + p.name; }

std::vector<std::string> PortNames(const Block& b, bool outputs) {
  std::vector<std::string> names;
  const int n = outputs ? b.num_outputs() : b.num_inputs();
  for (int i = 0; i < n; ++i) names.push_back((outputs ? b.output_port(i) : b.input_port(i)).name);
  return names;
}

// What makes `name` unfit for a block, or "": a block is named by instance
// path parts joined by '.', none empty, so that "name.port" splits back into
// the block and its port.
std::string BlockNameProblem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.front() == '.' || name.back() == '.' || name.find("..") != std::string::npos)
    return "has an empty part between dots";
  return "";
}

}  // namespace

int Diagram::FindBlock(std::string_view name) const {
  const auto it = block_index_.find(name);
  return it == block_index_.end() ? -1 : it->second;
}

int Diagram::FindBlockOf(std::string_view reference, std::string_view* port) const {
  // the longest prefix first: the whole reference, then up to each '.' from the right
  for (std::size_t end = reference.size();; --end) {
    if (end == reference.size() || reference[end] == '.') {
      const int b = FindBlock(reference.substr(0, end));
      if (b >= 0) {
        *port = end == reference.size() ? std::string_view() : reference.substr(end + 1);
        return b;
      }
    }
    if (end == 0) break;
  }
  const auto dot = reference.rfind('.');
  *port = dot == std::string_view::npos ? std::string_view() : reference.substr(dot + 1);
  return -1;
}

std::pair<int, int> Diagram::FindOutput(std::string_view reference) const {
  std::string_view port_name;
  const int b = FindBlockOf(reference, &port_name);
  if (b < 0) {
    // the block as the reference was written before ports could hold dots
    const std::string_view block_name = reference.substr(0, reference.rfind('.'));
    std::vector<std::string> names;
    for (const auto& blk : blocks_) names.push_back(blk->name());
    throw InputError("signal '" + std::string(reference) + "': no block named '" +
                     std::string(block_name) + "'" + DidYouMean(block_name, names));
  }
  const Block& blk = *blocks_[b];
  if (port_name.empty()) {
    if (blk.num_outputs() != 1)
      throw InputError("signal '" + std::string(reference) + "': block '" + blk.name() + "' has " +
                       std::to_string(blk.num_outputs()) + " outputs; name one of: " +
                       JoinNames(PortNames(blk, true)));
    return {b, 0};
  }
  const int port = blk.FindOutput(port_name);
  if (port < 0)
    throw InputError("signal '" + std::string(reference) + "': block '" + blk.name() +
                     "' has no output '" + std::string(port_name) + "'" +
                     DidYouMean(port_name, PortNames(blk, true)) +
                     "; its outputs: " + JoinNames(PortNames(blk, true)));
  return {b, port};
}

SignalRef Diagram::ResolveSignal(std::string_view reference) const {
  if (const auto alias = aliases_.find(reference); alias != aliases_.end()) {
    SignalRef ref = ResolveSignal(alias->second);
    ref.name = alias->first;  // a logged d[1].F is called that, not d[1].fr.F
    return ref;
  }
  const auto [b, port] = FindOutput(reference);
  const Block& blk = *blocks_[b];
  return {PortName(blk, blk.output_port(port)), layouts_[b].output_offset[port],
          layouts_[b].output_width[port]};
}

DiagramBuilder::DiagramBuilder() : diagram_(new Diagram) {}
DiagramBuilder::~DiagramBuilder() = default;

void DiagramBuilder::ThrowIfBuilt(const char* what) const {
  if (!diagram_) throw std::logic_error(std::string("DiagramBuilder::") + what + " after Build()");
}

Block& DiagramBuilder::AddBlock(std::unique_ptr<Block> block, std::string origin) {
  ThrowIfBuilt("AddBlock");
  const int existing = diagram_->FindBlock(block->name());
  if (existing >= 0) {
    const std::string& first = diagram_->origins_[existing];
    throw InputError(Where(origin) + "block name '" + block->name() + "' is used twice" +
                     (first.empty() ? "" : " (first at " + first + ")"));
  }
  // names a diagram's author writes are checked where they are read (no '.'
  // there); these are a program's, or instance paths made by flattening
  if (const std::string problem = BlockNameProblem(block->name()); !problem.empty())
    throw InputError(Where(origin) + "block name '" + block->name() + "' " + problem +
                     ": a block name is one or more parts joined by '.' (an instance path such as d[1].fr)");
  diagram_->block_index_.emplace(block->name(), diagram_->num_blocks());
  diagram_->blocks_.push_back(std::move(block));
  diagram_->origins_.push_back(std::move(origin));
  return *diagram_->blocks_.back();
}

void DiagramBuilder::Connect(std::string_view from, std::string_view to, std::string origin) {
  ThrowIfBuilt("Connect");
  pending_.push_back({std::string(from), std::string(to), std::move(origin)});
}

void DiagramBuilder::AddSignalAlias(std::string_view alias, std::string_view target, std::string origin) {
  ThrowIfBuilt("AddSignalAlias");
  const auto [it, fresh] = pending_aliases_.emplace(std::string(alias), PendingAlias{std::string(target), origin});
  if (!fresh)
    throw InputError(Where(origin) + "signal alias '" + std::string(alias) + "' is given twice" +
                     (it->second.origin.empty() ? "" : " (first at " + it->second.origin + ")"));
  alias_order_.push_back(std::string(alias));
}

// Follows each alias to the output it stands for and checks that output
// exists; before connections are resolved, which may name aliases.
void DiagramBuilder::ResolveAliases() {
  Diagram& d = *diagram_;
  for (const std::string& alias : alias_order_) {
    const PendingAlias& given = pending_aliases_.find(alias)->second;
    const std::string what = Where(given.origin) + "signal alias '" + alias + "' for '" + given.target + "': ";
    std::string_view port;
    if (const int b = d.FindBlockOf(alias, &port);
        b >= 0 && (port.empty() ? d.blocks_[b]->num_outputs() == 1 : d.blocks_[b]->FindOutput(port) >= 0))
      throw InputError(what + "'" + alias + "' already names an output of block '" + d.blocks_[b]->name() +
                       "'; give the alias a name of its own");
    std::string target = given.target;
    for (std::size_t steps = 0;; ++steps) {
      const auto next = pending_aliases_.find(target);
      if (next == pending_aliases_.end()) break;
      if (steps == pending_aliases_.size())
        throw InputError(what + "the aliases go round in a circle; one of them must name a block's output");
      target = next->second.target;
    }
    try {
      d.FindOutput(target);
    } catch (const InputError& e) {
      throw InputError(what + e.what());
    }
    d.aliases_.emplace(alias, std::move(target));
  }
}

Connection DiagramBuilder::Resolve(const PendingConnection& c) const {
  const Diagram& d = *diagram_;
  const std::string what =
      Where(c.origin) + "connection from '" + c.from + "' to '" + c.to + "': ";
  // only for a message: a list of every name per connection would make
  // resolving quadratic in the number of blocks
  const auto block_names = [&] {
    std::vector<std::string> names;
    for (const auto& b : d.blocks_) names.push_back(b->name());
    return names;
  };

  auto find_port = [&](const std::string& written, bool output, int* block, int* port) {
    const auto alias = d.aliases_.find(written);
    if (alias != d.aliases_.end() && !output)
      throw InputError(what + "'" + written + "' is another name for the output " + alias->second +
                       ", not an input; connect to an input");
    const std::string_view ref = alias != d.aliases_.end() ? std::string_view(alias->second) : written;
    std::string_view port_name;
    const char* side = output ? "output" : "input";
    *block = d.FindBlockOf(ref, &port_name);
    if (*block < 0) {
      const std::string_view block_name = ref.substr(0, ref.rfind('.'));
      throw InputError(what + "there is no block named '" + std::string(block_name) + "'" +
                       DidYouMean(block_name, block_names()));
    }
    const Block& b = *d.blocks_[*block];
    const auto names = PortNames(b, output);
    const int count = output ? b.num_outputs() : b.num_inputs();
    if (port_name.empty()) {
      if (count != 1)
        throw InputError(what + "block '" + b.name() + "' (" + b.type() + ") has " +
                         std::to_string(count) + " " + side + "s; write '" + b.name() +
                         ".PORT' with PORT one of: " + (names.empty() ? "(none)" : JoinNames(names)));
      *port = 0;
      return;
    }
    *port = output ? b.FindOutput(port_name) : b.FindInput(port_name);
    if (*port < 0)
      throw InputError(what + "block '" + b.name() + "' (" + b.type() + ") has no " + side +
                       " port '" + std::string(port_name) + "'" + DidYouMean(port_name, names) +
                       "; its " + side + "s: " + (names.empty() ? "(none)" : JoinNames(names)));
  };

  Connection r;
  find_port(c.from, true, &r.from_block, &r.from_port);
  find_port(c.to, false, &r.to_block, &r.to_port);
  const Block& a = *d.blocks_[r.from_block];
  const Block& b = *d.blocks_[r.to_block];
  const int wa = a.output_port(r.from_port).width, wb = b.input_port(r.to_port).width;
  if (wa != wb)
    throw InputError(what + "width mismatch: output " + PortName(a, a.output_port(r.from_port)) +
                     " has width " + std::to_string(wa) + ", input " +
                     PortName(b, b.input_port(r.to_port)) + " has width " + std::to_string(wb));
  return r;
}

void DiagramBuilder::CheckInputs(const std::vector<Connection>& resolved) const {
  const Diagram& d = *diagram_;
  // driver of each input, to find inputs driven twice and inputs not driven
  std::map<std::pair<int, int>, size_t> driver;
  for (size_t i = 0; i < resolved.size(); ++i) {
    const Connection& c = resolved[i];
    const auto key = std::make_pair(c.to_block, c.to_port);
    const auto [it, fresh] = driver.emplace(key, i);
    if (!fresh) {
      const Connection& first = resolved[it->second];
      const Block& to = *d.blocks_[c.to_block];
      const Block& a = *d.blocks_[first.from_block];
      const Block& b = *d.blocks_[c.from_block];
      throw InputError(Where(pending_[i].origin) + "input " + PortName(to, to.input_port(c.to_port)) +
                       " is driven twice: by " + PortName(a, a.output_port(first.from_port)) +
                       (pending_[it->second].origin.empty() ? "" : " (" + pending_[it->second].origin + ")") +
                       " and by " + PortName(b, b.output_port(c.from_port)) +
                       "; use a sum block to add signals");
    }
  }
  for (int bi = 0; bi < d.num_blocks(); ++bi) {
    const Block& b = *d.blocks_[bi];
    for (int p = 0; p < b.num_inputs(); ++p)
      if (!driver.count({bi, p}))
        throw InputError(Where(d.origins_[bi]) + "input " + PortName(b, b.input_port(p)) +
                         " is not connected: connect an output to it (e.g. <connect from=\"...\" to=\"" +
                         PortName(b, b.input_port(p)) + "\"/>)");
  }
}

void DiagramBuilder::LayOut(Diagram* d, const std::vector<Connection>& resolved) const {
  d->layouts_.resize(d->blocks_.size());
  for (int bi = 0; bi < d->num_blocks(); ++bi) {
    const Block& b = *d->blocks_[bi];
    BlockLayout& l = d->layouts_[bi];
    l.block = bi;
    for (int p = 0; p < b.num_outputs(); ++p) {
      l.output_offset.push_back(d->num_signals_);
      l.output_width.push_back(b.output_port(p).width);
      d->num_signals_ += b.output_port(p).width;
    }
    l.input_offset.assign(b.num_inputs(), 0);
    l.input_width.assign(b.num_inputs(), 0);
    l.first_state = d->num_states_;
    l.num_states = b.num_states();
    d->num_states_ += b.num_states();
    l.first_discrete = d->num_discrete_;
    l.num_discrete = b.num_discrete_states();
    d->num_discrete_ += b.num_discrete_states();
    l.first_crossing = d->num_crossings_;
    l.num_crossings = b.num_zero_crossings();
    d->num_crossings_ += b.num_zero_crossings();
    if (b.num_states() > 0) d->stateful_.push_back(bi);
    if (b.num_zero_crossings() > 0) d->crossing_.push_back(bi);
    if (b.sample_time().is_periodic()) d->periodic_.push_back(bi);
  }
  for (const Connection& c : resolved) {
    BlockLayout& l = d->layouts_[c.to_block];
    const int from = d->layouts_[c.from_block].output_offset[c.from_port];
    const int width = d->layouts_[c.from_block].output_width[c.from_port];
    l.input_offset[c.to_port] = from;
    l.input_width[c.to_port] = width;
    // A port that feeds itself through its own input (y = 1 - y) would read
    // the slot it is writing: the input reads a copy instead, which the
    // loop solver sets to the tear values.
    if (c.from_block == c.to_block && d->blocks_[c.to_block]->HasFeedthrough(c.to_port, c.from_port)) {
      l.input_offset[c.to_port] = d->num_signals_;
      for (int k = 0; k < width; ++k) d->input_copies_.push_back({from + k, d->num_signals_ + k});
      d->num_signals_ += width;
    }
  }
  d->connections_ = resolved;
}

namespace {

// Feedthrough graph over output ports: edges[u] lists (v, connection) when
// port v depends directly on port u through that connection.
using Edges = std::vector<std::vector<std::pair<int, int>>>;

// Strongly connected components (Tarjan's algorithm, iterative: a chain of
// 100000 blocks must not recurse 100000 deep). One finder serves every call
// of a schedule: its marks are sized once and reset only where a call
// touched them, so a call costs what its subgraph holds, not the diagram.
class ComponentFinder {
 public:
  explicit ComponentFinder(const Edges& edges)
      : edges_(edges), index_(edges.size(), -1), low_(edges.size(), 0), on_stack_(edges.size(), 0) {}

  // The components of the subgraph of `nodes` that are `active` (a mask over
  // every node; active nodes outside `nodes` must not be reachable), sinks
  // first.
  std::vector<std::vector<int>> operator()(const std::vector<int>& nodes, const std::vector<char>& active) {
    std::vector<std::vector<int>> components;
    int counter = 0;
    const auto enter = [&](int u) {
      index_[u] = low_[u] = counter++;
      stack_.push_back(u);
      on_stack_[u] = 1;
      calls_.push_back({u, 0});
    };
    for (const int root : nodes) {
      if (!active[root] || index_[root] >= 0) continue;
      enter(root);
      while (!calls_.empty()) {
        const int u = calls_.back().first;
        std::size_t& next = calls_.back().second;
        if (next < edges_[u].size()) {
          const int v = edges_[u][next++].first;
          if (!active[v]) continue;
          if (index_[v] < 0) enter(v);
          else if (on_stack_[v]) low_[u] = std::min(low_[u], index_[v]);
          continue;
        }
        calls_.pop_back();
        if (!calls_.empty()) low_[calls_.back().first] = std::min(low_[calls_.back().first], low_[u]);
        if (low_[u] != index_[u]) continue;
        std::vector<int> comp;
        int v;
        do {
          v = stack_.back();
          stack_.pop_back();
          on_stack_[v] = 0;
          comp.push_back(v);
        } while (v != u);
        components.push_back(std::move(comp));
      }
    }
    for (const int u : nodes) index_[u] = -1;
    return components;
  }

 private:
  const Edges& edges_;
  std::vector<int> index_, low_, stack_;
  std::vector<char> on_stack_;
  std::vector<std::pair<int, std::size_t>> calls_;  // (node, next edge) of the depth-first walk
};

// A component is a cycle when it has more than one node or a node feeding itself.
bool IsCycle(const std::vector<int>& comp, const Edges& edges) {
  if (comp.size() > 1) return true;
  for (const auto& e : edges[comp.front()])
    if (e.first == comp.front()) return true;
  return false;
}

// Output ports that cut every cycle of a loop: repeatedly, in each cycle that
// remains, the port with the most paths through it (in-degree x out-degree
// inside the cycle; ties to the narrower, then the earlier port). Few tears
// make a small Newton system. `mask` is a zeroed scratch mask over every
// node, left zeroed.
std::vector<int> ChooseTears(const std::vector<int>& loop, const Edges& edges, const std::vector<int>& width,
                             ComponentFinder& find_components, std::vector<char>& mask) {
  for (const int u : loop) mask[u] = 1;
  std::map<int, int> in, out;
  std::vector<int> tears;
  for (bool cut = true; cut;) {
    cut = false;
    for (const auto& comp : find_components(loop, mask)) {
      if (!IsCycle(comp, edges)) continue;
      in.clear();
      out.clear();
      for (const int u : comp) mask[u] = 2;  // in this component
      for (const int u : comp)
        for (const auto& [v, ci] : edges[u])
          if (mask[v] == 2) ++out[u], ++in[v];
      for (const int u : comp) mask[u] = 1;
      int best = comp.front();
      for (const int u : comp) {
        const long score = long(in[u]) * out[u], best_score = long(in[best]) * out[best];
        if (score > best_score || (score == best_score && (width[u] < width[best] ||
                                                           (width[u] == width[best] && u < best))))
          best = u;
      }
      tears.push_back(best);
      mask[best] = 0;
      cut = true;
    }
  }
  for (const int u : loop) mask[u] = 0;
  return tears;
}

}  // namespace

// Orders output ports so that every port is computed after the ports it
// depends on directly. Nodes are output ports; an edge runs from output A.o to
// output B.p when A.o drives an input of B that feeds B.p directly. Tarjan's
// algorithm yields the strongly connected components sinks-first; any
// component with more than one node, or a node with an edge to itself, is an
// algebraic loop, scheduled as one entry and solved at run time.
void DiagramBuilder::Schedule(Diagram* d) const {
  std::vector<int> first_node(d->num_blocks() + 1, 0);
  for (int b = 0; b < d->num_blocks(); ++b) first_node[b + 1] = first_node[b] + d->blocks_[b]->num_outputs();
  const int n = first_node.back();
  std::vector<OutputNode> nodes(n);
  std::vector<int> width(n);
  for (int b = 0; b < d->num_blocks(); ++b)
    for (int p = 0; p < d->blocks_[b]->num_outputs(); ++p) {
      nodes[first_node[b] + p] = {b, p};
      width[first_node[b] + p] = d->layouts_[b].output_width[p];
    }

  Edges edges(n);
  for (size_t ci = 0; ci < d->connections_.size(); ++ci) {
    const Connection& c = d->connections_[ci];
    const Block& to = *d->blocks_[c.to_block];
    for (int p = 0; p < to.num_outputs(); ++p)
      if (to.HasFeedthrough(c.to_port, p))
        edges[first_node[c.from_block] + c.from_port].push_back({first_node[c.to_block] + p, int(ci)});
  }

  // One cycle of the loop as block.port hops, for messages; `port` gets the
  // port the cycle starts from.
  std::vector<char> mask(n, 0), seen(n, 0);  // scratch, zero between uses
  auto describe = [&](const std::vector<int>& comp, std::string* port) {
    for (const int u : comp) mask[u] = 1;
    std::vector<std::pair<int, int>> path;  // (connection, node it reaches)
    std::vector<int> visited;
    int cur = comp.front();
    while (!seen[cur]) {
      seen[cur] = 1;
      visited.push_back(cur);
      for (const auto& [v, ci] : edges[cur])
        if (mask[v]) {
          path.push_back({ci, v});
          cur = v;
          break;
        }
    }
    for (const int u : comp) mask[u] = 0;
    for (const int u : visited) seen[u] = 0;
    // cur is the first node met twice: drop the lead-in before it
    const auto lead_in = std::find(visited.begin(), visited.end(), cur) - visited.begin();
    path.erase(path.begin(), path.begin() + lead_in);
    const Block& first = *d->blocks_[nodes[cur].block];
    *port = PortName(first, first.output_port(nodes[cur].port));
    std::string text;
    for (const auto& [ci, reached] : path) {
      const Connection& c = d->connections_[ci];
      const Block& a = *d->blocks_[c.from_block];
      const Block& b = *d->blocks_[c.to_block];
      text += "\n  " + PortName(a, a.output_port(c.from_port)) + " -> " + PortName(b, b.input_port(c.to_port)) +
              " (feeds " + PortName(b, b.output_port(nodes[reached].port)) + " directly)" +
              (pending_[ci].origin.empty() ? "" : " at " + pending_[ci].origin);
    }
    return text;
  };

  ComponentFinder find_components(edges);
  std::vector<int> all(n);
  for (int u = 0; u < n; ++u) all[u] = u;
  const std::vector<std::vector<int>> components = find_components(all, std::vector<char>(n, 1));
  std::multimap<int, int> copies_of;  // output slot -> input copy slots
  for (const auto& [from, copy] : d->input_copies_) copies_of.emplace(from, copy);
  // Tarjan emits sinks first: reverse for evaluation order
  for (auto it = components.rbegin(); it != components.rend(); ++it) {
    if (!IsCycle(*it, edges)) {
      d->schedule_.push_back(nodes[it->front()]);
      continue;
    }
    const std::vector<int> tear_ids = ChooseTears(*it, edges, width, find_components, mask);
    for (const int u : *it) mask[u] = 1;
    for (const int u : tear_ids) mask[u] = 0;
    std::vector<OutputNode> inner, tears;
    const auto order = find_components(*it, mask);  // all single ports now, sinks first
    for (const int u : *it) mask[u] = 0;
    for (auto o = order.rbegin(); o != order.rend(); ++o) inner.push_back(nodes[o->front()]);
    std::vector<int> offsets, widths;
    std::vector<std::pair<int, int>> copies;
    int unknowns = 0;
    for (const int u : tear_ids) {
      const int offset = d->layouts_[nodes[u].block].output_offset[nodes[u].port];
      tears.push_back(nodes[u]);
      offsets.push_back(offset);
      widths.push_back(width[u]);
      for (auto c = copies_of.lower_bound(offset); c != copies_of.end() && c->first < offset + width[u]; ++c)
        copies.push_back({unknowns + c->first - offset, c->second});
      unknowns += width[u];
    }
    OutputNode entry = tears.front();
    entry.loop = static_cast<int>(d->loops_.size());
    std::string port;
    std::string hops = describe(*it, &port);
    d->loops_.emplace_back(entry.loop, std::move(inner), std::move(tears), offsets, widths, std::move(copies),
                           std::move(port), std::move(hops));
    d->schedule_.push_back(entry);
  }
}

// Splits the schedule: the outputs that derivatives and zero crossings read,
// directly or through the outputs that feed them, are the dynamics schedule
// (a right-hand side or a root check computes those alone); the others are
// logged or watched only, and are computed for output rows.
void DiagramBuilder::SplitSchedule(Diagram* d) {
  const int nb = d->num_blocks();
  std::vector<std::vector<char>> needed(nb);
  std::vector<std::vector<int>> loop_of(nb), inbound(nb);
  for (int b = 0; b < nb; ++b) {
    needed[b].assign(d->blocks_[b]->num_outputs(), 0);
    loop_of[b].assign(d->blocks_[b]->num_outputs(), -1);
  }
  for (int l = 0; l < static_cast<int>(d->loops_.size()); ++l)
    for (const auto* nodes : {&d->loops_[l].inner(), &d->loops_[l].tears()})
      for (const OutputNode& node : *nodes) loop_of[node.block][node.port] = l;
  for (int c = 0; c < static_cast<int>(d->connections_.size()); ++c)
    inbound[d->connections_[c].to_block].push_back(c);
  std::vector<char> loop_needed(d->loops_.size(), 0);
  std::vector<OutputNode> work;
  auto mark = [&](int block, int port) {
    if (needed[block][port]) return;
    needed[block][port] = 1;
    work.push_back({block, port});
    const int l = loop_of[block][port];
    if (l < 0 || loop_needed[l]) return;
    loop_needed[l] = 1;  // a loop is solved as a whole
    for (const auto* nodes : {&d->loops_[l].inner(), &d->loops_[l].tears()})
      for (const OutputNode& node : *nodes)
        if (!needed[node.block][node.port]) {
          needed[node.block][node.port] = 1;
          work.push_back(node);
        }
  };
  for (const Connection& c : d->connections_) {
    const Block& to = *d->blocks_[c.to_block];
    if (to.num_states() > 0 || to.num_zero_crossings() > 0) mark(c.from_block, c.from_port);
  }
  while (!work.empty()) {
    const OutputNode node = work.back();
    work.pop_back();
    const Block& block = *d->blocks_[node.block];
    for (const int ci : inbound[node.block]) {
      const Connection& c = d->connections_[ci];
      if (block.HasFeedthrough(c.to_port, node.port)) mark(c.from_block, c.from_port);
    }
  }
  for (const OutputNode& entry : d->schedule_) {
    const bool in_dynamics = entry.loop >= 0 ? loop_needed[entry.loop] : needed[entry.block][entry.port];
    (in_dynamics ? d->dynamics_schedule_ : d->rest_schedule_).push_back(entry);
  }
}

std::unique_ptr<Diagram> DiagramBuilder::Build() {
  ThrowIfBuilt("Build");
  ResolveAliases();
  std::vector<Connection> resolved;
  for (const auto& c : pending_) resolved.push_back(Resolve(c));
  CheckInputs(resolved);
  LayOut(diagram_.get(), resolved);
  Schedule(diagram_.get());
  SplitSchedule(diagram_.get());
  pending_.clear();
  pending_aliases_.clear();
  alias_order_.clear();
  return std::move(diagram_);
}

}  // namespace mechflow::blocks
