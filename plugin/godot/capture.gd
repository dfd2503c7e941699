extends SceneTree
# Renders the example (make godot-pictures runs it in the real Godot 3.2 under Xvfb) and saves the viewport
# at the start and after each of the first three blasts to the folder given after `--`.

# Blasts come at frames 90, 180 and 270; 94 shows the first one's flash.
const SHOTS = {20: "example-start.png", 94: "example-blast1.png", 240: "example-blast2.png", 330: "example-blast3.png"}

var frame = 0
var folder = "."


func _initialize():
	var args = OS.get_cmdline_args()
	if args.size() > 0:
		folder = args[args.size() - 1]
	root.add_child(load("res://main.tscn").instance())


# After the frame's drawing: the viewport's texture holds what is on screen (upside down in GLES2).
func _idle(delta):
	frame += 1
	if SHOTS.has(frame):
		var shot = root.get_texture().get_data()
		shot.flip_y()
		var path = folder + "/" + SHOTS[frame]
		print("saved %s: %s" % [path, shot.save_png(path) == OK])
	if frame >= 330:
		quit(0)
