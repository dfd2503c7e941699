extends "res://checks.gd"
# PhysPixJoint2D nodes in a scene built here, each made in an order a scene may have: a hinge added before its
# bob (a 10 × 10 box 40 px to its left, level with it) swings the bob down about the anchor at its length; a rope
# (a rigid distance joint) that is a child of its lamp (so it enters the tree before the lamp is ready) holds the
# lamp still at 60 px with its weight as the reaction, and removing the rope's node frees the lamp to fall; the
# hinge taken out and put back makes a new joint, and freed lets the bob fly; a weld whose break_force is half
# its box's weight breaks at once (the node's `broken` signal and the world's joint_broken); a node_b that is no
# body makes nothing; a motor switched on and set at run time drives its hinge, a wheel's spin and a winch's
# length, and limits set at run time hold a wheel's slide. Prints "RESULT: PASS" and quits 0 only if every check holds; quits 1 if frames run out.

const World2D = preload("res://addons/physpix/physpix_world_2d.gd")
const Body2D = preload("res://addons/physpix/physpix_body_2d.gd")
const Joint2D = preload("res://addons/physpix/physpix_joint_2d.gd")

const HINGE_AT = Vector2(140, 100)
const ROPE_TOP = Vector2(300, 50)

var frame = 0
var world
var bob
var hinge
var lamp
var rope
var weak
var weld
var stray
var wheel  # a box on a hinge at its centre, its motor switched on at run time
var spinner  # a box on a wheel joint to the world (vertical slide on a spring), its motor and limits set at run time
var spun  # its box
var winch  # a distance joint from the world to a box, a rope 20..80 px, its motor switched on at run time
var hung  # its box
var worst_length = 0.0  # the bob's largest |distance to the hinge − 40| while it swings
var lowest = 0.0  # the bob's largest y while it swings
var broken = 0  # the weld node's broken signals
var world_broken = []
var first_hinge = 0
var bob_freed_at


func box(name, at):
	var img = Image.new()
	img.create(10, 10, false, Image.FORMAT_RGBA8)
	img.fill(Color(1, 1, 1))
	var t = ImageTexture.new()
	t.create_from_image(img, 0)
	var b = Body2D.new()
	b.name = name
	b.texture = t
	b.position = at
	return b


func joint(name, type, at, b_path, props = {}):
	var j = Joint2D.new()
	j.name = name
	j.joint_type = type
	j.position = at
	j.node_b = b_path
	for k in props:
		j.set(k, props[k])
	return j


func _initialize():
	world = World2D.new()
	world.backend = "cpu"
	world.connect("joint_broken", self, "_on_world_joint_broken")
	root.add_child(world)
	# The hinge first, its bob after it: the bob has no body yet when the hinge enters the tree.
	hinge = joint("Hinge", "revolute", HINGE_AT, NodePath("../Bob"))
	world.add_child(hinge)
	bob = box("Bob", HINGE_AT - Vector2(40, 0))
	world.add_child(bob)
	# The rope is a child of its lamp: it enters the tree before the lamp is ready. Its anchors, in its own
	# frame: the top (its position) and the lamp's top edge 60 px below.
	lamp = box("Lamp", ROPE_TOP + Vector2(0, 65))
	rope = joint("Rope", "distance", ROPE_TOP - lamp.position, NodePath(".."), {"anchor_b": Vector2(0, 60)})
	lamp.add_child(rope)
	world.add_child(lamp)
	weak = box("Weak", Vector2(500, 100))
	world.add_child(weak)
	weld = joint("Weld", "weld", Vector2(500, 95), NodePath("../Weak"), {"break_force": 0.5 * 100 * 980.0})
	weld.connect("broken", self, "_on_weld_broken")
	world.add_child(weld)
	check(weld.joint != 0, "a joint node entering the tree after its body makes its joint at once")
	spun = box("Spun", Vector2(900, 100))
	world.add_child(spun)
	spinner = joint("Spinner", "wheel", Vector2(900, 100), NodePath("../Spun"),
		{"axis": Vector2(0, 1), "spring_hertz": 4.0, "spring_damping_ratio": 1.0})
	world.add_child(spinner)
	hung = box("Hung", Vector2(1100, 105))
	world.add_child(hung)
	winch = joint("Winch", "distance", Vector2(1100, 50), NodePath("../Hung"),
		{"anchor_b": Vector2(0, 50), "min_length": 20.0, "max_length": 80.0})
	world.add_child(winch)
	var wheel_box = box("Wheel", Vector2(700, 100))
	world.add_child(wheel_box)
	wheel = joint("Axle", "revolute", Vector2(700, 100), NodePath("../Wheel"))
	world.add_child(wheel)
	stray = joint("Stray", "revolute", Vector2(), NodePath("../Hinge"))  # no body: an error, no joint
	world.add_child(stray)


func _on_weld_broken():
	broken += 1


func _on_world_joint_broken(a, b):
	world_broken.append([a, b])


func _iteration(_delta):
	frame += 1
	if frame == 1:  # the script's frame comes before the nodes' physics frame: nothing has stepped yet
		check(hinge.joint == 0 and rope.joint == 0, "the hinge and the rope wait for the world's first step")
		check(world.world.get_mass(bob.body) == 100.0, "a 10 × 10 box weighs 100 mass units")
	if frame == 2:
		check(hinge.joint != 0 and rope.joint != 0 and not hinge.is_in_group(Joint2D.PENDING),
			"the hinge and the rope made their joints once their bodies were made")
		check(lamp.position == ROPE_TOP + Vector2(0, 65),
			"made before the world's first step: the lamp has not sagged at all %s" % lamp.position)
		check(stray.joint == 0 and not stray.is_in_group(Joint2D.PENDING), "the stray gave up and made none")
		first_hinge = hinge.joint
		wheel.set_motor(true, 3.0, 1e9)
		spinner.set_motor(true, 3.0, 1e9)
		winch.set_motor(true, 30.0, 2e5)  # twice the box's weight: it pays out no faster, and the stop holds
	if frame >= 2 and frame <= 60:
		worst_length = max(worst_length, abs(bob.position.distance_to(HINGE_AT) - 40))
		lowest = max(lowest, bob.position.y)
	if frame == 3:
		check(broken == 1 and weld.joint == 0 and not weld.is_joined() and weld.get_reaction() == null,
			"the weld broke at once: its node's `broken` signal, its joint gone")
		check(world_broken == [[null, weak]], "and the world's joint_broken(null, weak): %s" % [world_broken])
	if frame == 60:
		print("hinge: the bob's distance to the anchor stayed within %.3f px of 40 over 60 frames; lowest y %.2f"
			% [worst_length, lowest])
		check(worst_length < 1.0, "the bob swings at the hinge's length: |d − 40| ≤ %.3f px < 1" % worst_length)
		check(lowest > HINGE_AT.y + 38, "the bob swung down under the anchor: lowest y %.2f > %.0f" % [lowest, HINGE_AT.y + 38])
		var angle = hinge.get_value()
		check(angle != null and abs(angle["value"]) > 0.5, "the hinge's value is the angle turned: %s" % [angle])
		check(near(wheel.get_value()["speed"], 3.0, 0.01), "set_motor at run time turns the wheel at 3 rad/s: %s"
			% [wheel.get_value()])
		wheel.motor_speed = -2.0
		check(near(spun.get_angular_velocity(), 3.0, 0.01), "set_motor at run time spins the wheel joint's box at 3 rad/s: %s"
			% spun.get_angular_velocity())
		spinner.set_limits(true, -0.5, 0.5)
		var weight = 100 * 980.0
		var r = rope.get_reaction()
		var v = rope.get_value()
		print("rope: lamp at %s, value %s, reaction %s, weight %.0f" % [lamp.position, v, r, weight])
		check(lamp.position.distance_to(ROPE_TOP + Vector2(0, 65)) < 0.05, "the lamp hangs still: %s" % lamp.position)
		check(near(v["value"], 60, 0.5), "the rope's value is its 60 px length: %s" % [v])
		check(near(-r["force"].y, weight, 0.03 * weight) and abs(r["force"].x) < 0.01 * weight,
			"the rope's reaction on the lamp %s holds its weight %.0f" % [r, weight])
		var n = world.world.get_joints().size()
		lamp.remove_child(rope)
		check(rope.joint == 0 and world.world.get_joints().size() == n - 1, "removing the rope's node destroys its joint")
		world.remove_child(hinge)
		check(hinge.joint == 0 and world.world.get_joints().size() == n - 2, "so does the hinge's")
		world.add_child(hinge)
	if frame == 30:
		var paid = winch.get_value()
		check(near(paid["speed"], 30.0, 0.5) and paid["value"] > 55 and paid["value"] < 80,
			"set_motor at run time pays the winch's rope out at 30 px/s: %s" % [paid])
	if frame == 61:
		check(hinge.joint != 0 and hinge.joint != first_hinge and world.world.get_joints().has(hinge.joint)
			and world.world.get_joints().size() == 4,
			"the hinge put back made a new joint: %s" % [world.world.get_joints()])
		hinge.queue_free()
		bob_freed_at = bob.position
	if frame == 90:
		check(lamp.position.y > ROPE_TOP.y + 65 + 50, "without its rope the lamp fell: y %.2f" % lamp.position.y)
		var left = world.world.get_joints()
		check(left.size() == 3 and left.has(wheel.joint) and left.has(spinner.joint) and left.has(winch.joint),
			"freeing the hinge's node destroyed its joint: %s" % [left])
		var slide = spinner.get_value()["value"]
		check(abs(slide) <= 0.5 + 0.01, "set_limits at run time holds the wheel's slide within 0.5 px: %.3f" % slide)
		check(near(winch.get_value()["value"], 80.0, 0.5), "the winch stops at the rope's 80 px: %s" % [winch.get_value()])
		check(near(wheel.get_value()["speed"], -2.0, 0.01), "setting motor_speed reached the joint: %s" % [wheel.get_value()])
		check(bob.position.distance_to(HINGE_AT) > 45 and bob.get_linear_velocity().y > 150,
			"without its hinge the bob flew off: %.2f px from the anchor, falling at %.0f px/s"
			% [bob.position.distance_to(HINGE_AT), bob.get_linear_velocity().y])
		rope.free()
		finish()
	if frame > 120:
		print("RESULT: FAIL (ran out of frames)")
		quit(1)
