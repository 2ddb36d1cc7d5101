-- tests/fuzz/minimise.lua RUNNER SEED CALLS OUTDIR — shortens a failing fuzz
-- run (run with stock lua5.4). The fuzzer is deterministic for a seed, and
-- FUZZ_SKIP makes it draw a call's arguments without making the call, so
-- the minimiser removes chunks of calls (halves, quarters, … single calls)
-- and keeps a removal when the run still fails the same way. Budget:
-- FUZZ_MIN_SECONDS (default 120). Leaves OUTDIR/minimal.lua, the replay of
-- the shortest failing run found.
local runner, seed, ncalls, out = arg[1], tonumber(arg[2]), tonumber(arg[3]), arg[4]
assert(runner and seed and ncalls and out, "usage: minimise.lua RUNNER SEED CALLS OUTDIR")
local budget = tonumber(os.getenv("FUZZ_MIN_SECONDS") or "") or 120
local t0 = os.time()

-- What kind of failure a run ended with: its first failure line, numbers
-- and addresses blanked, so another instance of the same bug still matches.
local function run(skip)
  local list = {}
  for k in pairs(skip) do list[#list + 1] = k end
  table.sort(list)
  local cmd = string.format("FUZZ_SEED=%d FUZZ_CALLS=%d FUZZ_SECONDS=100000 FUZZ_SKIP=%s FUZZ_REPLAY=%s/try.lua " ..
                            "%s --headless --frames 1000000 --every 20 --size 96x72 --out %s/frames tests/fuzz/fuzz_api.lua 2>&1",
                            seed, ncalls, table.concat(list, ","), out, runner, out)
  local p = io.popen(cmd)
  local text = p:read("a")
  p:close()
  local line = text:match("FUZZ FAILURE:[^\n]*") or text:match("ERROR: %w+Sanitizer:[^\n]*")
               or text:match("runtime error:[^\n]*") or text:match("Segmentation fault") or ""
  return (line:gsub("0x%x+", "#"):gsub("%d+", "#"):sub(1, 100))
end

local want = run({})
if want == "" then
  print("minimise: the run no longer fails: nothing to do")
  os.exit(1)
end
print("minimise: failure: " .. want)
os.execute(string.format("cp %s/try.lua %s/minimal.lua", out, out))

local skip, kept = {}, ncalls
local chunk = ncalls // 2
while chunk >= 1 and os.time() - t0 < budget do
  local start = 1
  while start <= ncalls - 1 and os.time() - t0 < budget do -- the last call, the failing one, stays
    local trial, removed = {}, 0
    for k in pairs(skip) do trial[k] = true end
    for k = start, math.min(start + chunk - 1, ncalls - 1) do
      if not trial[k] then trial[k] = true; removed = removed + 1 end
    end
    if removed > 0 and run(trial) == want then
      skip, kept = trial, kept - removed
      os.execute(string.format("cp %s/try.lua %s/minimal.lua", out, out))
      print(string.format("minimise: %d calls left", kept))
    end
    start = start + chunk
  end
  chunk = chunk // 2
end
print(string.format("minimise: %d of %d calls left in %s/minimal.lua (%d s)", kept, ncalls, out, os.time() - t0))
