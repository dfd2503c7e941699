extends "res://checks.gd"
# The example scene (plugin/godot/example/main.tscn) run as it ships, its timer's blasts and all: the crates
# come to rest, the first blast carves the terrain's texture and a crate falls into the crater, the second cuts
# the bridge and its piece appears as a PhysPixBody2D node drawn with its pixels. run.sh also fails on any
# ERROR line. Prints the frame cost: the world's step, events and node updates, ms per physics frame.

const Body2D = preload("res://addons/physpix/physpix_body_2d.gd")
const FRAMES = 300  # 5 s: blasts at 1.5, 3 and 4.5 s

var frame = 0
var main
var world
var start = {}  # crate name -> position at the start
var blast_frames = []
var splits = []  # [parent, piece]
var destroyed = []
var costs = []



func crates():
	var found = []
	for n in world.get_children():
		if n is Body2D and n.name.begins_with("Crate") and not n.is_queued_for_deletion():
			found.append(n)
	return found


func alpha_at(image, x, y):
	image.lock()
	var a = image.get_pixel(x, y).a
	image.unlock()
	return a


func opaque_pixels(image):
	var n = 0
	image.lock()
	for y in range(image.get_height()):
		for x in range(image.get_width()):
			if image.get_pixel(x, y).a > 0.5:
				n += 1
	image.unlock()
	return n


func _initialize():
	main = load("res://main.tscn").instance()
	root.add_child(main)
	world = main.get_node("World")
	main.connect("exploded", self, "_on_exploded")
	world.connect("body_split", self, "_on_split")
	world.connect("body_destroyed", self, "_on_destroyed")
	for c in crates():
		start[c.name] = c.position
	check(crates().size() == 8 and world.get_node("Terrain").body != 0 and world.get_node("Bridge").body != 0,
		"the scene's 8 crates, terrain and bridge made their bodies")


func _on_exploded(at):
	blast_frames.append(frame)


func _on_split(parent, piece):
	splits.append([parent, piece])


func _on_destroyed(node):
	destroyed.append(node.name)


func _iteration(delta):
	frame += 1
	if frame > 2:
		costs.append(world.last_step_ms)
	if frame == 85:
		# Resting contacts sit contact_slop (0.75 px) deep: the top of the three-crate stack is 2.25 px down.
		var still = true
		for c in crates():
			still = still and c.get_linear_velocity().length() < 5.0 and c.position.distance_to(start[c.name]) < 2.5
		check(still and blast_frames.empty(), "the crates rest where they stand before the first blast")
	if frame == 92:
		var terrain = world.get_node("Terrain")
		# The blast at (200, 345) is bitmap point (200, 5) of the 960 × 200 terrain centred at (480, 440).
		check(blast_frames.size() == 1 and alpha_at(terrain.texture.get_data(), 200, 5) == 0.0
			and alpha_at(terrain.texture.get_data(), 200, 60) == 1.0, "the first blast carved the terrain's texture")
		check(alpha_at(load("res://terrain.png").get_data(), 200, 5) == 1.0, "and left terrain.png as it was")
	if frame == 175:
		var fell = []
		for c in crates():
			if abs(c.position.x - 200) < 36 and c.position.y > 340:
				fell.append(c.name)
		check(not fell.empty(), "a crate fell into the crater (centre below the old ground, y > 340): %s" % [fell])
	if frame == 186:
		var cut = null
		for s in splits:
			if s[0].name == "Bridge":
				cut = s[1]
		check(cut != null, "the second blast cut the bridge: body_split(Bridge, piece) (%d splits, destroyed %s)"
			% [splits.size(), destroyed])
		if cut != null:
			var size = world.get_world().get_size(cut.body)
			var look = cut.texture.get_data()
			check(cut is Body2D and cut.get_parent() == world and cut.body_type == "dynamic"
				and look.get_size() == size and opaque_pixels(look) > 0.8 * size.x * size.y,
				"the piece %s is a dynamic PhysPixBody2D in the world, drawn with its %s pixels" % [cut.name, size])
	if frame == FRAMES:
		check(blast_frames.size() == 3, "three blasts in 5 s: frames %s" % [blast_frames])
		costs.sort()
		var total = 0.0
		for c in costs:
			total += c
		print("frame cost: median %.3f ms, mean %.3f ms, max %.3f ms per physics frame over %d frames (%d bodies)"
			% [costs[costs.size() / 2], total / costs.size(), costs[-1], costs.size(), world.get_world().get_bodies().size()])
		finish()
	if frame > FRAMES + 10:
		quit(1)
