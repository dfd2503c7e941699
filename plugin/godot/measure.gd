extends SceneTree
# The example's frame cost (make godot-frame-cost): the scene run in real time for 12 s at 60 physics frames a
# second, a blast each second (its timer stopped, so that each blast is timed here). Prints the percentiles of
# PhysPixWorld2D.last_step_ms (step, signals, node moves) and of a blast (erase, impulses, texture redraw).

const FRAMES = 720

var frame = 0
var main
var world
var costs = []
var blasts = []


func _initialize():
	main = load("res://main.tscn").instance()
	root.add_child(main)
	world = main.get_node("World")
	main.get_node("Timer").stop()


func pct(sorted, q):
	return sorted[int(q * (sorted.size() - 1))]


func _iteration(delta):
	frame += 1
	if frame > 2:
		costs.append(world.last_step_ms)
	if frame % 60 == 30 and frame < FRAMES - 10:
		var start = OS.get_ticks_usec()
		main.explode(main.BLASTS[(frame / 60) % main.BLASTS.size()], main.blast_radius)
		blasts.append((OS.get_ticks_usec() - start) / 1000.0)
	if frame == FRAMES:
		costs.sort()
		blasts.sort()
		print("physics frame: median %.3f ms, 95th percentile %.3f ms, max %.3f ms over %d frames"
			% [pct(costs, 0.5), pct(costs, 0.95), costs[-1], costs.size()])
		print("blast: median %.3f ms, max %.3f ms over %d" % [pct(blasts, 0.5), blasts[-1], blasts.size()])
		quit(0)
