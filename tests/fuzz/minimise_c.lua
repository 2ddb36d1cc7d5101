-- tests/fuzz/minimise_c.lua FUZZ_C SEED CALLS OUTDIR — shortens a failing run
-- of the C API fuzzer (build/fuzz_c) as minimise.lua does the Lua one's (run
-- with stock lua5.4). Each call of fuzz_c draws from its own stream (seed and
-- call number), and FUZZ_SKIP makes it pass over a call without making it, so
-- the minimiser removes chunks of calls (halves, quarters, … single calls)
-- and keeps a removal when the run still fails the same way. Budget:
-- FUZZ_MIN_SECONDS (default 120). Leaves OUTDIR/minimal-skip.txt (the calls
-- skipped) and OUTDIR/minimal.txt (the trace of the shortest failing run).
local bin, seed, ncalls, out = arg[1], arg[2], tonumber(arg[3]), arg[4]
assert(bin and seed and seed:match("^%d+$") and ncalls and out, "usage: minimise_c.lua FUZZ_C SEED CALLS OUTDIR")
local budget = tonumber(os.getenv("FUZZ_MIN_SECONDS") or "") or 120
local t0 = os.time()

-- The skipped calls as merged ranges ("3-9,12"), written to a file: a long
-- list would not fit in the environment.
local function write_skip(skip, path)
  local list = {}
  for k in pairs(skip) do list[#list + 1] = k end
  table.sort(list)
  local parts, i = {}, 1
  while i <= #list do
    local j = i
    while j < #list and list[j + 1] == list[j] + 1 do j = j + 1 end
    parts[#parts + 1] = i == j and tostring(list[i]) or (list[i] .. "-" .. list[j])
    i = j + 1
  end
  local fh = assert(io.open(path, "w"))
  fh:write(table.concat(parts, ","), "\n")
  fh:close()
end

-- What kind of failure a run ended with: its first failure line, numbers and
-- addresses blanked, so another instance of the same bug still matches.
local function run(skip)
  write_skip(skip, out .. "/try-skip.txt")
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
      keep()
      print(string.format("minimise_c: %d calls left", kept))
    end
    start = start + chunk
  end
  chunk = chunk // 2
end
print(string.format("minimise_c: %d of %d calls left (%d s): the trace in %s/minimal.txt; replay:", kept, ncalls,
                    os.time() - t0, out))
print(string.format("    FUZZ_SEED=%s FUZZ_CALLS=%d FUZZ_TRACE=1 FUZZ_SKIP=@%s/minimal-skip.txt %s", seed, ncalls, out, bin))
