extends Node2D
# The example's game: a blast erases every body's pixels in a circle and throws the dynamic bodies near it
# outward. Blasts come from the timer (the BLASTS points in turn, so the scene runs unattended) and where
# the left mouse button clicks.

signal exploded(at)

const BLASTS = [Vector2(200, 345), Vector2(480, 334), Vector2(760, 345), Vector2(300, 352), Vector2(640, 352),
	Vector2(110, 352), Vector2(860, 352), Vector2(480, 470)]

export var blast_radius = 36.0  # px
export var blast_speed = 420.0  # px/s given to a body at the blast's centre, falling to 0 at 3 radii

var blasts = 0
var _flashes = []  # [centre, radius, age s]

onready var world = $World


func _ready():
	$Timer.connect("timeout", self, "_on_timer")


func _unhandled_input(event):
	if event is InputEventMouseButton and event.pressed and event.button_index == BUTTON_LEFT:
		explode(get_global_mouse_position(), blast_radius)


func _on_timer():
	explode(BLASTS[blasts % BLASTS.size()], blast_radius)
	# Pieces thrown off the screen would fall for ever: freeing a node destroys its body.
	for node in world.get_children():
		if node.global_position.y > 2000:
			node.queue_free()


func explode(at, radius):
	blasts += 1
	world.erase_circle(at, radius)
	var reach = radius * 3.0
	for b in world.get_world().query_circle(world.to_local(at), reach):
		var node = world.node_of(b)
		if node != null and node.body_type == "dynamic":
			var away = node.global_position - at
			var speed = blast_speed * (1.0 - min(away.length() / reach, 1.0))
			node.apply_impulse(away.normalized() * speed * node.get_mass())
	_flashes.append([at, radius, 0.0])
	emit_signal("exploded", at)


func _process(delta):
	for f in _flashes:
		f[2] += delta
	while not _flashes.empty() and _flashes[0][2] > 0.4:
		_flashes.pop_front()
	update()


# Drawn over the world (which shows behind this node): each blast a fading disc.
func _draw():
	for f in _flashes:
		var t = f[2] / 0.4
		draw_circle(f[0], f[1] * (1.0 + t), Color(1.0, 0.85, 0.4, 0.8 * (1.0 - t)))
