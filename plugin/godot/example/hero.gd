extends "res://addons/physpix/physpix_character_2d.gd"
# The example's hero, a PhysPixCharacter2D: the left and right arrows walk, up (or space) jumps from the ground, and
# down blasts the ground under its feet (the blast signal; main.gd's explode makes the crater and the push).

signal blast(at, radius)

export var walk_speed = 150.0  # px/s
export var jump_speed = 420.0  # px/s, up
export var blast_radius = 24.0  # px: the crater under its feet

var velocity = Vector2()  # px/s, what the last move left
var _down_held = false  # a blast each press, not each frame


func _physics_process(delta):
	velocity.x = (Input.get_action_strength("ui_right") - Input.get_action_strength("ui_left")) * walk_speed
	if is_grounded():
		velocity.y = min(velocity.y, 0.0)  # the ground took the fall; a jump's rise is kept
		if Input.is_action_pressed("ui_up") or Input.is_action_pressed("ui_accept"):
			velocity.y = -jump_speed
	velocity = move(velocity + get_node(world).gravity * delta, delta)
	var down = Input.is_action_pressed("ui_down")
	if down and not _down_held:
		emit_signal("blast", global_position + Vector2(0, half_height + radius), blast_radius)
	_down_held = down
