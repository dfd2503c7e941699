extends "res://checks.gd"
# PhysPixWorld2D in the editor (Engine.editor_hint, as the editor sets it): nothing steps, and with debug_draw on
# the overlay outlines the PhysPixBody2D nodes as placed: a crate's four edges at its node's corners, following the
# node when it is moved or turned (the same body), remade when its texture changes, gone when the node goes, and
# the whole editor world gone when debug_draw is switched off.
# Runs over idle frames (_idle); prints "RESULT: PASS" and quits 0 only if every check holds.

const World2D = preload("res://addons/physpix/physpix_world_2d.gd")

var frame = 0
var world
var terrain
var crate
var crate_body = 0


func body(name, tex, at, options = {}):
	return add_body(world, name, tex, at, options)


# The outline segments (kind 1) of a body of the editor's world.
func outline(b):
	var out = []
	for s in world.debug_segments:
		if s["kind"] == 1 and s["body"] == b:
			out.append(s)
	return out


# Whether the outline's ends are the corners of a w × h box centred on the node, turned with it (0.01 px).
func outlines_box(segments, node, w, h):
	if segments.size() != 4:
		return false
	var corners = []
	for c in [Vector2(-w, -h), Vector2(w, -h), Vector2(w, h), Vector2(-w, h)]:
		corners.append(node.transform.xform(c / 2))
	for s in segments:
		for end in [s["a"], s["b"]]:
			var found = false
			for c in corners:
				found = found or end.distance_to(c) < 0.01
			if not found:
				return false
	return true


func _initialize():
	Engine.editor_hint = true
	world = World2D.new()
	world.position = Vector2(300, 200)  # bodies are drawn in the world node's frame
	world.debug_draw = true
	world.debug_flags = 1 | 16  # outlines and centres
	root.add_child(world)
	terrain = body("Terrain", texture(200, 60), Vector2(100, 170), {"body_type": "static"})
	crate = body("Crate", texture(16, 16), Vector2(100, 40), {"rotation": 0.3})


func _idle(_delta):
	frame += 1
	if frame == 3:
		check(crate.body == 0 and terrain.body == 0, "in the editor a body node makes no body of its own")
		check(world._editor_bodies.size() == 2, "the editor's world holds the two body nodes' bodies")
		crate_body = world._editor_bodies[crate.get_instance_id()][0]
		check(outlines_box(outline(crate_body), crate, 16, 16),
			"the crate's outline: its 4 edges at its node's corners, turned 0.3 rad: %s" % [outline(crate_body)])
		check(outlines_box(outline(world._editor_bodies[terrain.get_instance_id()][0]), terrain, 200, 60), "the terrain's 4 edges")
		crate.position = Vector2(60, 90)
		crate.rotation = -0.5
	if frame == 6:
		check(crate.position == Vector2(60, 90) and world.world.get_time() == 0.0,
			"nothing steps: the crate stays where it was put and the world's clock at 0")
		check(world._editor_bodies[crate.get_instance_id()][0] == crate_body, "a moved node keeps its body")
		check(outlines_box(outline(crate_body), crate, 16, 16), "the outline follows the moved, turned node")
		crate.texture = texture(32, 8)
	if frame == 9:
		var remade = world._editor_bodies[crate.get_instance_id()][0]
		check(remade != crate_body and outline(crate_body).empty(), "a new texture remakes the body")
		check(outlines_box(outline(remade), crate, 32, 8), "the remade body is 32 × 8")
		crate_body = remade
		world.remove_child(crate)
		crate.free()
	if frame == 12:
		check(world._editor_bodies.size() == 1 and outline(crate_body).empty(), "a removed node's body goes")
		world.debug_draw = false
	if frame == 15:
		check(world.debug_segments.empty() and world.world == null and world._editor_bodies.empty(),
			"debug_draw off: the overlay and the editor's world are gone")
		Engine.editor_hint = false
		finish()
	if frame > 30:
		quit(1)
