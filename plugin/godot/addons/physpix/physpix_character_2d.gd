tool
extends Node2D
class_name PhysPixCharacter2D
# A character the game moves, not a body: a capsule (two discs of radius, their centres half_height above and below
# the node's origin) that move() takes through its PhysPixWorld2D's pixels each frame, sliding along them, climbing
# steps up to step_height and keeping to the ground (pp_world_move_character). Bodies do not push it, nor it them;
# nothing in the world changes. Draws its capsule in color (transparent: nothing).

export(NodePath) var world = NodePath("..")  # the PhysPixWorld2D it moves in; by default its parent
export var radius = 8.0 setget set_radius  # px, > 0
export var half_height = 8.0 setget set_half_height  # px, >= 0; 0: one disc
export var step_height = 4.0  # px: a ledge up to this high is climbed while walking along the ground
export var snap_distance = 4.0  # px: a grounded character walking on keeps to ground within this below it
export(float, 0.0, 1.5708) var max_slope = 0.8  # rad: steeper ground is a wall to slide down
export var mask_bits = 0xffffffff  # the bodies whose category_bits meet it block it (sensors never)
export var color = Color(0.9, 0.3, 0.2, 1.0) setget set_color

var _last = null  # the last move's result in global terms: grounded, ground_normal, ground_velocity, ground_body


func set_radius(v):
	radius = v
	update()


func set_half_height(v):
	half_height = v
	update()


func set_color(v):
	color = v
	update()


func _world_node():
	var n = get_node_or_null(world)
	if n == null or not n.has_method("_drain_events"):
		push_error("PhysPixCharacter2D %s: world (%s) is not a PhysPixWorld2D" % [name, world])
		return null
	return n


# Moves the node by velocity (global, px/s) over delta (s) as far as the pixels let it; returns the velocity left (the
# part the surfaces met took away is gone), global px/s. On failure it stays and returns velocity.
func move(velocity, delta):
	var w = _world_node()
	if w == null:
		return velocity
	var frame = w.global_transform
	var def = {"radius": radius, "half_height": half_height, "step_height": step_height,
		"snap_distance": snap_distance, "max_slope": max_slope, "mask_bits": mask_bits}
	var m = w.get_world().move_character(w.to_local(global_position), frame.basis_xform_inv(velocity), delta, def)
	if m == null:
		push_error("PhysPixCharacter2D %s: %s" % [name, w.world.get_last_error()])
		return velocity
	global_position = w.to_global(m["position"])
	_last = {"grounded": m["grounded"], "ground_normal": frame.basis_xform(m["ground_normal"]).normalized(),
		"ground_velocity": frame.basis_xform(m["ground_velocity"]), "ground_body": w.node_of(m["ground_body"])}
	return frame.basis_xform(m["velocity"])


# Whether the last move ended on ground no steeper than max_slope.
func is_grounded():
	return _last != null and _last["grounded"]


# The unit normal out of the ground the last move ended on (global); Vector2() when not grounded.
func get_ground_normal():
	return _last["ground_normal"] if _last != null else Vector2()


# The velocity of the ground under the character (global, px/s): a moving platform's; Vector2() when not grounded.
func get_ground_velocity():
	return _last["ground_velocity"] if _last != null else Vector2()


# The PhysPixBody2D the last move ended on, or null (not grounded, or a body without a node).
func get_ground_body():
	return _last["ground_body"] if _last != null else null


func _draw():
	if color.a <= 0.0:
		return
	draw_circle(Vector2(0, -half_height), radius, color)
	draw_circle(Vector2(0, half_height), radius, color)
	draw_rect(Rect2(-radius, -half_height, 2 * radius, 2 * half_height), color)
