-- tests/fuzz/minimise.lua RUNNER SEED CALLS OUTDIR — shortens a failing fuzz
-- run (run with stock lua5.4). The fuzzer is deterministic for a seed, and
-- FUZZ_SKIP makes it draw a call's arguments without making the call, so
-- the minimiser skips calls and keeps a removal when the run still fails
-- the same way (tests/fuzz/minimise_lib.lua: other worlds' calls first,
-- then chunks). Budget: FUZZ_MIN_SECONDS (default 120). Leaves
-- OUTDIR/minimal.lua, the replay of the shortest failing run found.
package.path = "tests/fuzz/?.lua;" .. package.path
local R = require "minimise_lib"
local runner, seed, ncalls, out = arg[1], tonumber(arg[2]), tonumber(arg[3]), arg[4]
assert(runner and seed and ncalls and out, "usage: minimise.lua RUNNER SEED CALLS OUTDIR")
local budget = tonumber(os.getenv("FUZZ_MIN_SECONDS") or "") or 120
local t0 = os.time()

-- What kind of failure a run ended with: its first failure line, numbers
-- and addresses blanked, so another instance of the same bug still matches.
local function run(skip)
  R.write_skip(skip, out .. "/try-skip.txt")
  local cmd = string.format("FUZZ_SEED=%d FUZZ_CALLS=%d FUZZ_SECONDS=100000 FUZZ_SKIP=@%s/try-skip.txt FUZZ_REPLAY=%s/try.lua " ..
                            "%s --headless --frames 1000000 --every 20 --size 96x72 --out %s/frames tests/fuzz/fuzz_api.lua 2>&1",
                            seed, ncalls, out, out, runner, out)
  local p = io.popen(cmd)
  local text = p:read("a")
  p:close()
  local line = text:match("FUZZ FAILURE:[^\n]*") or text:match("ERROR: %w+Sanitizer:[^\n]*")
               or text:match("runtime error:[^\n]*") or text:match("Segmentation fault") or ""
  return (line:gsub("0x%x+", "#"):gsub("%d+", "#"):sub(1, 100))
end

local function keep() os.execute(string.format("cp %s/try.lua %s/minimal.lua", out, out)) end

local want = run({})
if want == "" then
  print("minimise: the run no longer fails: nothing to do")
  os.exit(1)
end
print("minimise: failure: " .. want)
keep()

-- The worlds each call names (W[i]: the i-th world made, in the replay's
-- lines "... -- N"); tether.world makes one.
local worlds, makes = {}, {}
for line in io.lines(out .. "/minimal.lua") do
  local c = tonumber(line:match("%-%- (%d+)$") or "")
  if c then
    local names = {}
    for i in line:gmatch("W%[(%d+)%]") do names[#names + 1] = tonumber(i) end
    worlds[c] = names
    if line:find('F.call("tether.world"', 1, true) then makes[c] = true end
  end
end

local _, kept, tried = R.reduce {
  ncalls = ncalls, worlds = worlds, makes = makes, keep = keep,
  fails = function(skip) return run(skip) == want end,
  over = function() return os.time() - t0 >= budget end,
  say = function(msg) print("minimise: " .. msg) end,
}
print(string.format("minimise: %d of %d calls left in %s/minimal.lua (%d runs, %d s)", kept, ncalls, out, tried + 1,
                    os.time() - t0))
