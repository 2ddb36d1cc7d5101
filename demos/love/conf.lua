-- demos/love/conf.lua — LÖVE's settings for the tether demo.
function love.conf(t)
  t.identity = "tether-demo"
  t.window.title = "tether in LÖVE: grains, a cloth and a rope (drag with the mouse)"
  t.window.width, t.window.height = 960, 600
  t.modules.audio, t.modules.sound, t.modules.joystick = false, false, false
end
