-- tests/fuzz/minimise_lib.lua — the reduction shared by minimise.lua (the
-- Lua API fuzzer) and minimise_c.lua (the C API fuzzer). Both fuzzers draw
-- every call alike whether an earlier call was made or skipped, so a failing
-- run of N calls shrinks by skipping calls: a removal is kept when the run
-- still fails the same way. Plain Lua 5.1 to 5.4 (tests/lua/test_minimise.lua
-- runs it under the runner and LuaJIT).
--
-- Order, cheapest big wins first: a run often fails on a world made late,
-- after thousands of calls on other worlds (a 38 k-call run took over 400 s
-- to reach 13 k calls by halving call ranges alone), so first every call
-- that names none of the failing call's worlds goes at once, then each other
-- world's calls (and the calls that name no world) as a group, largest
-- first; calls that make a world stay in these (a world made or not shifts
-- which world later calls pick). Then chunks of the calls left: halves,
-- quarters, … single calls, each tried once per size.
local M = {}

-- The skip set as sorted, merged ranges: "3-9,12".
function M.ranges(skip)
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
  return table.concat(parts, ",")
end

-- Written to a file: a long list would not fit in the environment.
function M.write_skip(skip, path)
  local fh = assert(io.open(path, "w"))
  fh:write(M.ranges(skip), "\n")
  fh:close()
end

-- The groups of whole-world removals: every call that names none of the
-- failing call's worlds, then per other world (key "-" for calls that name
-- no world), largest first. worlds[c] lists the worlds call c names.
local function world_groups(o)
  local failing, all, by, keys = {}, {}, {}, {}
  for _, k in ipairs(o.worlds[o.ncalls] or {}) do failing[k] = true end
  for c = 1, o.ncalls - 1 do
    local names, related = o.worlds[c] or {}, false
    for _, k in ipairs(names) do related = related or failing[k] end
    if not related and not (o.makes and o.makes[c]) then
      all[#all + 1] = c
      for _, k in ipairs(#names > 0 and names or { "-" }) do
        if not by[k] then by[k] = {}; keys[#keys + 1] = k end
        table.insert(by[k], c)
      end
    end
  end
  table.sort(keys, function(a, b) return #by[a] > #by[b] or (#by[a] == #by[b] and tostring(a) < tostring(b)) end)
  local groups = { all }
  for _, k in ipairs(keys) do groups[#groups + 1] = by[k] end
  return groups
end

-- o: ncalls, fails(skip) (true when the run without the calls of the set
-- skip still fails the same way), keep() (after each kept removal),
-- worlds (call -> list of the worlds it names; nil: no world phase), makes
-- (set of calls that make a world), over() (true when the budget is spent),
-- say(message). Returns the skip set, the calls left and the runs tried.
function M.reduce(o)
  local skip, kept, tried = {}, o.ncalls, 0
  local function try(calls)
    local trial, removed = {}, 0
    for k in pairs(skip) do trial[k] = true end
    for _, c in ipairs(calls) do
      if not trial[c] then trial[c] = true; removed = removed + 1 end
    end
    if removed == 0 or o.over() then return false end
    tried = tried + 1
    if not o.fails(trial) then return false end
    skip, kept = trial, kept - removed
    o.keep()
    o.say(string.format("%d calls left", kept))
    return true
  end
  if o.worlds then
    for _, g in ipairs(world_groups(o)) do try(g) end
  end
  local left = {}
  for c = 1, o.ncalls - 1 do if not skip[c] then left[#left + 1] = c end end -- the failing call stays
  local chunk = math.floor(#left / 2)
  while chunk >= 1 and not o.over() do
    local i = 1
    while i <= #left and not o.over() do
      local part = {}
      for j = i, math.min(i + chunk - 1, #left) do part[#part + 1] = left[j] end
      if try(part) then
        local rest = {}
        for j = 1, #left do if j < i or j >= i + #part then rest[#rest + 1] = left[j] end end
        left = rest
      else
        i = i + chunk
      end
    end
    chunk = math.floor(math.min(chunk, #left) / 2)
  end
  return skip, kept, tried
end

return M
