extends "res://checks.gd"
# The PhysPixCharacter2D node in a PhysPixWorld2D moved to (1000, 500): a game loop walks it along a flat static
# terrain, grounded at a constant height, speed × time in 2 s; it reports the terrain's node and normal. A wall
# takes the velocity into it, and bad settings are the library's errors (get_last_error names the field).

const World2D = preload("res://addons/physpix/physpix_world_2d.gd")
const Character2D = preload("res://addons/physpix/physpix_character_2d.gd")
const SPEED = 150.0  # px/s
const G = 980.0
const FRAMES = 120

var frame = 0
var world
var terrain
var wall
var hero
var start
var velocity = Vector2()
var heights = []
var grounded_frames = 0


func _initialize():
	world = World2D.new()
	world.position = Vector2(1000, 500)  # the character's global position is not the world's frame
	world.backend = "cpu"
	root.add_child(world)
	terrain = add_body(world, "Terrain", texture(600, 40), Vector2(300, 220), {"body_type": "static"})  # top y = 200
	wall = add_body(world, "Wall", texture(20, 100), Vector2(560, 150), {"body_type": "static"})  # left face x = 550
	hero = Character2D.new()
	hero.name = "Hero"
	hero.radius = 6.0
	hero.half_height = 10.0
	hero.position = Vector2(40, 200 - 16 - 0.01)  # its foot radius + half_height below its origin
	world.add_child(hero)
	start = hero.global_position
	check(start.distance_to(Vector2(1040, 683.99)) < 1e-3, "the character starts on the terrain, global %s" % start)


func _iteration(delta):
	frame += 1
	if frame <= FRAMES:
		velocity = hero.move(Vector2(SPEED, velocity.y + G * delta), delta)
		if hero.is_grounded():
			grounded_frames += 1
			velocity.y = 0.0
			heights.append(hero.global_position.y)
	if frame == FRAMES:
		check(grounded_frames == FRAMES, "grounded every frame: %d of %d" % [grounded_frames, FRAMES])
		heights.sort()
		check(heights[-1] - heights[0] <= 0.5 and near(heights[0], start.y, 0.5),
			"at a constant height: %.3f..%.3f, started at %.3f" % [heights[0], heights[-1], start.y])
		var walked = hero.global_position.x - start.x
		check(near(walked, SPEED * FRAMES * delta, 0.02 * SPEED * FRAMES * delta),
			"walked %.2f px in %d frames at %.0f px/s" % [walked, FRAMES, SPEED])
		check(hero.get_ground_body() == terrain and hero.get_ground_normal().distance_to(Vector2(0, -1)) < 1e-3
			and hero.get_ground_velocity() == Vector2(), "on the terrain's node, normal %s, ground velocity %s"
			% [hero.get_ground_normal(), hero.get_ground_velocity()])
	if frame == FRAMES + 1:
		# Toward the wall at 1000 px/s for 0.5 s: it stops touching it, the velocity into it taken away.
		var left = hero.move(Vector2(1000, 0), 0.5)
		var x = hero.global_position.x - world.position.x
		check(near(x, 550 - 6, 0.5) and abs(left.x) < 1e-3, "stopped at the wall: x %.3f, velocity %s" % [x, left])
		var at = hero.global_position
		hero.radius = 0.0
		var kept = hero.move(Vector2(10, 0), delta)
		check(kept == Vector2(10, 0) and hero.global_position == at
			and world.world.get_last_error().find("def->radius must be > 0") >= 0,
			"radius 0 refused, the character left where it was: %s" % world.world.get_last_error())
		check(world.world.move_character(Vector2(), Vector2(), delta, {"radiu": 3.0}) == null
			and world.world.get_last_error().find("\"radiu\", which is no character field") >= 0,
			"an unknown key refused: %s" % world.world.get_last_error())
		finish()
	if frame > FRAMES + 10:
		quit(1)
