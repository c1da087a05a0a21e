-- Control script of the Molecule seed model (docs/ELEMENTS.md 7 and
-- 9.15): the degree of the molecule's surface follows
--   mdeg = (nmax + nmin)/2 + (nmax - nmin)/2 sin(om t)
-- set before every output row, so each row shows the value at its time.

local nmin, nmax, om

local function degree(t)
  return (nmax + nmin) / 2 + (nmax - nmin) / 2 * math.sin(om * t)
end

function init(sim)
  nmin, nmax, om = sim:get("nmin"), sim:get("nmax"), sim:get("om")
  sim:set("mdeg", degree(sim.t))
end

function step(sim)
  sim:set("mdeg", degree(sim.t))
end
