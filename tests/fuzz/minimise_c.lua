-- tests/fuzz/minimise_c.lua FUZZ_C SEED CALLS OUTDIR — shortens a failing run
-- of the C API fuzzer (build/fuzz_c) as minimise.lua does the Lua one's (run
-- with stock lua5.4). Each call of fuzz_c draws from its own stream (seed and
-- call number), and FUZZ_SKIP makes it pass over a call without making it, so
-- the minimiser skips calls and keeps a removal when the run still fails the
-- same way (tests/fuzz/minimise_lib.lua: other worlds' calls first, then
-- chunks). Budget: FUZZ_MIN_SECONDS (default 120). Leaves
-- OUTDIR/minimal-skip.txt (the calls skipped) and OUTDIR/minimal.txt (the
-- trace of the shortest failing run).
package.path = "tests/fuzz/?.lua;" .. package.path
local R = require "minimise_lib"
local bin, seed, ncalls, out = arg[1], arg[2], tonumber(arg[3]), arg[4]
assert(bin and seed and seed:match("^%d+$") and ncalls and out, "usage: minimise_c.lua FUZZ_C SEED CALLS OUTDIR")
local budget = tonumber(os.getenv("FUZZ_MIN_SECONDS") or "") or 120
local t0 = os.time()

-- What kind of failure a run ended with: its first failure line, numbers and
-- addresses blanked, so another instance of the same bug still matches.
local function run(skip)
  R.write_skip(skip, out .. "/try-skip.txt")
  local cmd = string.format("FUZZ_SEED=%s FUZZ_CALLS=%d FUZZ_TRACE=1 FUZZ_SKIP=@%s/try-skip.txt %s >%s/try.txt 2>&1",
                            seed, ncalls, out, bin, out)
  os.execute(cmd)
  local fh = io.open(out .. "/try.txt")
  local text = fh and fh:read("a") or ""
  if fh then fh:close() end
  local line = text:match("ERROR: %w+Sanitizer:[^\n]*") or text:match("runtime error:[^\n]*")
               or text:match("FUZZ FAILURE at call %d+, seed %d+: ([^\n]*)") or text:match("FUZZ CRASH") or ""
  return (line:gsub("0x%x+", "#"):gsub("%d+", "#"):sub(1, 100))
end

local function keep()
  os.execute(string.format("cp %s/try.txt %s/minimal.txt && cp %s/try-skip.txt %s/minimal-skip.txt", out, out, out, out))
end

local want = run({})
if want == "" then
  print("minimise_c: the run no longer fails: nothing to do")
  os.exit(1)
end
print("minimise_c: failure: " .. want)
keep()

-- The worlds each call names, from the trace: "#N ..." and its indented
-- lines name worlds w<k> (k counts the worlds made); "w<k> = tt_world_..."
-- makes one.
local worlds, makes, c = {}, {}, nil
for line in io.lines(out .. "/minimal.txt") do
  local n, rest = line:match("^#(%d+) (.*)")
  if n then c = tonumber(n); worlds[c] = worlds[c] or {} end
  if c then
    for k in (rest or line):gmatch("%f[%w_]w(%d+)%f[^%w_]") do table.insert(worlds[c], tonumber(k)) end
    if rest and rest:match("^w%d+ = tt_world_") then makes[c] = true end
  end
end

local _, kept, tried = R.reduce {
  ncalls = ncalls, worlds = worlds, makes = makes, keep = keep,
  fails = function(skip) return run(skip) == want end,
  over = function() return os.time() - t0 >= budget end,
  say = function(msg) print("minimise_c: " .. msg) end,
}
print(string.format("minimise_c: %d of %d calls left (%d runs, %d s): the trace in %s/minimal.txt; replay:", kept, ncalls,
                    tried + 1, os.time() - t0, out))
print(string.format("    FUZZ_SEED=%s FUZZ_CALLS=%d FUZZ_TRACE=1 FUZZ_SKIP=@%s/minimal-skip.txt %s", seed, ncalls, out, bin))
