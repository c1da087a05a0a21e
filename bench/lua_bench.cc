// Benchmark: the cost of Lua in the right-hand side, against built-in elements.
//
// Pairs of diagrams that compute the same equations, one with built-in C++
// elements (the reference) and one with Lua:
//   damping_ratio   the seed DampingRatio (diagrams/examples/damping_ratio.xml):
//                   its spring-damper force as a built-in `linear` element
//                   (c = cstiff, x0 = 1.25, d = cdiss, f0 = -mass 9.81) versus
//                   the file's Lua expression law
//                   -cstiff*(x-1.25)-cdiss*v-mass*9.81.
//   oscillator      the damped oscillator as integrators, gains and a sum
//                   (damped_oscillator_blocks.xml) versus one Lua block with two
//                   states (damped_oscillator_lua.xml).
//   lag             a first-order lag driven by a sine: the built-in
//                   first_order_lag block versus a Lua block with one state.
// For each pair:
//   run      wall time of constructing blocks::Simulator and Run() (loading is
//            outside), median over --repeat alternating runs (reference first on
//            even runs, Lua first on odd runs), and the right-hand sides each run
//            evaluated (integrator + difference Jacobian): the per-RHS ratio
//            divides out any difference in the number of steps;
//   rhs      one evaluation of the diagram's passes (outputs, then derivatives)
//            as the simulator calls them, timed over a loop of --calls
//            evaluations at moving states: the right-hand side alone, without
//            CVODE's own work.
// Then the calling convention of a Lua block function, measured on the Lua C
// API directly: numbers as arguments and multiple results (what the block does)
// versus two preallocated tables filled and read per call.
//
// Usage: bench_lua [--repeat N] [--calls N]   (defaults 7 and 200000)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <lua.hpp>

#include "blocks/framework/evaluation.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"
#include "scripting/lua_state.h"

namespace {

using namespace mechflow;

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Example(const std::string& name) { return std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + name; }

// `text` with `from` replaced by `to` (which must occur once).
std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos)
    throw std::runtime_error("expected exactly one '" + from + "' in the diagram");
  return text.replace(at, from.size(), to);
}

diagrams::LoadedDiagram Load(const std::string& text, const std::string& path) {
  return diagrams::LoadDiagramDescription(diagrams::ReadDiagramText(text, path));
}

struct RunResult {
  double seconds = 0;
  long rhs = 0;  // integrator + difference-Jacobian right-hand sides
  double last = 0;  // last value of the first logged column, to compare the pair
};

RunResult RunOnce(const diagrams::LoadedDiagram& d) {
  const auto start = Clock::now();
  blocks::Simulator sim(*d.diagram, d.solver, d.logged);
  const blocks::RunOutcome outcome = sim.Run();
  RunResult r;
  r.seconds = Seconds(start);
  if (!outcome.ok) throw std::runtime_error("run failed: " + outcome.failure);
  r.rhs = sim.stats().rhs_evals + sim.stats().jac_rhs_evals;
  r.last = sim.results().Column(1).back();
  return r;
}

// Seconds per evaluation of outputs + derivatives, over `calls` evaluations
// at states moved a little each time (so no block can reuse an evaluation).
double RhsSeconds(const diagrams::LoadedDiagram& loaded, int calls) {
  const blocks::Diagram& d = *loaded.diagram;
  blocks::Context ctx;
  ctx.signals.assign(d.num_signals(), 0.0);
  ctx.discrete.assign(d.num_discrete_states(), 0.0);
  std::vector<double> x(std::max(1, d.num_states()), 0.0), xdot(x.size(), 0.0);
  std::vector<double> crossings(std::max(1, d.num_zero_crossings()), 0.0);
  ctx.x = x.data();
  ctx.xdot = xdot.data();
  ctx.crossings = crossings.data();
  ctx.time = loaded.solver.t_start;
  blocks::InitializeStates(d, &ctx);
  const std::vector<double> x0 = x;
  double checksum = 0;
  const auto start = Clock::now();
  for (int i = 0; i < calls; ++i) {
    ctx.time = 1e-6 * i;
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = x0[k] * (1 + 1e-9 * (i & 1023));
    ++ctx.evaluation;
    blocks::EvaluateOutputs(d, &ctx);
    blocks::EvaluateDerivatives(d, &ctx);
    checksum += xdot[0];
  }
  const double seconds = Seconds(start) / calls;
  if (!std::isfinite(checksum)) throw std::runtime_error("non-finite derivative");
  return seconds;
}

struct Pair {
  std::string name;
  std::string what_reference, what_lua;
  diagrams::LoadedDiagram reference, lua;
};

void Compare(Pair& p, int repeat, int calls) {
  RunOnce(p.reference);  // warm-up
  RunOnce(p.lua);
  std::vector<double> t_ref, t_lua;
  RunResult r_ref, r_lua;
  for (int i = 0; i < repeat; ++i) {
    if (i % 2 == 0) {
      r_ref = RunOnce(p.reference);
      r_lua = RunOnce(p.lua);
    } else {
      r_lua = RunOnce(p.lua);
      r_ref = RunOnce(p.reference);
    }
    t_ref.push_back(r_ref.seconds);
    t_lua.push_back(r_lua.seconds);
  }
  std::vector<double> rhs_ref, rhs_lua;
  for (int i = 0; i < 3; ++i) {
    rhs_ref.push_back(RhsSeconds(p.reference, calls));
    rhs_lua.push_back(RhsSeconds(p.lua, calls));
  }
  const double m_ref = Median(t_ref), m_lua = Median(t_lua);
  const double e_ref = Median(rhs_ref), e_lua = Median(rhs_lua);
  std::printf("\n%s\n  reference: %s\n  lua:       %s\n", p.name.c_str(), p.what_reference.c_str(), p.what_lua.c_str());
  std::printf("  %-28s %14s %14s %8s\n", "", "reference", "lua", "ratio");
  std::printf("  %-28s %14.3f %14.3f %8.2f\n", "run wall time [ms] (median)", 1e3 * m_ref, 1e3 * m_lua, m_lua / m_ref);
  std::printf("  %-28s %14ld %14ld %8.2f\n", "RHS evaluations per run", r_ref.rhs, r_lua.rhs,
              double(r_lua.rhs) / double(r_ref.rhs));
  std::printf("  %-28s %14.3f %14.3f %8.2f\n", "run time per RHS [us]", 1e6 * m_ref / r_ref.rhs, 1e6 * m_lua / r_lua.rhs,
              (m_lua / r_lua.rhs) / (m_ref / r_ref.rhs));
  std::printf("  %-28s %14.3f %14.3f %8.2f\n", "one RHS alone [us]", 1e6 * e_ref, 1e6 * e_lua, e_lua / e_ref);
  std::printf("  %-28s %14.9g %14.9g\n", "last logged value", r_ref.last, r_lua.last);
}

// --- calling convention ----------------------------------------------------------

// Seconds per call of `fn` (the function on top of the stack) from C, the way
// scripting/lua_block.cc calls: traceback handler, function, numbers, pcall
// bounded by the instruction hook, results read back.
double TimeCalls(scripting::LuaState& lua, int calls, const std::function<void(lua_State*, int)>& push_and_call) {
  lua_State* L = lua.get();
  const int fn = lua_gettop(L);
  const auto start = Clock::now();
  for (int i = 0; i < calls; ++i) push_and_call(L, fn);
  return Seconds(start) / calls;
}

void CallingConvention(int calls) {
  scripting::LuaState lua;
  lua_State* L = lua.get();
  const char* code =
      "local c, d = 39.48, 1.2566\n"
      "args = function(t, x, v) return v, -c*x - d*v end\n"
      "tables = function(input, output) local x, v = input[2], input[3]; output[1] = v; output[2] = -c*x - d*v end\n";
  std::string error;
  if (!lua.Run(code, "=bench", &error)) throw std::runtime_error(error);
  double sink = 0;

  // numbers as arguments, results as multiple values; `bounded`: under the
  // instruction-count hook, as code that may loop runs
  auto by_arguments = [&](bool bounded) {
    lua_getglobal(L, "args");
    const double seconds = TimeCalls(lua, calls, [&](lua_State* L, int fn) {
      const int top = lua_gettop(L);
      lua_pushcfunction(L, &scripting::LuaState::TracebackHandler);
      lua_pushvalue(L, fn);
      lua_pushnumber(L, 0.1);
      lua_pushnumber(L, 0.5);
      lua_pushnumber(L, -0.2);
      int status;
      if (bounded) {
        scripting::BoundedCall bound(lua);
        status = lua_pcall(L, 3, LUA_MULTRET, top + 1);
      } else {
        status = lua_pcall(L, 3, LUA_MULTRET, top + 1);
      }
      if (status != LUA_OK || lua_gettop(L) - top - 1 != 2) throw std::runtime_error("args call failed");
      sink += lua_tonumber(L, top + 2) + lua_tonumber(L, top + 3);
      lua_settop(L, top);
    });
    lua_settop(L, 0);
    return seconds;
  };
  const double by_args = by_arguments(true);
  const double unbounded = by_arguments(false);  // what the bound costs

  lua_getglobal(L, "tables");
  lua_createtable(L, 3, 0);  // input, reused
  lua_createtable(L, 2, 0);  // output, reused
  const double by_tables = TimeCalls(lua, calls, [&](lua_State* L, int) {
    const int fn = 1, in = 2, out = 3;
    const int top = lua_gettop(L);
    lua_pushnumber(L, 0.1);
    lua_rawseti(L, in, 1);
    lua_pushnumber(L, 0.5);
    lua_rawseti(L, in, 2);
    lua_pushnumber(L, -0.2);
    lua_rawseti(L, in, 3);
    lua_pushcfunction(L, &scripting::LuaState::TracebackHandler);
    lua_pushvalue(L, fn);
    lua_pushvalue(L, in);
    lua_pushvalue(L, out);
    int status;
    {
      scripting::BoundedCall bounded(lua);
      status = lua_pcall(L, 2, 0, top + 1);
    }
    if (status != LUA_OK) throw std::runtime_error("tables call failed");
    lua_rawgeti(L, out, 1);
    lua_rawgeti(L, out, 2);
    sink += lua_tonumber(L, -1) + lua_tonumber(L, -2);
    lua_settop(L, top);
  });
  lua_settop(L, 0);
  std::printf("\ncalling convention (one call of a 2-state derivative function, bounded, from C)\n");
  std::printf("  numbers as arguments, multiple results: %8.1f ns\n", 1e9 * by_args);
  std::printf("  the same without the instruction bound:  %8.1f ns  (%.2f x)\n", 1e9 * unbounded, unbounded / by_args);
  std::printf("  preallocated input and output tables:   %8.1f ns  (%.2f x)\n", 1e9 * by_tables,
              by_tables / by_args);
  if (!std::isfinite(sink)) std::printf("(checksum %g)\n", sink);
}

[[noreturn]] void Usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s [--repeat N] [--calls N]   (defaults 7 and 200000)\n", argv0);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 7, calls = 200000;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--repeat" || arg == "--calls") && i + 1 < argc) {
      const int n = std::atoi(argv[++i]);
      if (n < 1) Usage(argv[0]);
      (arg == "--repeat" ? repeat : calls) = n;
    } else {
      Usage(argv[0]);
    }
  }
  try {
    std::vector<Pair> pairs;
    {
      const std::string path = Example("damping_ratio.xml");
      const std::string text = ReadFile(path);
      const std::string linear = Replace(text, "type=\"expression\"", "type=\"linear\"");
      const std::string law = "expression=\"-cstiff*(x-1.25)-cdiss*v-mass*9.81\"";
      pairs.push_back({"damping_ratio (seed DampingRatio, mechanism force element)",
                       "built-in linear element c=cstiff x0=1.25 d=cdiss f0=-mass*9.81",
                       "Lua expression law -cstiff*(x-1.25)-cdiss*v-mass*9.81",
                       Load(Replace(linear, law, "c=\"cstiff\" x0=\"1.25\" d=\"cdiss\" f0=\"-mass*9.81\""), path),
                       Load(text, path)});
    }
    {
      // the example's block, and the same written with an outputs function and
      // a helper function (two calls per evaluation, each under the count hook)
      const std::string blocks_path = Example("damped_oscillator_blocks.xml");
      const std::string lua_path = Example("damped_oscillator_lua.xml");
      const std::string lua = ReadFile(lua_path);
      const std::string two_calls = Replace(
          lua, "return v, (-c/m)*x + (-d/m)*v",
          "local function a(x, v) return (-c/m)*x + (-d/m)*v end\n return v, a(x, v) end\n"
          "function outputs(t, x, v) return x, v");
      pairs.push_back({"oscillator (x'' = -(c x + d v)/m, two states), Lua as first written",
                       "damped_oscillator_blocks.xml: 2 integrators, 2 gains, 1 sum",
                       "one lua block: outputs + derivatives with a helper (2 bounded calls per RHS)",
                       Load(ReadFile(blocks_path), blocks_path), Load(two_calls, lua_path)});
      pairs.push_back({"oscillator, Lua as in damped_oscillator_lua.xml",
                       "damped_oscillator_blocks.xml: 2 integrators, 2 gains, 1 sum",
                       "one lua block: straight-line derivatives only (1 call per RHS, no count hook)",
                       Load(ReadFile(blocks_path), blocks_path), Load(lua, lua_path)});
    }
    const auto lag = [](const std::string& block) {
      return "<diagram name=\"lag\"><identifiers><identifier name=\"tau\" value=\"0.05\"/></identifiers>"
             "<blocks><block type=\"sine\" name=\"u\" frequency=\"1\"/>" +
             block +
             "</blocks><connections><connect from=\"u.y\" to=\"lag.u\"/></connections>"
             "<solver t_end=\"10\" rtol=\"1e-8\" atol=\"1e-10\"/>"
             "<output interval=\"0.01\"><log signal=\"lag.y\"/></output></diagram>";
    };
    const std::string builtin_lag = lag("<block type=\"first_order_lag\" name=\"lag\" time_constant=\"tau\"/>");
    pairs.push_back(
        {"lag (tau y' + y = u, u = sin(2 pi t)), Lua with outputs and a helper", "first_order_lag block",
         "lua block: outputs + derivatives with a helper (2 bounded calls per RHS)", Load(builtin_lag, "lag.xml"),
         Load(lag("<block type=\"lua\" name=\"lag\" inputs=\"u\" states=\"y\" feedthrough=\"none\">"
                  "local function rate(y, u) return (u - y)/tau end "
                  "function derivatives(t, y, u) return rate(y, u) end "
                  "function outputs(t, y, u) return y end</block>"),
              "lag.xml")});
    pairs.push_back({"lag, Lua straight-line", "first_order_lag block",
                     "lua block: derivatives only (1 call per RHS, no count hook)", Load(builtin_lag, "lag.xml"),
                     Load(lag("<block type=\"lua\" name=\"lag\" inputs=\"u\" states=\"y\">"
                              "function derivatives(t, y, u) return (u - y)/tau end</block>"),
                          "lag.xml")});
    std::printf("bench_lua: median of %d alternating runs; one RHS alone: median of 3 loops of %d\n", repeat, calls);
    for (auto& p : pairs) Compare(p, repeat, calls);
    CallingConvention(calls * 5);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_lua: %s\n", e.what());
    return 1;
  }
  return 0;
}
