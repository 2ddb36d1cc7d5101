-- bench/love/conf.lua — the pour benchmark needs no window: physics and the
-- timer only, so it runs without a display.
function love.conf(t)
  t.identity = "tether-bench"
  t.window = false
  t.modules.window, t.modules.graphics, t.modules.audio, t.modules.sound = false, false, false, false
  t.modules.joystick, t.modules.mouse, t.modules.keyboard, t.modules.touch = false, false, false, false
end
