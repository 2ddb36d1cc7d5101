-- tests/love/conf.lua — LÖVE's settings for the test game: a small window,
-- no audio (Xvfb machines have no sound device), no vsync (frames as fast
-- as they come).
function love.conf(t)
  t.identity = "tether-love-test"
  t.window.title = "tether under LÖVE (test)"
  t.window.width, t.window.height = 320, 240
  t.window.vsync = 0
  t.modules.audio, t.modules.sound, t.modules.joystick = false, false, false
end
