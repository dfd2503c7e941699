extends "res://checks.gd"
# The addon's nodes in a scene built here: a PhysPixWorld2D with a static terrain, a crate, a bar, a pebble and
# a sensor as PhysPixBody2D nodes. The crate falls through the sensor and rests (its node follows its body),
# an erase carves the terrain's texture and the crate falls into the hole, a cut bar adds a sibling node drawn
# with the piece's pixels, the pebble erased whole is destroyed, a lamp hung from the terrain by a hinge drops
# when the erase takes the hinge's pixel (joint_broken), and the signals carry the nodes.
# Runs over physics frames (_iteration); prints "RESULT: PASS" and quits 0 only if every check holds,
# and quits 1 if the frames run out first.

const World2D = preload("res://addons/physpix/physpix_world_2d.gd")
const Body2D = preload("res://addons/physpix/physpix_body_2d.gd")

var frame = 0
var world
var terrain
var crate
var bar
var pebble
var sensor
var lamp
var events = []  # [signal name, args...]
var rest_y = 0.0
var moved_world  # a second world, its node moved to (1000, 500): bodies and calls in its frame
var moved_crate
var pebble_at


func body(name, tex, at, options = {}):
	return add_body(world, name, tex, at, options)


func alpha_at(tex, x, y):
	var img = tex.get_data()
	img.lock()
	var a = img.get_pixel(x, y).a
	img.unlock()
	return a


func seen(what):
	var found = []
	for e in events:
		if e[0] == what:
			found.append(e)
	return found


func _initialize():
	world = World2D.new()
	world.preset = "fast"
	world.substeps = 2
	world.contact_events = true
	world.backend = "cpu"
	world.connect("body_split", self, "_on_split")
	world.connect("body_destroyed", self, "_on_destroyed")
	world.connect("contact_begin", self, "_on_contact_begin")
	world.connect("sensor_begin", self, "_on_sensor_begin")
	world.connect("joint_broken", self, "_on_joint_broken")
	root.add_child(world)
	terrain = body("Terrain", texture(200, 60, Color(0.5, 0.3, 0.1)), Vector2(100, 170), {"body_type": "static"})
	crate = body("Crate", texture(16, 16, Color(0.8, 0.6, 0.2)), Vector2(100, 40), {"density": 2.0})
	bar = body("Bar", texture(60, 6, Color(0.3, 0.3, 0.8)), Vector2(40, 130))
	pebble = body("Pebble", texture(4, 4, Color(1, 1, 1)), Vector2(180, 136))
	sensor = body("Sensor", texture(40, 4, Color(0, 1, 0, 0.5)), Vector2(100, 90),
		{"body_type": "static", "is_sensor": true, "alpha_threshold": 100})
	lamp = body("Lamp", texture(6, 6, Color(1, 1, 0)), Vector2(150, 210))  # under the terrain (bottom at 200)
	var hinge = world.world.create_joint({"type": "revolute", "body_a": terrain.body, "body_b": lamp.body,
		"anchor_a": Vector2(150, 199)})
	check(hinge != null, "the lamp hangs from a terrain pixel: %s" % world.world.get_last_error())
	moved_world = World2D.new()
	moved_world.position = Vector2(1000, 500)
	root.add_child(moved_world)
	var ground = Body2D.new()
	ground.texture = texture(100, 20, Color(1, 1, 1))
	ground.position = Vector2(0, 110)  # top at 100 in its world, 600 on screen
	ground.body_type = "static"
	moved_world.add_child(ground)
	moved_crate = Body2D.new()
	moved_crate.texture = texture(10, 10, Color(1, 1, 1))
	moved_crate.position = Vector2(0, 60)
	moved_world.add_child(moved_crate)
	check(terrain.body != 0 and crate.body != 0 and bar.body != 0 and sensor.body != 0,
		"the nodes made their bodies when ready")
	var st = world.world.get_settings()
	check(st["substeps"] == 2 and st["solver_iterations"] == 10 and st["backend"] == "cpu" and st["contact_events"],
		"the world's exported settings reached its world: %s" % [st])
	check(world.world.get_mass(crate.body) == 512.0, "the crate's density 2 × 256 pixels: %s" % world.world.get_mass(crate.body))


func _on_split(parent, piece):
	events.append(["body_split", parent, piece])


func _on_destroyed(node):
	events.append(["body_destroyed", node])


func _on_contact_begin(a, b, point, normal, speed):
	events.append(["contact_begin", a, b, point, normal, speed])


func _on_sensor_begin(s, b):
	events.append(["sensor_begin", s, b])


func _on_joint_broken(a, b):
	events.append(["joint_broken", a, b])


func _iteration(delta):
	frame += 1
	if frame == 85:
		world.debug_draw = true
	if frame == 89:
		var edges = []
		for s in world.debug_segments:
			if s["kind"] == 1 and s["body"] == crate.body:
				edges.append(s)
		check(edges.size() == 4, "debug_draw: the resting 16×16 crate's outline is its 4 edges: %s" % [edges])
		var overlay = world.get_node("PhysPixDebugOverlay")
		check(overlay != null and overlay.get_index() == world.get_child_count() - 1,
			"the overlay is the world's last child, drawn above the bodies")
		world.debug_draw = false
	if frame == 90:
		check(world.debug_segments.empty(), "debug_draw off: the overlay is cleared")
		rest_y = crate.position.y
		var p = world.world.get_position(crate.body)
		check(near(rest_y, 140 - 8, 1.5), "the crate rests on the terrain: y %.2f ≈ 132" % rest_y)
		check(crate.position.distance_to(p) < 1e-3, "its node is at its body's position %s" % p)
		var landed = false
		for e in seen("contact_begin"):
			landed = landed or (e[1] == crate and e[2] == terrain) or (e[1] == terrain and e[2] == crate)
		check(landed, "contact_begin(crate, terrain) as nodes: %d contact_begin signals" % seen("contact_begin").size())
		var sensed = seen("sensor_begin")
		check(sensed.size() >= 1 and sensed[0][1] == sensor and sensed[0][2] == crate,
			"sensor_begin(sensor, crate): %s" % [sensed])
		var hit = world.raycast(Vector2(150, 0), Vector2(150, 300))
		check(hit != null and hit["body"] == terrain and near(hit["point"].y, 140, 0.5),
			"world.raycast gives the terrain node at y 140: %s" % [hit])
		check(moved_crate.global_position.distance_to(Vector2(1000, 595)) < 1.5
			and moved_world.raycast(Vector2(1020, 0), Vector2(1020, 1000))["point"].distance_to(Vector2(1020, 600)) < 0.5,
			"in a world node moved to (1000, 500) the crate rests at global %s and a global ray meets the ground at y 600"
			% moved_crate.global_position)
		crate.friction = 0.3
		check(near(world.world.get_friction(crate.body), 0.3, 1e-6), "a node property reaches its body")

		# Carve the terrain under the crate: its texture shows the hole at once, the shared resource is untouched.
		var shared = terrain.texture
		var erased = terrain.erase_circle(Vector2(100, 140), 20)
		check(erased > 500, "terrain.erase_circle erased %d pixels" % erased)
		check(terrain.texture != shared and alpha_at(terrain.texture, 100, 5) == 0.0
			and alpha_at(terrain.texture, 100, 30) == 1.0 and alpha_at(terrain.texture, 10, 5) == 1.0,
			"the terrain's texture shows the hole (transparent at its centre, opaque below and beside it)")
		check(alpha_at(shared, 100, 5) == 1.0, "the texture it started from is unchanged")

		# Cut the bar in two: a sibling node drawn with the piece's pixels, with the bar's settings.
		var cut = bar.erase_circle(bar.global_position, 4)
		var splits = seen("body_split")
		check(cut > 0 and splits.size() == 1 and splits[0][1] == bar, "bar.erase_circle split it: %s" % [splits])
		if splits.size() == 1:
			var piece = splits[0][2]
			var size = world.world.get_size(piece.body)
			check(piece is Body2D and piece.get_parent() == bar.get_parent() and piece.body != 0,
				"the piece is a PhysPixBody2D sibling of the bar: %s" % piece.name)
			check(piece.texture.get_size() == size and alpha_at(piece.texture, 1, 1) == 1.0
				and piece.density == bar.density and piece.global_position.distance_to(world.world.get_position(piece.body)) < 1e-3,
				"drawn with its own %s pixels, at its body, with the bar's density" % size)
			check(alpha_at(bar.texture, 30, 3) == 0.0, "the bar's texture shows the cut")
		# The world's erase reaches the pebble and the terrain under it: one destroyed, the other carved.
		var at = pebble.global_position
		pebble_at = at
		check(world.erase_circle(at, 6) > 16 and alpha_at(terrain.texture, int(at.x), 1) == 0.0,
			"world.erase_circle carved the terrain's texture under the pebble")
		check(seen("body_destroyed").size() == 1 and seen("body_destroyed")[0][1] == pebble,
			"the pebble erased whole: body_destroyed(pebble) %s" % [seen("body_destroyed")])
		check(near(lamp.position.y, 210, 0.5) and seen("joint_broken").empty(), "the lamp hangs still: y %.2f" % lamp.position.y)
		world.erase_circle(Vector2(150, 199), 4)
		check(seen("joint_broken") == [["joint_broken", terrain, lamp]],
			"erasing the hinge's pixel: joint_broken(terrain, lamp) %s" % [seen("joint_broken")])
	if frame == 91:
		check(not is_instance_valid(pebble), "the destroyed pebble's node is freed")
		var filled = world.paint_circle(Vector2(pebble_at.x, 142), 3)  # inside the terrain's bitmap (top at 140)
		check(filled > 0 and alpha_at(terrain.texture, int(pebble_at.x), 2) == 1.0,
			"world.paint_circle filled %s pixels of the terrain back, drawn at once" % filled)
		var n = world.world.get_bodies().size()
		sensor.free()
		check(world.world.get_bodies().size() == n - 1, "freeing a node destroys its body")
	if frame == 150:
		check(crate.position.y > rest_y + 10, "the crate fell into the hole: y %.2f > %.2f + 10" % [crate.position.y, rest_y])
		check(lamp.position.y > 250, "the lamp fell: y %.2f" % lamp.position.y)
		finish()
	if frame > 200:
		print("RESULT: FAIL (ran out of frames)")
		quit(1)
