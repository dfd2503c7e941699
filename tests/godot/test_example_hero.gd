extends "res://checks.gd"
# The example's hero (plugin/godot/example/hero.gd) played by scripted input, the timer's blasts stopped: it walks
# right for 40 frames (150 px/s: 100 px), jumps and lands, then blasts the ground under its feet and ends grounded on
# the crater's floor, below where it started. run.sh also fails on any ERROR line.

const WALK = 40
const FRAMES = 240

var frame = 0
var main
var hero
var start
var jumped_at = -1  # the frame the jump left the ground
var peak = 0.0  # the highest it rose above the ground, px
var landed_at = -1
var blasted_at = -1
var exploded = []


func _initialize():
	main = load("res://main.tscn").instance()
	root.add_child(main)
	main.get_node("Timer").stop()
	main.connect("exploded", self, "_on_exploded")
	hero = main.get_node("World/Hero")
	start = hero.global_position


func _on_exploded(at):
	exploded.append(at)


func press(action, down):
	if down:
		Input.action_press(action)
	else:
		Input.action_release(action)


# Runs before the nodes' _physics_process of the same frame: the input is what the hero reads.
func _iteration(delta):
	frame += 1
	press("ui_right", frame <= WALK)
	press("ui_up", frame == WALK + 1)
	if frame == WALK:
		check(hero.is_grounded() and near(hero.global_position.y, start.y, 0.5)
			and near(hero.global_position.x - start.x, 150.0 * (WALK - 1) / 60.0, 3.0),
			"walked grounded from %s to %s" % [start, hero.global_position])
	if frame > WALK + 1 and jumped_at < 0 and not hero.is_grounded():
		jumped_at = frame
	if jumped_at > 0 and landed_at < 0:
		peak = max(peak, start.y - hero.global_position.y)
		if hero.is_grounded():
			landed_at = frame
			check(peak > 60 and near(hero.global_position.y, start.y, 0.5),
				"jumped %.1f px high and landed at y %.2f (ground %.2f) after %d frames"
				% [peak, hero.global_position.y, start.y, landed_at - jumped_at])
	if landed_at > 0 and blasted_at < 0 and frame > landed_at + 5:
		blasted_at = frame
		press("ui_down", true)
	if frame == blasted_at + 1:
		press("ui_down", false)
	if frame == FRAMES:
		var at = hero.global_position
		var floor_y = hero.global_position.y + hero.half_height + hero.radius
		check(exploded.size() == 1 and exploded[0].distance_to(Vector2(start.x + 100, 340)) < 6,
			"one blast, under its feet on the old ground: %s" % [exploded])
		check(hero.is_grounded() and at.y > start.y + 10 and near(at.x, exploded[0].x, 6) if exploded.size() == 1
			else false, "grounded in the crater at %s, %.1f px below where it started; its foot at y %.1f"
			% [at, at.y - start.y, floor_y])
		finish()
	if frame > FRAMES + 10:
		quit(1)
