tool
extends Node2D
class_name PhysPixWorld2D
# A PhysPix world: PhysPixBody2D nodes under it are its bodies. It steps in _physics_process, moves each
# awake body's node to its pose, and turns PhysPix's events into signals with the nodes they concern.
# Positions given to its methods are global; the world's own frame is this node's.
# In the editor nothing steps; with debug_draw on, the overlay shows the bodies as placed (outlines, boxes,
# centres of mass), made from each PhysPixBody2D's settings and following its node as it is moved.

signal body_split(parent, piece)  # PhysPixBody2D, and the new PhysPixBody2D sibling drawn with its pixels
signal body_destroyed(body)  # PhysPixBody2D left without pixels; it is freed after the signal
signal contact_begin(a, b, point, normal, speed)  # needs contact_events; speed: approach, px/s
signal contact_end(a, b)
signal sensor_begin(sensor, body)
signal sensor_end(sensor, body)
signal joint_broken(a, b)  # a joint between a and b (null: the static world) broke by force or by an erase

# Loaded when first needed, not preloaded: the editor's first scan of a project may parse this script while
# the body script is still loading, and a preload then fails ("possible cyclic reference").
const NATIVE_PATH = "res://addons/physpix/physpix_world.gdns"
const BODY_PATH = "res://addons/physpix/physpix_body_2d.gd"
const JOINTS_PENDING = "physpix_pending_joints"  # PhysPixJoint2D nodes waiting for their bodies (its PENDING)
const EXPLOSION_IMPULSE_PER_LENGTH = 5000.0  # explode's default, mass·px/s per px: PP_EXPLOSION_IMPULSE_PER_LENGTH

export var gravity = Vector2(0, 980) setget set_gravity  # px/s²
export(String, "fast", "balanced", "accurate") var preset = "balanced"
export(int, 0, 64) var substeps = 0  # 0: the preset's
export(int, 0, 1000) var solver_iterations = 0  # 0: the preset's
export(String, "auto", "cpu", "gpu") var backend = "auto"
export var contact_events = false setget set_contact_events
export var settings = {}  # pp_world_def fields by their C names, e.g. {"allow_sleep": false}; they win
export var debug_draw = false  # draw PhysPix's overlay (pp_world_debug_draw) over the bodies, each physics frame
export(int, FLAGS, "outlines", "AABBs", "contacts", "joints", "centres", "velocities") var debug_flags = 63

var world = null  # the native PhysPixWorld, made when the first body or call needs it
var last_step_ms = 0.0  # what the last physics frame cost: step, events and node updates
var _nodes = {}  # body int -> PhysPixBody2D
var _joints = {}  # joint int -> PhysPixJoint2D
var debug_segments = []  # the overlay drawn: {a, b, rgba, kind, body} in this node's frame, px
var _overlay = null  # a child drawn above the bodies (a parent draws below its children)
var _editor_bodies = {}  # in the editor: a PhysPixBody2D node's instance id -> [body int, str() of what made it]


# The native world, created from the exported settings on first use.
func get_world():
	if world == null:
		world = load(NATIVE_PATH).new()
		var def = {"preset": preset, "gravity": gravity, "backend": backend, "contact_events": contact_events}
		if substeps > 0:
			def["substeps"] = substeps
		if solver_iterations > 0:
			def["solver_iterations"] = solver_iterations
		for k in settings:
			def[k] = settings[k]
		if world.create(def) != true:
			push_error("PhysPixWorld2D %s: %s" % [name, world.get_last_error()])
	return world


func set_gravity(g):
	gravity = g
	if world != null:
		world.set_gravity(g)


func set_contact_events(on):
	contact_events = on
	if world != null:
		world.set_contact_events(on)


func _physics_process(delta):
	if Engine.editor_hint:
		return  # the editor shows the scene as placed
	var start = OS.get_ticks_usec()
	# Joint nodes whose bodies are made by now make their joints (REALTIME: call_group alone defers the calls).
	get_tree().call_group_flags(SceneTree.GROUP_CALL_REALTIME, JOINTS_PENDING, "_try_make", false)
	get_world().step(delta)
	_drain_events()
	var frame = global_transform
	for s in world.get_body_states(true):  # sleeping and static bodies stay where they are
		var node = _nodes.get(s["body"])
		if node != null:
			node.global_transform = frame * Transform2D(s["angle"], s["position"])
	_update_overlay()
	last_step_ms = (OS.get_ticks_usec() - start) / 1000.0


func _process(_delta):
	if Engine.editor_hint:
		_editor_overlay()


# What a PhysPixBody2D node's body is made from, read from its properties (in the editor its script does not
# run, but its exported values are there): [bitmap texture, position and options for add_body_image], or null.
func _body_spec(node):
	var source = node.texture if node.texture != null else node.get("collision_mask")
	if source == null:
		return null
	# The node's origin is the body's pivot: where the Sprite draws the texture's point (centre - offset).
	var pivot = (source.get_size() / 2 if node.centered else Vector2()) - node.offset
	var local = global_transform.affine_inverse() * node.global_transform
	var options = {"pivot": pivot, "angle": local.get_rotation()}
	for k in ["density", "friction", "restitution", "fixed_rotation", "is_sensor", "one_way", "detach_islands",
			"alpha_threshold", "linear_velocity", "angular_velocity"]:
		options[k] = node.get(k)
	for k in ["collision_mask", "weights"]:
		if node.get(k) != null:
			options[k] = node.get(k)
	return [source, local.origin, options]


# The PhysPixBody2D nodes under n.
func _body_nodes(n, out = []):
	for c in n.get_children():
		if c.get_script() == load(BODY_PATH):
			out.append(c)
		_body_nodes(c, out)
	return out


# In the editor: each body node's body made once (again when its bitmap, type or shape settings change) and moved
# to its node, then the overlay drawn; nothing steps. Off, the editor's world goes.
func _editor_overlay():
	if not debug_draw:
		if world != null:
			_editor_bodies = {}
			world = null
			_update_overlay()  # clears it
		return
	var w = get_world()
	var seen = {}
	for node in _body_nodes(self):
		var id = node.get_instance_id()  # not the node: a freed node's key reads back as null
		seen[id] = true
		var spec = _body_spec(node)
		var made_from = ""  # the bitmap and settings, not the pose: moving the node moves the body
		if spec != null:
			var settings = spec[2].duplicate()
			settings.erase("angle")
			made_from = str([spec[0], node.get("body_type"), settings])
		var entry = _editor_bodies.get(id)
		if entry != null and entry[1] != made_from:
			w.destroy_body(entry[0])
			entry = null
		if entry == null and spec != null:
			var b = w.add_body_image(spec[0], spec[1], node.get("body_type"), spec[2])
			entry = [b, made_from] if b != null else null
			if entry != null:
				_editor_bodies[id] = entry
		if entry != null:
			var local = global_transform.affine_inverse() * node.global_transform
			w.set_transform(entry[0], local.origin, local.get_rotation())
		elif _editor_bodies.has(id):
			_editor_bodies.erase(id)
	for id in _editor_bodies.keys():
		if not seen.has(id):
			w.destroy_body(_editor_bodies[id][0])
			_editor_bodies.erase(id)
	_update_overlay()


# The debug overlay: segments read after the step, drawn by a child kept last so it lies above every body.
func _update_overlay():
	if not debug_draw and debug_segments.empty():
		return
	debug_segments = world.debug_draw(debug_flags) if debug_draw else []
	if _overlay == null:
		_overlay = Node2D.new()
		_overlay.name = "PhysPixDebugOverlay"
		_overlay.connect("draw", self, "_draw_overlay")
		add_child(_overlay)
	elif _overlay.get_index() != get_child_count() - 1:
		move_child(_overlay, get_child_count() - 1)
	_overlay.update()


func _draw_overlay():
	for s in debug_segments:
		_overlay.draw_line(s["a"], s["b"], Color(s["rgba"]), 1.0)


# Erases the pixels of every body within radius (px) of a global point; returns how many.
func erase_circle(center, radius):
	var at = to_local(center)
	var touched = get_world().query_circle(at, radius)
	var erased = world.world_erase_circle(at, radius)
	_show_erased(touched, at, radius)
	return erased


# After an erase of the circle (world px) from the bodies touched: their nodes draw the crater.
func _show_erased(touched, at, radius):
	_drain_events()  # first: a body erased whole has no pixels left to draw
	for b in touched:
		var node = _nodes.get(b)
		if node != null:
			node._redraw_circle(at, radius)


# A blast at a global point: erases the pixels within erase_radius of it (px) from the bodies whose category meets
# erase_mask, then pushes each dynamic body whose category meets mask with a pixel within radius + falloff (px) by
# impulse_per_length (mass·px/s per px) × its solid extent across the blast, full within radius, falling linearly to
# 0 at radius + falloff. Returns the pixels erased.
func explode(center, radius, falloff = 0.0, impulse_per_length = EXPLOSION_IMPULSE_PER_LENGTH, erase_radius = 0.0,
		mask = 0xffffffff, erase_mask = 0xffffffff):
	var at = to_local(center)
	var touched = get_world().query_circle(at, erase_radius, erase_mask) if erase_radius > 0.0 else []
	var erased = world.explode(at, radius, falloff, impulse_per_length, erase_radius, mask, erase_mask)
	_show_erased(touched, at, erase_radius)
	return erased


# Makes solid, with weight 1..255, the pixels within radius of a global point in every body whose bitmap holds
# the point (a crater's own body, though the circle may reach none of its pixels). Returns how many.
func paint_circle(center, radius, weight = 255):
	var at = to_local(center)
	var painted = 0
	for b in _nodes.keys():
		var local = world.get_transform(b).affine_inverse().xform(at) + world.get_pivot(b)
		if Rect2(Vector2(), world.get_size(b)).has_point(local):
			var n = world.paint_circle(b, at, radius, weight)
			if n != null:
				painted += n
				_nodes[b]._redraw_circle(at, radius)
	return painted


# The nearest solid pixel on the segment between two global points: {body (a node, or null for a body
# without one), point (global), normal, fraction}, or null.
func raycast(from, to, mask_bits = 0xffffffff):
	var hit = get_world().raycast(to_local(from), to_local(to), mask_bits)
	if hit == null:
		return null
	hit["body"] = _nodes.get(hit["body"])
	hit["point"] = to_global(hit["point"])
	hit["normal"] = global_transform.basis_xform(hit["normal"])
	return hit


# The node of a body int, or null.
func node_of(body):
	return _nodes.get(body)


func _register(node):
	_nodes[node.body] = node


func _unregister(node):
	_nodes.erase(node.body)


func _register_joint(node):
	_joints[node.joint] = node


func _unregister_joint(node):
	_joints.erase(node.joint)


# Events become signals; a split adds the piece's node first, a destroyed body's node goes after its signal.
func _drain_events():
	for e in world.get_events():
		var a = _nodes.get(e["body"])
		var b = _nodes.get(e["other"])
		match e["type"]:
			"split":
				if a != null:
					var piece = _add_piece(a, e["other"])
					a._redraw_all()
					emit_signal("body_split", a, piece)
			"destroyed":
				_nodes.erase(e["body"])
				if a != null:
					a.body = 0
					emit_signal("body_destroyed", a)
					a.queue_free()
			"contact_begin":
				emit_signal("contact_begin", a, b, to_global(e["point"]), global_transform.basis_xform(e["normal"]),
					e["approach_speed"])
			"contact_end":
				emit_signal("contact_end", a, b)
			"sensor_begin":
				emit_signal("sensor_begin", a, b)
			"sensor_end":
				emit_signal("sensor_end", a, b)
			"joint_broken":
				var j = _joints.get(e["joint"])
				_joints.erase(e["joint"])
				if j != null and is_instance_valid(j):
					j._broke()
				emit_signal("joint_broken", a, b)


# A sibling of the parent's node for the piece body, with the parent's settings and the piece's own pixels.
func _add_piece(parent, body):
	var piece = load(BODY_PATH).new()
	piece.body = body
	piece.world_node = self
	piece.name = parent.name + "Piece"
	piece._copy_settings(parent)
	piece.body_type = world.get_type(body)
	piece._take_texture(null)
	_nodes[body] = piece
	parent.get_parent().add_child(piece)
	piece.global_transform = global_transform * world.get_transform(body)
	return piece
