extends Node2D
class_name PhysPixJoint2D
# A PhysPix joint between two PhysPixBody2D nodes (node_a empty: the static world), made in a scene.
# The anchors and the axis are in this node's own frame, so by default the joint sits at the node's position.
# It makes its joint as soon as it is in the tree and both bodies have theirs (bodies make theirs when ready, which
# may be after this node): at the latest just before their world's next step, which first asks every pending
# joint node. It destroys the joint when it leaves the tree, and makes a new one if it comes back. The node
# itself does not move with the bodies.

signal broken  # the joint broke: its reaction passed break_force, or an erase took its anchor's pixels

const PENDING = "physpix_pending_joints"  # the group of joint nodes waiting for their bodies

export(NodePath) var node_a = NodePath()  # a PhysPixBody2D, or empty for the static world
export(NodePath) var node_b = NodePath()  # a PhysPixBody2D
export(String, "revolute", "prismatic", "distance", "weld", "mouse", "wheel", "motor") var joint_type = "revolute"
export var anchor_a = Vector2()  # in this node's frame; REVOLUTE, WELD and MOUSE use anchor_a alone
export var anchor_b = Vector2()  # in this node's frame (PRISMATIC, DISTANCE)
export var axis = Vector2(1, 0)  # PRISMATIC: the slide direction, in this node's frame
export var collide_connected = false
export var enable_limit = false setget set_enable_limit  # REVOLUTE, PRISMATIC, WHEEL (its slide): lower..upper hold
export var lower = 0.0 setget set_lower  # rad or px
export var upper = 0.0 setget set_upper
export var enable_motor = false setget set_enable_motor  # REVOLUTE, PRISMATIC, WHEEL (its spin), DISTANCE (its length)
export var motor_speed = 0.0 setget set_motor_speed  # rad/s or px/s, b relative to a
export var max_motor_force = 0.0 setget set_max_motor_force  # mass·px/s², or a torque mass·px²/s² for REVOLUTE, WHEEL
export var min_length = 0.0 setget set_min_length  # DISTANCE, px; 0 and 0 keep the creation length rigid
export var max_length = 0.0 setget set_max_length  # DISTANCE, px; a rope has min 0
export var spring_hertz = -1.0  # DISTANCE, WELD, MOUSE: Hz, 0 rigid; < 0 the type's default (0; MOUSE 5)
export var spring_damping_ratio = -1.0  # < 0 the type's default (0; MOUSE 0.7)
export var max_force = 0.0  # MOUSE: the largest pull, mass·px/s²; 0 no cap
export var break_force = 0.0  # mass·px/s²; 0 never breaks

var joint = 0  # the native joint int; 0 before it is made, after it is destroyed or broke
var world_node = null  # the PhysPixWorld2D of its bodies


func _enter_tree():
	add_to_group(PENDING)
	_try_make(true)


func _ready():
	_try_make(true)


func _exit_tree():
	if is_in_group(PENDING):
		remove_from_group(PENDING)
	destroy()


# Makes the joint if both bodies have theirs; otherwise it stays pending. The world calls this with
# quiet false before each step: a node_a or node_b that is then no PhysPixBody2D is an error, and it gives up.
func _try_make(quiet):
	if not is_in_group(PENDING) or not is_inside_tree():
		return
	var a = get_node_or_null(node_a) if not node_a.is_empty() else null
	var b = get_node_or_null(node_b)
	var missing = ""
	if b == null or not b.has_method("_copy_settings"):
		missing = "node_b (%s)" % node_b
	elif not node_a.is_empty() and (a == null or not a.has_method("_copy_settings")):
		missing = "node_a (%s)" % node_a
	if missing != "":
		if not quiet:
			push_error("PhysPixJoint2D %s: %s is not a PhysPixBody2D" % [name, missing])
			remove_from_group(PENDING)
		return
	if b.body == 0 or (a != null and a.body == 0):
		return  # a body not made yet
	remove_from_group(PENDING)
	if a != null and a.world_node != b.world_node:
		push_error("PhysPixJoint2D %s: node_a and node_b are in different PhysPixWorld2D nodes" % name)
		return
	world_node = b.world_node
	var frame = world_node.global_transform.affine_inverse() * global_transform  # this node in the world's frame
	var def = {"type": joint_type, "body_a": a.body if a != null else 0, "body_b": b.body,
		"anchor_a": frame.xform(anchor_a), "anchor_b": frame.xform(anchor_b), "axis": frame.basis_xform(axis),
		"collide_connected": collide_connected, "enable_limit": enable_limit, "lower": lower, "upper": upper,
		"enable_motor": enable_motor, "motor_speed": motor_speed, "max_motor_force": max_motor_force,
		"min_length": min_length, "max_length": max_length, "max_force": max_force, "break_force": break_force}
	if spring_hertz >= 0:
		def["spring_hertz"] = spring_hertz
	if spring_damping_ratio >= 0:
		def["spring_damping_ratio"] = spring_damping_ratio
	var w = world_node.get_world()
	var j = w.create_joint(def)
	if j == null:
		push_error("PhysPixJoint2D %s: %s" % [name, w.get_last_error()])
		return
	joint = j
	world_node._register_joint(self)


# Destroys the joint now (leaving the tree does this too).
func destroy():
	if is_joined():
		world_node._unregister_joint(self)
		world_node.world.destroy_joint(joint)
	joint = 0


# Whether the joint exists: false before it is made and after it broke, was destroyed or lost a body.
func is_joined():
	if joint != 0 and is_instance_valid(world_node) and world_node.world != null \
			and world_node.world.get_joints().has(joint):
		return true
	if joint != 0 and is_instance_valid(world_node):
		world_node._unregister_joint(self)  # gone with one of its bodies
	joint = 0
	return false


# {force: Vector2 (global directions), torque} on node_b's body in the last substep, or null without a joint.
func get_reaction():
	if not is_joined():
		return null
	var r = world_node.world.get_joint_reaction(joint)
	r["force"] = world_node.global_transform.basis_xform(r["force"])
	return r


# {value, speed}: a hinge's angle since creation (rad, rad/s), a slider's translation or a distance (px, px/s);
# null without a joint.
func get_value():
	return world_node.world.get_joint_value(joint) if is_joined() else null


# MOUSE: the global point the grabbed body is pulled toward.
func set_target(point):
	if is_joined():
		world_node.world.set_joint_target(joint, world_node.to_local(point))


# Both at once (setting lower and upper one by one may pass through lower > upper, which is refused).
func set_limits(enabled, lower_value, upper_value):
	enable_limit = enabled
	lower = lower_value
	upper = upper_value
	_send_limits()


func set_motor(enabled, speed, max_force_value):
	enable_motor = enabled
	motor_speed = speed
	max_motor_force = max_force_value
	_send_motor()


# The world calls this when its event says the joint broke.
func _broke():
	joint = 0
	emit_signal("broken")


# ---- settable at run time: motor and limits (REVOLUTE, PRISMATIC), lengths (DISTANCE) ----

func set_enable_motor(v):
	enable_motor = v
	_send_motor()


func set_motor_speed(v):
	motor_speed = v
	_send_motor()


func set_max_motor_force(v):
	max_motor_force = v
	_send_motor()


func set_enable_limit(v):
	enable_limit = v
	_send_limits()


func set_lower(v):
	lower = v
	_send_limits()


func set_upper(v):
	upper = v
	_send_limits()


func set_min_length(v):
	min_length = v
	_send_limits()


func set_max_length(v):
	max_length = v
	_send_limits()


func _send_motor():
	if joint != 0 and joint_type in ["revolute", "prismatic", "wheel", "distance"] and is_joined():
		world_node.world.set_joint_motor(joint, enable_motor, motor_speed, max_motor_force)


func _send_limits():
	if joint == 0 or not is_joined():
		return
	if joint_type in ["revolute", "prismatic", "wheel"]:
		world_node.world.set_joint_limits(joint, enable_limit, lower, upper)
	elif joint_type == "distance":
		world_node.world.set_joint_limits(joint, min_length != 0 or max_length != 0, min_length, max_length)
