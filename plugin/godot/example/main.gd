extends Node2D
# The example's game: a blast (PhysPixWorld2D.explode) erases every body's pixels in a circle and throws the
# dynamic bodies near it outward. Blasts come from the timer (the BLASTS points in turn, so the scene runs
# unattended), where the left mouse button clicks, and under the Hero's feet (hero.gd's blast signal).

signal exploded(at)

const BLASTS = [Vector2(200, 345), Vector2(480, 334), Vector2(760, 345), Vector2(300, 352), Vector2(640, 352),
	Vector2(110, 352), Vector2(860, 352), Vector2(480, 470)]

export var blast_radius = 36.0  # px: the crater, and the push at full strength
export var blast_falloff = 72.0  # px past blast_radius over which the push falls to 0
export var blast_impulse_per_length = 6000.0  # mass·px/s per px of a body's extent across the blast

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
	world.explode(at, radius, blast_falloff, blast_impulse_per_length, radius)
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
