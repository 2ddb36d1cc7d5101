-- bench/mask_bench.lua DIR — the pixel-mask overlap benchmark from Lua, with
-- pygame.mask beside it (run by `make bench` after the C bench, whose mask
-- section writes the masks as PNGs into DIR and times the C calls and the
-- per-pixel reference). Lua and pygame take turns, two rounds each, so a
-- change of load on the machine falls on both; each figure is the median
-- of 7 batches of calls (with the min–max over the rounds beside it).
--   LUA_CPATH='build/?.so' lua5.4 bench/mask_bench.lua build/bench-out
local tether = require "tether"
local M = tether.mask
local dir = arg[1] or "build/bench-out"

local CALLS = { "overlap", "overlap_area", "overlap_mask" }
local SIZES = { 32, 128, 512, 1024 }

local function timed(fn)
  local n = 1
  local dt
  repeat
    local t0 = os.clock(); fn(n); dt = os.clock() - t0
    if dt < 0.02 then n = n * 4 end
  until dt >= 0.02
  local ts = { dt / n }
  for _ = 1, 6 do local t0 = os.clock(); fn(n); ts[#ts + 1] = (os.clock() - t0) / n end
  table.sort(ts)
  return ts[4] * 1e9, ts[1] * 1e9, ts[7] * 1e9
end

local function lua_round(res)
  for _, s in ipairs(SIZES) do
    for _, kind in ipairs { "random", "solid" } do
      local a = M.load(("%s/mask_%s_a_%d.png"):format(dir, kind, s))
      local b = M.load(("%s/mask_%s_b_%d.png"):format(dir, kind, s))
      for _, align in ipairs { "unaligned", "aligned" } do
        local dx, dy = align == "unaligned" and 13 or 0, 7
        for _, call in ipairs(CALLS) do
          local f = a[call]
          local med, lo, hi = timed(function(n) for _ = 1, n do f(a, b, dx, dy) end end)
          res[#res + 1] = { ("%s-%d-%s"):format(kind, s, align), call, med, lo, hi }
        end
      end
    end
  end
  local a = M.load(dir .. "/mask_worst_a.png")
  local bs, ox, oy = {}, {}, {}
  local k = 0
  for line in io.lines(dir .. "/mask_worst.txt") do
    k = k + 1
    ox[k], oy[k] = line:match("(%S+) (%S+)"); ox[k], oy[k] = math.tointeger(ox[k]), math.tointeger(oy[k])
    bs[k] = M.load(("%s/mask_worst_%d.png"):format(dir, k - 1))
    assert(a:overlap(bs[k], ox[k], oy[k]) == nil, "the worst case shares a bit")
  end
  local med, lo, hi = timed(function(n)
    for i = 1, n do local j = (i & 7) + 1; a:overlap(bs[j], ox[j], oy[j]) end
  end)
  res[#res + 1] = { "worst-1024", "overlap", med, lo, hi }
end

local function python()
  for _, p in ipairs { "/usr/bin/python3", "python3" } do
    local f = io.popen("PYGAME_HIDE_SUPPORT_PROMPT=1 " .. p .. " -c 'import pygame' >/dev/null 2>&1 && echo yes")
    local ok = f:read("l") == "yes"
    f:close()
    if ok then return p end
  end
end

local function pygame_round(py, res)
  local f = io.popen(("%s bench/mask_pygame.py %s"):format(py, dir))
  for line in f:lines() do
    local case, call, med, lo, hi = line:match("^(%S+) (%S+) (%S+) (%S+) (%S+)$")
    if case then res[#res + 1] = { case, call, tonumber(med), tonumber(lo), tonumber(hi) } end
  end
  f:close()
end

local function load_avg()
  local f = io.open("/proc/loadavg")
  if not f then return "?" end
  local s = f:read("l"); f:close()
  return s:match("^(%S+ %S+ %S+)")
end

-- C side (bench_mask.c): case/call → C ns, reference ns
local c = {}
for line in io.lines(dir .. "/mask_c.csv") do
  local case, call, cn, rn = line:match("^([^,]+),([^,]+),([^,]+),([^,]+)$")
  if case ~= "case" and case then c[case .. " " .. call] = { tonumber(cn), tonumber(rn) } end
end

local py = python()
local rounds = { lua = {}, pygame = {} }
local load_before = load_avg()
for r = 1, 2 do
  rounds.lua[r] = {}; lua_round(rounds.lua[r])
  if py then rounds.pygame[r] = {}; pygame_round(py, rounds.pygame[r]) end
end
local load_after = load_avg()

-- per case: the median of the rounds' medians, and the min/max over everything
local function merge(list)
  local out = {}
  for _, res in ipairs(list) do
    for _, row in ipairs(res) do
      local key = row[1] .. " " .. row[2]
      local o = out[key] or { meds = {}, lo = math.huge, hi = 0 }
      o.meds[#o.meds + 1] = row[3]
      o.lo = math.min(o.lo, row[4]); o.hi = math.max(o.hi, row[5])
      out[key] = o
    end
  end
  for _, o in pairs(out) do table.sort(o.meds); o.med = (o.meds[1] + o.meds[#o.meds]) / 2 end
  return out
end
local L, P = merge(rounds.lua), merge(rounds.pygame)

print(("\n== Pixel masks: overlap calls from Lua vs pygame.mask (%s), ns per call ==")
  :format(py and "python3-pygame, same PNG masks, taking turns" or "pygame ABSENT"))
print("target: every call <= 0.7x pygame's time; without pygame: 1024² area <= 9 us, worst case <= 12 us")
print(("machine load (1, 5, 15 min): %s before, %s after; %d cores"):format(load_before, load_after,
  tonumber(io.popen("nproc"):read("l")) or 0))
print(("%-24s %-13s %10s %21s %10s %10s %8s %12s"):format("masks", "call", "Lua ns", "(min-max)", "pygame ns",
  "C ns", "per-px", "Lua/pygame"))
local csv = assert(io.open(dir .. "/mask.csv", "w"))
csv:write("case,call,lua_ns,lua_min,lua_max,pygame_ns,pygame_min,pygame_max,c_ns,reference_ns\n")
local keys = {}
for _, row in ipairs(rounds.lua[1]) do keys[#keys + 1] = row[1] .. " " .. row[2] end
local worst_ratio, met = 0, true
for _, key in ipairs(keys) do
  local l, p, cc = L[key], P[key], c[key] or {}
  local case, call = key:match("^(%S+) (%S+)$")
  local ratio = p and l.med / p.med
  if ratio then worst_ratio = math.max(worst_ratio, ratio); if ratio > 0.7 then met = false end end
  print(("%-24s %-13s %10.0f %10.0f-%-10.0f %10s %10s %8s %12s"):format(case, call, l.med, l.lo, l.hi,
    p and ("%.0f"):format(p.med) or "-", cc[1] and ("%.0f"):format(cc[1]) or "-",
    cc[2] and ("%.0f"):format(cc[2]) or "-", ratio and ("%.2f"):format(ratio) or "-"))
  csv:write(("%s,%s,%.1f,%.1f,%.1f,%s,%s,%s,%s,%s\n"):format(case, call, l.med, l.lo, l.hi,
    p and p.med or "", p and p.lo or "", p and p.hi or "", cc[1] or "", cc[2] or ""))
end
csv:close()
if py then
  print(("worst Lua/pygame ratio %.2f: target (<= 0.7 everywhere) %s"):format(worst_ratio, met and "met" or "NOT met"))
else
  local area, worst = L["random-1024-unaligned overlap_area"].med, L["worst-1024 overlap"].med
  print(("pygame absent (as root, make bench installs python3-pygame): 1024² area %.1f us (<= 9), worst case %.1f us (<= 12)")
    :format(area / 1e3, worst / 1e3))
end
