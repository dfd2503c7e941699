extends "res://checks.gd"
# PhysPix inside a real Godot 3.2 through PhysPixWorld: a crate falls onto terrain and rests,
# the terrain under it is erased and it falls again, a cut bar splits, bad calls are refused;
# a scene file loads (user:// and plain paths), a malformed one is refused with its JSON path,
# and a snapshot loaded into a second object continues exactly as the original; rays and queries
# find what is there, a sensor reports a ball falling freely through it, a landing reports its
# speed and the resting contacts' impulses carry the weight, and a one-way platform is passed
# from below and landed on from above; world settings, poses, pixels, states and properties (issue 25);
# joints: a hinge pendulum's period, a reaction, a motor, breaking and misuse (issue 24).
# Exits 0 and prints "RESULT: PASS" only if every check holds (run.sh wants both).

const PhysPixWorld = preload("res://addons/physpix/physpix_world.gdns")
const DT = 1.0 / 60.0




func solid_mask(w, h):
	var m = PoolByteArray()
	m.resize(w * h)
	for i in range(w * h):
		m[i] = 1
	return m


func is_int(x):
	return typeof(x) == TYPE_INT


func steps(world, n):
	for i in range(n):
		world.step(DT)


# The scene of the README's example: a static 400×40 ground (top at y = 380) and a 32×32 crate.
const SCENE = """{"camera": {"center": [200, 300], "zoom": 2, "width": 400, "height": 300},
 "bodies": [{"name": "ground", "type": "static", "box": [400, 40], "position": [200, 400]},
            {"name": "crate", "box": [32, 32], "position": [200, 300]}]}"""
const BAD_SCENE = '{"bodies": [{"name": "crate", "box": [8, 8], "density": -1}]}'


func write_text(path, text):
	var f = File.new()
	var err = f.open(path, File.WRITE)
	if err == OK:
		f.store_string(text)
		f.close()
	return err


# Removes a folder and everything in it; true if it is gone.
func remove_tree(path):
	var dir = Directory.new()
	if dir.open(path) == OK:
		dir.list_dir_begin(true, true)  # skip "." and ".." and hidden
		var name = dir.get_next()
		while name != "":
			if dir.current_is_dir():
				remove_tree(path + "/" + name)
			else:
				dir.remove(path + "/" + name)
			name = dir.get_next()
		dir.list_dir_end()
		dir.remove(path)
	return not dir.dir_exists(path)


# The one body of the given mass (the scene's crate: 32·32 = 1024; the static ground has none).
func body_of_mass(world, mass):
	for b in world.get_bodies():
		if world.get_mass(b) == mass:
			return b
	return null


# Issue 10: a box dropped 60 px (bottom 40 → ground top 100) onto a ground, in a world that reports
# contact events and never sleeps.
const LANDING_SCENE = """{"world": {"contact_events": true, "allow_sleep": false, "backend": "cpu"},
 "bodies": [{"type": "static", "box": [200, 40], "position": [100, 120]},
            {"box": [20, 20], "position": [100, 30], "restitution": 0}]}"""



func test_rays_and_queries():
	var q = PhysPixWorld.new()
	var ground = q.add_body_mask(solid_mask(200, 40), 200, 40, Vector2(100, 120), "static")  # top y = 100
	var hit = q.raycast(Vector2(105, 0), Vector2(105, 200))
	check(typeof(hit) == TYPE_DICTIONARY and hit["body"] == ground and near(hit["point"].x, 105, 0.5)
		and near(hit["point"].y, 100, 0.5) and hit["normal"].distance_to(Vector2(0, -1)) < 1e-3
		and near(hit["fraction"], 0.5, 0.5 / 200), "raycast down meets the top face at (105, 100), normal (0, -1): %s %s"
		% [hit, q.get_last_error()])
	check(q.raycast(Vector2(0, 0), Vector2(300, 0)) == null and q.get_last_error() == "", "a ray above it misses: null")
	check(q.raycast(Vector2(105, 0), Vector2(105, 200), 2) == null and q.get_last_error() == "",
		"a mask without the ground's category misses")
	check(q.raycast(Vector2(), Vector2(1, 1), -1) == null and q.get_last_error().find("0..0xffffffff") >= 0,
		"mask -1 refused: %s" % q.get_last_error())
	var box = q.add_body_mask(solid_mask(20, 20), 20, 20, Vector2(40, 50))  # 30..50 × 40..60
	var at = q.query_point(Vector2(45.5, 55.5))
	check(at == [box], "query_point finds the box: %s" % [at])
	check(q.query_aabb(Vector2(0, 0), Vector2(300, 300)) == [ground, box], "query_aabb finds both in slot order")
	check(q.query_circle(Vector2(100, 80), 10.0) == [], "query_circle above the ground finds nothing")
	check(q.query_circle(Vector2(100, 95), 10.0, 1) == [ground], "query_circle reaching the ground finds it")
	q.erase_circle(box, Vector2(45, 55), 4.0)
	check(q.query_point(Vector2(45.5, 55.5)) == [], "erased pixels are not found")


# Issue 44: a blast pushes a box by its extent across it (16 px × 10 mass·px/s per px), a cast drops a box onto the
# ground, and a ray through both names them nearest first.
func test_explode_and_casts():
	var q = PhysPixWorld.new()
	q.create({"gravity": Vector2(0, 0), "backend": "cpu"})
	var ground = q.add_body_mask(solid_mask(200, 40), 200, 40, Vector2(100, 120), "static")  # top y = 100
	var box = q.add_body_mask(solid_mask(16, 16), 16, 16, Vector2(100, 50))  # 92..108 × 42..58
	var hit = q.cast_body(box, Vector2(0, 100))
	check(typeof(hit) == TYPE_DICTIONARY and hit["body"] == ground and near(hit["fraction"] * 100, 42, 1.0 / 16)
		and hit["normal"].distance_to(Vector2(0, -1)) < 1e-6, "cast_body stops the box 42 px down on the ground: %s %s"
		% [hit, q.get_last_error()])
	check(q.cast_body(box, Vector2(0, -100)) == null and q.get_last_error() == "", "cast up: nothing")
	var hits = q.raycast_all(Vector2(100, 0), Vector2(100, 200))
	check(hits.size() == 2 and hits[0]["body"] == box and hits[1]["body"] == ground, "raycast_all: box, then ground: %s"
		% [hits])
	check(q.explode(Vector2(80, 50), 30.0, 0.0, 10.0) == 0, "explode without an erase erases nothing")
	var momentum = q.get_linear_velocity(box).x * q.get_mass(box)
	check(near(momentum, 160, 0.05), "the box took 16 px × 10: %s" % momentum)
	check(q.explode(Vector2(100, 100), 10.0, 0.0, 10.0, 5.0) > 0, "explode with an erase carves the ground")
	check(q.explode(Vector2(), -1.0) == null and q.get_last_error().find("radius") >= 0, "a negative radius refused: %s"
		% q.get_last_error())


func test_sensor():
	var s = PhysPixWorld.new()
	var sensor = s.add_body_mask(solid_mask(200, 20), 200, 20, Vector2(100, 100), "static", {"is_sensor": true})
	var ball = s.add_body_mask(solid_mask(8, 8), 8, 8, Vector2(100, 40))
	check(is_int(sensor) and is_int(ball), "a sensor made with options {is_sensor: true}: %s" % s.get_last_error())
	var seen = []
	var falls_freely = true
	for k in range(1, 46):
		s.step(DT)
		var vy = s.get_linear_velocity(ball).y
		falls_freely = falls_freely and near(vy, 980.0 * k * DT, 0.01 * 980.0 * k * DT)
		for e in s.get_events():
			seen.append(e["type"])
			if e["type"] == "sensor_begin":
				check(e["body"] == sensor and e["other"] == ball and e["normal"].y < -0.95
					and near(e["approach_speed"], vy, 980.0 * DT + 1.0),
					"sensor_begin: the sensor, the ball, normal up, approach %s ≈ %s px/s" % [e["approach_speed"], vy])
	check(falls_freely, "the ball falls freely through the sensor (velocity within 1 % of g·t every step)")
	check(seen == ["sensor_begin", "sensor_end"], "events sensor_begin then sensor_end: %s" % [seen])
	check(s.get_position(ball).y > 130, "the ball fell through: y %s" % s.get_position(ball).y)


func test_landing_and_impulses():
	var path = OS.get_user_data_dir() + "/physpix_landing_%d.json" % OS.get_process_id()
	var l = PhysPixWorld.new()
	var loaded = write_text(path, LANDING_SCENE) == OK and l.load_scene(path) == true
	Directory.new().remove(path)
	check(loaded, "a scene with contact_events loads: %s" % l.get_last_error())
	var box = body_of_mass(l, 400.0)
	var begins = []
	for k in range(180):
		l.step(DT)
		for e in l.get_events():
			if e["type"] == "contact_begin":
				begins.append(e)
	var expected = sqrt(2.0 * 980.0 * 60.0)
	check(begins.size() == 1 and near(begins[0]["approach_speed"], expected, 0.05 * expected),
		"one contact_begin at sqrt(2 g h) = %.1f px/s: %s" % [expected, begins])
	var total = 0.0
	for k in range(30):
		l.step(DT)
		for c in l.get_contacts():
			total += c["normal_impulse"]
	var weight = 400.0 * 980.0 / 240.0  # mass · g · substep (1/60 s over 4 substeps)
	check(box != null and near(total / 30.0, weight, 0.02 * weight),
		"resting contacts' normal_impulse sum %.1f ≈ m·g·h = %.1f" % [total / 30.0, weight])


func test_contact_events_switch():
	var e = PhysPixWorld.new()
	e.add_body_mask(solid_mask(200, 20), 200, 20, Vector2(100, 100), "static")  # top y = 90
	e.add_body_mask(solid_mask(10, 10), 10, 10, Vector2(100, 60))
	e.set_contact_events(true)
	var begins = 0
	for k in range(60):
		e.step(DT)
		for ev in e.get_events():
			if ev["type"] == "contact_begin":
				begins += 1
	check(begins == 1, "set_contact_events(true): the landing begins one contact, got %d" % begins)
	check(e.set_contact_events(1) == null and e.get_last_error().find("expected bool") >= 0,
		"set_contact_events(1) is refused: %s" % e.get_last_error())


func test_one_way():
	var o = PhysPixWorld.new()
	var platform = o.add_body_mask(solid_mask(200, 10), 200, 10, Vector2(100, 100), "static", {"one_way": true})
	var box = o.add_body_mask(solid_mask(16, 16), 16, 16, Vector2(100, 200))
	o.set_velocity(box, Vector2(0, -sqrt(2.0 * 980.0 * 200.0)), 0.0)
	var top = 200.0
	for k in range(300):
		o.step(DT)
		top = min(top, o.get_position(box).y)
	var y = o.get_position(box).y
	check(is_int(platform) and top < 95 - 8 - 50, "the box rose through the one-way platform to y %.1f" % top)
	check(near(y, 95 - 8, 1.5), "and came to rest on its top: y %.2f ≈ 87" % y)
	check(o.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(), "static", {"one_wya": true}) == null
		and o.get_last_error().find("one_wya") >= 0, "an unknown option refused: %s" % o.get_last_error())
	check(o.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(), "static", {"one_way": 1}) == null
		and o.get_last_error().find("expected bool") >= 0, "an option of the wrong type refused: %s" % o.get_last_error())
	check(o.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(), "static", {"one_way": true, "one_way_direction": Vector2()})
		== null and o.get_last_error().find("one_way_direction") >= 0, "a zero direction refused: %s" % o.get_last_error())

# Issue 24: a hinge pendulum's period against the physical pendulum's, a hanging box's reaction, a motor, a joint
# broken by force with its event, and misuse refused with the reason.
func test_joints():
	var j = PhysPixWorld.new()
	j.create({"backend": "cpu"})
	var d = 25.0
	var rod = j.add_body_mask(solid_mask(10, 60), 10, 60, Vector2(200, 200))
	var hinge = j.create_joint({"type": "revolute", "body_b": rod, "anchor_a": Vector2(200, 200 - d)})
	check(is_int(hinge) and j.get_joints() == [hinge], "create_joint(revolute) to the world: %s %s" % [hinge, j.get_last_error()])
	j.set_velocity(rod, Vector2(-0.2 * d, 0), 0.2)
	var prev = j.get_joint_value(hinge)["value"]
	var ups = []  # times of upward zero crossings of the angle, s
	for k in range(1, 601):
		j.step(DT)
		var v = j.get_joint_value(hinge)["value"]
		if prev < 0 and v >= 0:
			ups.append((k - 1 + prev / (prev - v)) * DT)
		prev = v
	var m = j.get_mass(rod)
	var inertia = m * (10 * 10 + 60 * 60) / 12.0 + m * d * d  # about the hinge
	var analytic = 2 * PI * sqrt(inertia / (m * 980.0 * d))
	var period = (ups[-1] - ups[0]) / (ups.size() - 1) if ups.size() >= 3 else 0.0
	print("hinge pendulum: period %.4f s over %d swings, analytic 2π√(I/(m·g·d)) = %.4f s (%+.2f %%)"
		% [period, ups.size() - 1, analytic, 100 * (period / analytic - 1)])
	check(near(period, analytic, 0.03 * analytic), "the hinge pendulum's period %.4f s within 3 %% of %.4f s" % [period, analytic])

	var box = j.add_body_mask(solid_mask(20, 20), 20, 20, Vector2(400, 100))
	var hang = j.create_joint({"type": "revolute", "body_b": box, "anchor_a": Vector2(400, 92)})
	steps(j, 60)
	var r = j.get_joint_reaction(hang)
	var weight = j.get_mass(box) * 980.0
	check(near(-r["force"].y, weight, 0.02 * weight) and abs(r["force"].x) < 0.01 * weight,
		"a hanging box's reaction %s ≈ its weight %.0f" % [r, weight])
	var wheel = j.add_body_mask(solid_mask(20, 20), 20, 20, Vector2(600, 100))
	var motor = j.create_joint({"type": "revolute", "body_b": wheel, "anchor_a": Vector2(600, 100), "enable_motor": true,
		"motor_speed": 3.0, "max_motor_force": 1e9})
	steps(j, 30)
	check(near(j.get_joint_value(motor)["speed"], 3.0, 0.01), "the motor turns at 3 rad/s: %s" % [j.get_joint_value(motor)])
	j.set_joint_motor(motor, false, 0.0, 0.0)
	j.set_joint_limits(motor, true, -0.5, 0.5)
	check(j.get_last_error() == "", "set_joint_motor and set_joint_limits accepted")

	# Broken by force: the event names the joint, and its int goes stale.
	var weak = j.create_joint({"type": "revolute", "body_b": box, "anchor_a": Vector2(400, 108), "break_force": 0.5 * weight,
		"user_data": 7})
	j.destroy_joint(hang)
	j.step(DT)
	var broken = []
	for e in j.get_events():
		if e["type"] == "joint_broken":
			broken.append(e)
	check(broken.size() == 1 and broken[0]["joint"] == weak and broken[0]["body"] == 0 and broken[0]["other"] == box,
		"the weak joint broke: event joint_broken {joint, body 0, other box}: %s" % [broken])
	check(j.get_joint_value(weak) == null and j.get_last_error().find("PP_ERR_INVALID_HANDLE") >= 0,
		"a broken joint's int is stale: %s" % j.get_last_error())

	# Misuse: refused with the reason, never a crash.
	check(j.create_joint({"type": "hinge", "body_b": box}) == null and j.get_last_error().find("\"revolute\"") >= 0,
		"an unknown type refused with the names: %s" % j.get_last_error())
	check(j.create_joint({"body_b": box}) == null and j.get_last_error().find("no \"type\"") >= 0,
		"a def without a type refused: %s" % j.get_last_error())
	check(j.create_joint({"type": "weld", "body_b": box, "anchour_a": Vector2()}) == null
		and j.get_last_error().find("anchour_a") >= 0, "an unknown key refused: %s" % j.get_last_error())
	check(j.create_joint({"type": "weld", "body_b": 1.5}) == null and j.get_last_error().find("expected int") >= 0,
		"a float body refused: %s" % j.get_last_error())
	check(j.create_joint({"type": "weld", "body_a": box, "body_b": box}) == null
		and j.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0, "a joint of a body to itself refused: %s" % j.get_last_error())
	check(j.create_joint({"type": "revolute", "body_b": 123456789}) == null
		and j.get_last_error().find("PP_ERR_INVALID_HANDLE") >= 0, "a stale body refused: %s" % j.get_last_error())
	check(j.set_joint_target(motor, Vector2()) == null and j.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0,
		"set_joint_target on a hinge refused: %s" % j.get_last_error())
	check(j.set_joint_motor(motor, true, 1.0, -1.0) == null and j.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0,
		"a negative motor force refused: %s" % j.get_last_error())
	check(j.get_joint_reaction("motor") == null and j.get_last_error().find("expected a joint (int)") >= 0,
		"a String for a joint refused: %s" % j.get_last_error())
	j.destroy_joint(motor)
	check(j.destroy_joint(motor) == null and j.get_last_error().find("PP_ERR_INVALID_HANDLE") >= 0,
		"destroying it twice: %s" % j.get_last_error())
	check(j.get_joints() == [hinge], "one joint left: %s" % [j.get_joints()])
	return true


# Issue 41: a wheel sags by m·g/k = g/ω² on its spring; a motor joint takes a crate to the offsets it is given.
func test_wheel_and_motor_joints():
	var j = PhysPixWorld.new()
	j.create({"backend": "cpu"})
	var hz = 2.0
	var hub = j.add_body_mask(solid_mask(20, 20), 20, 20, Vector2(200, 200))
	var wheel = j.create_joint({"type": "wheel", "body_b": hub, "anchor_a": Vector2(200, 200), "anchor_b": Vector2(200, 200),
		"axis": Vector2(0, 1), "spring_hertz": hz, "spring_damping_ratio": 0.7})
	check(is_int(wheel), "create_joint(wheel): %s %s" % [wheel, j.get_last_error()])
	var crate = j.add_body_mask(solid_mask(20, 20), 20, 20, Vector2(400, 200))
	var motor = j.create_joint({"type": "motor", "body_b": crate, "linear_offset": Vector2(420, 150), "angular_offset": 0.2})
	check(is_int(motor), "create_joint(motor): %s %s" % [motor, j.get_last_error()])
	steps(j, 240)
	var sag = 980.0 / pow(2 * PI * hz, 2)
	var value = j.get_joint_value(wheel)["value"]
	print("wheel sag %.4f px, m·g/k %.4f px (%+.2f %%)" % [value, sag, 100 * (value / sag - 1)])
	check(near(value, sag, 0.03 * sag), "the wheel sags m·g/k within 3 %%: %.4f px against %.4f px" % [value, sag])
	check(j.get_position(crate).distance_to(Vector2(420, 150)) < 0.5 and near(j.get_angle(crate), 0.2, 0.01),
		"the motor joint holds the crate at its offsets: %s, %s rad" % [j.get_position(crate), j.get_angle(crate)])
	j.set_joint_offsets(motor, Vector2(380, 170), 0.0)
	j.set_joint_spring(wheel, 4.0, 0.7, 0.0)
	check(j.get_last_error() == "", "set_joint_offsets and set_joint_spring accepted: %s" % j.get_last_error())
	steps(j, 240)
	check(j.get_position(crate).distance_to(Vector2(380, 170)) < 0.5, "moved to the new offsets: %s" % [j.get_position(crate)])
	check(near(j.get_joint_value(wheel)["value"], sag / 4, 0.03 * sag / 4), "a 4 Hz spring sags a quarter: %s" % [j.get_joint_value(wheel)])
	check(j.set_joint_offsets(wheel, Vector2(), 0.0) == null and j.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0,
		"set_joint_offsets on a wheel refused: %s" % j.get_last_error())
	return true


# Issue 25: world settings at creation, poses, pixels in and out, states in one call, runtime properties.
# Issue 39: every pixel call fed huge, negative and 32-bit-wrapping ints is refused with a message, never a crash
# (read_rgba(body, 1, 9223372036854775807) overflowed its row check and killed godot3-server).
const INT64_MAX = 9223372036854775807
const INT64_MIN = -9223372036854775807 - 1
const BAD_INTS = [INT64_MAX, INT64_MIN, -1, 4294967312, 2147483648, -2147483649]


func test_pixel_calls_with_huge_arguments():
	var p = PhysPixWorld.new()
	var box = p.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(50, 50), "static")
	var refused = 0
	var calls = 0
	for n in BAD_INTS:
		var results = [
			p.add_body_mask(solid_mask(4, 4), n, 1, Vector2()),
			p.add_body_mask(solid_mask(4, 4), 1, n, Vector2()),
			p.write_pixels(box, n, 0, 1, 1, solid_mask(1, 1)),
			p.write_pixels(box, 0, n, 1, 1, solid_mask(1, 1)),
			p.write_pixels(box, 0, 0, n, 1, solid_mask(1, 1)),
			p.write_pixels(box, 0, 0, 1, n, solid_mask(1, 1)),
			p.write_pixels(box, 0, 0, n, n, solid_mask(1, 1)),
			p.read_rgba(box, n),
			p.read_rgba(box, 1, n),
			p.read_rgba(box, n, n),
			p.read_rgba(box, n, 1),
			p.read_mask(n),
			p.read_weights(n),
			p.paint_circle(box, Vector2(50, 50), 2.0, n),
			p.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(), "dynamic", {"weights": PoolByteArray([n & 255])}),
		]
		for r in results:
			calls += 1
			if r == null and p.get_last_error() != "":
				refused += 1
			else:
				print("not refused: %s (argument %d)" % [r, n])
	check(refused == calls, "%d of %d pixel calls with huge or negative ints refused" % [refused, calls])
	check(p.read_rgba(box, 1, 3).size() == 48 and p.read_mask(box).size() == 16, "and the body still reads back")
	return true


# Issue 39: a world's first body and first joint share slot 0, and had one int: destroy_joint(body) removed the
# joint. Each is now refused where the other is expected, with a message saying what it is.
func test_handle_kinds():
	var k = PhysPixWorld.new()
	var box = k.add_body_mask(solid_mask(16, 16), 16, 16, Vector2(100, 100))
	var hinge = k.create_joint({"type": "revolute", "body_b": box, "anchor_a": Vector2(100, 92)})
	check(is_int(box) and is_int(hinge) and box != hinge, "the first body and joint have different ints: %s %s" % [box, hinge])
	check(k.destroy_joint(box) == null and k.get_last_error().find("is a body handle, not a joint") >= 0,
		"destroy_joint(a body) refused: %s" % k.get_last_error())
	check(k.get_joint_value(box) == null and k.get_last_error().find("is a body handle, not a joint") >= 0,
		"get_joint_value(a body) refused: %s" % k.get_last_error())
	check(k.get_position(hinge) == null and k.get_last_error().find("is a joint handle, not a body") >= 0,
		"get_position(a joint) refused: %s" % k.get_last_error())
	check(k.destroy_body(hinge) == null and k.get_last_error().find("is a joint handle, not a body") >= 0,
		"destroy_body(a joint) refused: %s" % k.get_last_error())
	check(k.create_joint({"type": "weld", "body_b": hinge}) == null
		and k.get_last_error().find("is a joint handle, not a body") >= 0,
		"a joint as a joint's body refused: %s" % k.get_last_error())
	check(k.get_joints() == [hinge] and k.get_bodies() == [box], "both still there: %s %s" % [k.get_joints(), k.get_bodies()])
	return true


func test_native_gains():
	var g = PhysPixWorld.new()
	check(g.create({"preset": "fast", "gravity": Vector2(0, 500), "backend": "cpu", "contact_events": true,
		"sleep_time": 2}) == true, "create(settings): %s" % g.get_last_error())
	var st = g.get_settings()
	check(st["substeps"] == 1 and st["solver_iterations"] == 10 and st["gravity"] == Vector2(0, 500)
		and st["backend"] == "cpu" and st["contact_events"] == true and st["sleep_time"] == 2.0
		and st["contact_mode"] == "manifold", "get_settings: the fast preset with the fields given: %s" % [st])
	check(g.create({"substepz": 2}) == null and g.get_last_error().find("substepz") >= 0,
		"an unknown settings key refused: %s" % g.get_last_error())
	check(g.create({"backend": "gpx"}) == null and g.get_last_error().find("\"cpu\"") >= 0,
		"an unknown backend refused with the names: %s" % g.get_last_error())
	check(g.create({"substeps": 0.5}) == null and g.get_last_error().find("expected int") >= 0,
		"a float substeps refused: %s" % g.get_last_error())
	check(g.get_settings()["substeps"] == 1, "a refused create leaves the world as it was")
	check(g.create({"substeps": 99}) == null and g.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0,
		"substeps 99 refused by PhysPix: %s" % g.get_last_error())
	check(g.create() == true and g.get_settings()["substeps"] == 4, "create() gives the default world")

	# A 10×6 box with a custom pivot; size, pivot, transform.
	var box = g.add_body_mask(solid_mask(10, 6), 10, 6, Vector2(50, 50), "dynamic", {"pivot": Vector2(0, 0), "density": 2.0,
		"friction": 0.25})
	check(g.get_size(box) == Vector2(10, 6) and g.get_pivot(box) == Vector2(0, 0) and g.get_mass(box) == 120.0
		and g.get_friction(box) == 0.25, "size, pivot, density and friction from the options: %s %s %s %s"
		% [g.get_size(box), g.get_pivot(box), g.get_mass(box), g.get_friction(box)])
	g.set_transform(box, Vector2(100, 40), 0.5)
	check(g.get_position(box).distance_to(Vector2(100, 40)) < 1e-3 and near(g.get_angle(box), 0.5, 1e-6),
		"set_transform: %s %s" % [g.get_position(box), g.get_angle(box)])
	check(g.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(), "dynamic", {"weights": PoolByteArray([1, 2])}) == null
		and g.get_last_error().find("expected 16") >= 0, "weights of the wrong size refused: %s" % g.get_last_error())
	var w4 = PoolByteArray()
	for i in range(16):
		w4.append(51)
	var light = g.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(-200, 0), "dynamic", {"weights": w4})
	check(near(g.get_mass(light), 16 * 51.0 / 255.0, 1e-4), "weights 51/255 make a 4×4 body of mass %s" % g.get_mass(light))
	var lw = g.read_weights(light)
	check(typeof(lw) == TYPE_RAW_ARRAY and lw.size() == 16 and lw[0] == 51 and lw[15] == 51, "read_weights: 16 × 51")

	# Pixels: read the mask, clear a 5×6 half with write_pixels, read the look's rows.
	var mask = g.read_mask(box)
	check(typeof(mask) == TYPE_RAW_ARRAY and mask.size() == 60 and mask[0] == 1 and mask[59] == 1, "read_mask: 60 ones")
	var zeros = PoolByteArray()
	zeros.resize(30)
	for i in range(30):
		zeros[i] = 0
	check(g.write_pixels(box, 5, 0, 5, 6, zeros) == true and g.get_mass(box) == 60.0 and g.read_mask(box)[9] == 0
		and g.read_mask(box)[4] == 1, "write_pixels cleared the right half: mass %s" % g.get_mass(box))
	check(g.write_pixels(box, 0, 0, 5, 6, zeros.subarray(0, 9)) == null and g.get_last_error().find("expected 30") >= 0,
		"a short mask refused: %s" % g.get_last_error())
	var rgba = g.read_rgba(box)
	var rows = g.read_rgba(box, 2, 3)
	check(rgba.size() == 240 and rows.size() == 120 and rows == rgba.subarray(80, 199) and rgba[3] == 255 and rgba[39] == 0,
		"read_rgba: the whole look (opaque left, clear right) and rows 2..4 of it")
	check(g.read_rgba(box, 4, 3) == null and g.get_last_error().find("outside") >= 0, "rows past the bitmap refused")

	# States in one call, and runtime properties.
	var states = g.get_body_states()
	check(states.size() == 2 and states[0]["body"] == box and states[0]["position"] == g.get_position(box)
		and states[0]["awake"] == true and states[1]["body"] == light, "get_body_states: %s" % [states])
	g.set_awake(box, false)
	check(g.get_body_states(true).size() == 1 and g.get_body_states(true)[0]["body"] == light
		and g.get_body_states().size() == 2, "get_body_states(true) leaves out the body put to sleep")
	g.set_awake(box, true)
	g.set_gravity(Vector2(0, -100))
	g.set_gravity_scale(light, 2.0)
	g.step(DT)
	check(near(g.get_linear_velocity(box).y, -100.0 * DT, 1e-3) and near(g.get_linear_velocity(light).y, -200.0 * DT, 1e-3),
		"set_gravity up, gravity scale 2 doubles it: %s %s" % [g.get_linear_velocity(box), g.get_linear_velocity(light)])
	g.set_gravity(Vector2())
	g.set_velocity(light, Vector2(), 0.0)
	g.apply_force(light, Vector2(60.0 * g.get_mass(light), 0), g.get_position(light))
	g.step(DT)
	check(near(g.get_linear_velocity(light).x, 1.0, 1e-3), "apply_force m·60 px/s² for 1/60 s: v.x %s" % g.get_linear_velocity(light).x)
	var inertia_turn = g.get_angular_velocity(light)
	g.apply_angular_impulse(light, 10.0)
	check(g.get_angular_velocity(light) > inertia_turn, "apply_angular_impulse turns it")
	g.apply_torque(light, -1000.0)
	g.step(DT)
	check(g.get_angular_velocity(light) < g.get_angular_velocity(box) + 10.0, "apply_torque accepted: %s" % g.get_last_error())
	g.set_restitution(light, 0.5)
	g.set_density(light, 2.0)
	g.set_damping(light, 0.1, 0.2)
	g.set_filter(light, 2, 0xffffffff)
	check(g.get_restitution(light) == 0.5 and g.get_density(light) == 2.0 and g.get_gravity_scale(light) == 2.0
		and g.get_last_error() == "", "restitution, density, damping, filter set")
	g.set_awake(light, false)
	check(g.is_awake(light) == false and g.get_type(light) == "dynamic", "set_awake(false) puts it to sleep")
	check(g.set_restitution(light, 2.0) == null and g.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0,
		"restitution 2 refused: %s" % g.get_last_error())
	check(g.set_filter(light, -1, 0) == null and g.get_last_error().find("0..0xffffffff") >= 0, "filter -1 refused")
	# Type and fixed rotation: a kinematic body ignores gravity and keeps its velocity; fixed rotation holds its angle.
	g.set_gravity(Vector2(0, 980))
	g.set_type(light, "kinematic")
	g.set_velocity(light, Vector2(30, 0), 2.0)
	g.set_fixed_rotation(light, true)
	var turned = g.get_angle(light)
	g.step(DT)
	check(g.get_type(light) == "kinematic" and g.get_linear_velocity(light) == Vector2(30, 0) and g.get_angle(light) == turned,
		"set_type kinematic, set_fixed_rotation: %s %s %s" % [g.get_type(light), g.get_linear_velocity(light), g.get_angle(light)])
	g.set_type(light, "dynamic")
	g.step(DT)
	check(near(g.get_linear_velocity(light).y, 980.0 * DT, 0.05), "dynamic again, gravity takes it (its damping 0.1/s on top): %s" % g.get_linear_velocity(light))
	check(g.set_type(light, "floating") == null and g.get_last_error().find("expected \"dynamic\"") >= 0,
		"an unknown type refused: %s" % g.get_last_error())
	g.set_gravity(Vector2())

	# Textures: an ImageTexture of an RGB8 image is read whole; an unimported PNG is refused, not an 8×8 body.
	var img = Image.new()
	img.create(12, 7, false, Image.FORMAT_RGB8)
	img.fill(Color(1, 0, 0))
	var tex = ImageTexture.new()
	tex.create_from_image(img, 0)
	var from_tex = g.add_body_image(tex, Vector2(300, 0))
	check(is_int(from_tex) and g.get_size(from_tex) == Vector2(12, 7) and g.get_mass(from_tex) == 84.0,
		"add_body_image(ImageTexture of RGB8): 12×7, mass %s" % g.get_mass(from_tex))
	var mask_img = Image.new()
	mask_img.create(12, 7, false, Image.FORMAT_L8)
	mask_img.fill(Color(0, 0, 0))
	mask_img.lock()
	for y in range(7):
		for x in range(6):
			mask_img.set_pixel(x, y, Color(1, 1, 1))  # white left half solid, black right half empty
	mask_img.unlock()
	var grey = Image.new()
	grey.create(12, 7, false, Image.FORMAT_RGBA8)
	grey.fill(Color8(51, 51, 51, 255))
	var masked = g.add_body_image(tex, Vector2(400, 0), "dynamic", {"collision_mask": mask_img, "weights": grey})
	check(is_int(masked) and near(g.get_mass(masked), 42 * 0.2, 1e-4) and g.read_mask(masked)[5] == 1
		and g.read_mask(masked)[6] == 0, "collision_mask (L8, white solid) and weights (grey 51) images: mass %s %s"
		% [g.get_mass(masked), g.get_last_error()])
	var mw = g.read_weights(masked)
	check(mw.size() == 84 and mw[5] == 51 and mw[6] == 0, "read_weights: 51 where solid, 0 where not: %d %d" % [mw[5], mw[6]])
	check(g.add_body_image(tex, Vector2(), "dynamic", {"collision_mask": grey.get_rect(Rect2(0, 0, 4, 4))}) == null
		and g.get_last_error().find("4 × 4 pixels") >= 0, "a mask image of another size refused: %s" % g.get_last_error())
	img.save_png("res://never_imported.png")
	var placeholder = load("res://never_imported.png")
	check(placeholder != null and g.add_body_image(placeholder, Vector2()) == null
		and g.get_last_error().find("never imported") >= 0 and g.get_last_error().find("does not exist") < 0,
		"an unimported texture refused: %s" % g.get_last_error())
	# A path with no file loads as the same kind of placeholder (Godot prints its own error): told apart from one
	# never imported, since the fix is the path, not an import.
	var missing = load("res://no_such_texture.png")
	check(missing != null and g.add_body_image(missing, Vector2()) == null
		and g.get_last_error().find("'res://no_such_texture.png' does not exist") >= 0
		and g.get_last_error().find("never imported") < 0,
		"a texture that does not exist refused as such: %s" % g.get_last_error())
	check(g.add_body_image(null, Vector2()) == null and g.get_last_error().find("null") >= 0
		and g.get_last_error().find("load()") >= 0, "a null texture refused: %s" % g.get_last_error())
	check(g.add_body_image(ImageTexture.new(), Vector2()) == null and g.get_last_error().find("no readable image") >= 0,
		"a texture without an image refused: %s" % g.get_last_error())
	return true  # a runtime error returns null before this: the caller checks


# Issue 24: world def fields by name at creation (a world without gravity keeps a body at rest; every field
# get_settings names goes back through create), NaN and wrong types refused with the world kept, the new getters.
# Issue 43: debug_draw gives a box's four outline edges, culls by the view box and refuses unknown flags;
# get_joint_anchors reports where a hinge holds.
func test_debug_draw():
	var d = PhysPixWorld.new()
	var box = d.add_body_mask(solid_mask(16, 16), 16, 16, Vector2(100, 50))  # 92..108 × 42..58
	var segs = d.debug_draw(1)
	var want = [[Vector2(92, 42), Vector2(108, 42)], [Vector2(108, 42), Vector2(108, 58)],
		[Vector2(108, 58), Vector2(92, 58)], [Vector2(92, 58), Vector2(92, 42)]]
	var found = 0
	for s in segs:
		for w in want:
			if s["a"] == w[0] and s["b"] == w[1] and s["kind"] == 1 and s["body"] == box:
				found += 1
	check(segs.size() == 4 and found == 4, "debug_draw(1): a 16×16 box is its 4 edges: %s %s" % [segs, d.get_last_error()])
	check(d.debug_draw().size() == 4 + 4 + 2 + 1, "debug_draw(): outline, AABB, axes and velocity")
	check(d.debug_draw(63, Vector2(500, 500), Vector2(600, 600)) == [], "a view box away from the box draws nothing")
	check(d.debug_draw(64) == null and d.get_last_error().find("flags") >= 0,
		"unknown flag bits refused: %s" % d.get_last_error())
	var hinge = d.create_joint({"type": "revolute", "body_b": box, "anchor_a": Vector2(100, 40)})
	var anchors = d.get_joint_anchors(hinge)
	check(typeof(anchors) == TYPE_DICTIONARY and anchors["anchor_a"] == Vector2(100, 40)
		and anchors["anchor_a"].distance_to(anchors["anchor_b"]) < 1e-3, "get_joint_anchors: %s" % [anchors])
	return true


func test_settings_at_creation():
	var g = PhysPixWorld.new()
	check(g.create({"gravity": Vector2(0, 0), "substeps": 3, "allow_sleep": false, "backend": "cpu"}) == true,
		"create without gravity: %s" % g.get_last_error())
	var st = g.get_settings()
	check(st["substeps"] == 3 and st["gravity"] == Vector2(0, 0) and st["allow_sleep"] == false
		and st["solver_iterations"] == 20, "settings read back over the balanced preset: %s" % [st])
	var box = g.add_body_mask(solid_mask(16, 16), 16, 16, Vector2(40, 40), "dynamic", {"user_data": 77})
	steps(g, 60)
	check(g.get_position(box) == Vector2(40, 40) and g.get_linear_velocity(box) == Vector2(0, 0) and g.is_awake(box),
		"without gravity a lone box stays put, awake (allow_sleep off): %s" % [g.get_position(box)])
	check(g.get_user_data(box) == 77, "get_user_data gives the options' user_data: %s" % [g.get_user_data(box)])
	check(g.get_fixed_rotation(box) == false, "get_fixed_rotation: free by default")
	g.set_fixed_rotation(box, true)
	check(g.get_fixed_rotation(box) == true, "get_fixed_rotation after set_fixed_rotation(true)")
	check(g.create(5) == null and g.get_last_error().find("expected Dictionary") >= 0,
		"settings that are no Dictionary refused: %s" % g.get_last_error())
	check(g.create({"gravity": Vector2(NAN, 0)}) == null and g.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0
		and g.get_last_error().find("gravity") >= 0, "a NaN gravity refused by PhysPix: %s" % g.get_last_error())
	check(g.create({"allow_sleep": 1}) == null and g.get_last_error().find("expected bool") >= 0,
		"an int flag refused: %s" % g.get_last_error())
	check(g.create({"gravity": [0, 0]}) == null and g.get_last_error().find("expected Vector2") >= 0,
		"an Array for a Vector2 refused: %s" % g.get_last_error())
	check(g.get_position(box) == Vector2(40, 40) and g.get_settings()["substeps"] == 3,
		"refused creates leave the world and its bodies as they were")
	var back = g.create(st)
	var again = g.get_settings()
	var same = back == true and again.size() == st.size()
	for k in st:
		same = same and again.has(k) and again[k] == st[k]
	check(same, "every field get_settings names goes back through create: %s" % [again])
	return true


func _init():
	# A runtime error stops _init, and with no quit() pending the engine then hangs; quit(1) first
	# makes any early stop exit 1. Only the end of this function turns it into quit(0).
	quit(1)
	var w = PhysPixWorld.new()
	check(w != null, "PhysPixWorld.new() gives an instance (Server.64 entry found)")
	if w == null:
		return

	# Bodies: terrain 400×100 with its top at y = 300, a 24×24 crate, an 80×8 bar, a 4×4 pebble.
	var terrain = w.add_body_mask(solid_mask(400, 100), 400, 100, Vector2(200, 350), "static")
	var crate = w.add_body_mask(solid_mask(24, 24), 24, 24, Vector2(200, 200))
	var bar = w.add_body_mask(solid_mask(80, 8), 80, 8, Vector2(80, 200), "dynamic")
	var pebble = w.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(350, 50))
	check(is_int(terrain) and is_int(crate) and is_int(bar) and is_int(pebble),
		"add_body_mask returns int handles (terrain %s, crate %s, bar %s)" % [terrain, crate, bar])
	check(w.get_mass(crate) == 576.0, "crate mass %s == 24·24 pixels × density 1" % w.get_mass(crate))

	# An Image made in GDScript: RGBA8 directly, and LA8 converted on a copy.
	var img = Image.new()
	img.create(24, 24, false, Image.FORMAT_RGBA8)
	img.fill(Color(0.8, 0.5, 0.2, 1.0))
	img.lock()
	for y in range(8):
		for x in range(24):
			img.set_pixel(x, y, Color(0, 0, 0, 0.2))  # alpha 51 < 128: not solid
	img.unlock()
	var sprite = w.add_body_image(img, Vector2(-500, 0), "static")
	check(is_int(sprite) and w.get_mass(sprite) == 0.0,
		"add_body_image makes a static body (mass %s: static bodies have none)" % w.get_mass(sprite))
	var sprite_dyn = w.add_body_image(img, Vector2(-800, 0))
	check(w.get_mass(sprite_dyn) == 24.0 * 16.0,
		"add_body_image mass %s == 384 opaque pixels (24×16) × density 1" % w.get_mass(sprite_dyn))
	var la = Image.new()
	la.create(10, 10, false, Image.FORMAT_LA8)
	la.fill(Color(1, 1, 1, 1))
	var la_body = w.add_body_image(la, Vector2(-1100, 0))
	check(w.get_mass(la_body) == 100.0,
		"add_body_image of an LA8 image, converted: mass %s == 100" % w.get_mass(la_body))
	check(la.get_format() == Image.FORMAT_LA8, "the caller's LA8 image keeps its format")
	w.destroy_body(sprite)
	w.destroy_body(sprite_dyn)
	w.destroy_body(la_body)

	# world_erase_circle over the pebble erases all of it: a "destroyed" event.
	var erased = w.world_erase_circle(Vector2(350, 50), 5.0)
	var events = w.get_events()
	check(erased == 16, "world_erase_circle erased %s pixels of the 4×4 pebble" % erased)
	check(events.size() == 1 and events[0]["type"] == "destroyed" and events[0]["body"] == pebble,
		"a destroyed event for the pebble: %s" % [events])
	check(w.get_bodies().size() == 3, "3 bodies left: %s" % [w.get_bodies()])

	# The crate falls 88 px and rests on the terrain: centre at 300 − 12 = 288.
	var contact = null
	for i in range(150):
		w.step(DT)
		for c in w.get_contacts():
			if contact == null and ((c["a"] == terrain and c["b"] == crate) or (c["a"] == crate and c["b"] == terrain)):
				contact = c
	var rest = w.get_position(crate)
	var v = w.get_linear_velocity(crate)
	print("crate at rest: position %s, velocity %s, angle %s" % [rest, v, w.get_angle(crate)])
	check(abs(rest.y - 288.0) <= 1.5, "crate rests at y %.2f, within 1.5 px of 288" % rest.y)
	check(abs(rest.x - 200.0) <= 1.0, "crate stays at x %.2f (200)" % rest.x)
	check(v.length() < 1.0 and abs(w.get_angular_velocity(crate)) < 0.01,
		"crate velocity %s (|v| %.3f px/s) and spin %.4f rad/s are ~0" % [v, v.length(), w.get_angular_velocity(crate)])
	var t = w.get_transform(crate)
	check(typeof(t) == TYPE_TRANSFORM2D and t.origin.distance_to(rest) < 1e-3, "get_transform origin %s" % t.origin)
	check(contact != null, "a terrain–crate contact was reported: %s" % [contact])
	if contact != null:
		var down = 1.0 if contact["a"] == crate else -1.0  # normal points from a to b
		check(contact["normal"].y * down > 0.9 and contact["pixel_count"] > 0,
			"contact normal %s points from the crate down into the terrain" % contact["normal"])

	# Erase the terrain under the crate (a bowl 60 px wide, 47 px deep): it falls again.
	var hole = w.erase_circle(terrain, Vector2(200, 320), 30.0)
	check(hole > 2000, "erase_circle removed %s terrain pixels" % hole)
	steps(w, 30)
	var fallen = w.get_position(crate)
	print("crate after the terrain under it was erased: position %s" % fallen)
	check(fallen.y > rest.y + 10.0, "crate fell again: y %.2f > %.2f + 10" % [fallen.y, rest.y])
	check(fallen.y < 350.0, "and stays in the bowl: y %.2f < 350" % fallen.y)

	# Cut the resting bar through its middle: a split event with a new body.
	var before = w.get_bodies()
	var bar_at = w.get_position(bar)
	var cut = w.erase_circle(bar, bar_at, 6.0)
	events = w.get_events()
	var after = w.get_bodies()
	print("bar at %s cut by %s pixels: events %s, bodies %s -> %s" % [bar_at, cut, events, before, after])
	check(cut > 0 and cut < 160, "erase_circle on the bar removed %s pixels" % cut)
	check(events.size() == 1 and events[0]["type"] == "split" and events[0]["body"] == bar,
		"one split event for the bar")
	if events.size() == 1:
		var piece = events[0]["other"]
		check(piece != 0 and not (piece in before) and (piece in after), "split's other %s is a new body" % piece)
		var total = w.get_mass(bar) + w.get_mass(piece)
		check(total == 640.0 - cut, "pieces' masses %s + %s == 640 − %s" % [w.get_mass(bar), w.get_mass(piece), cut])
	check(after.size() == before.size() + 1, "bodies grew by one: %d -> %d" % [before.size(), after.size()])
	steps(w, 10)

	# Bad calls are refused with nil and a message; the engine carries on.
	var r = w.step("x")
	var err = w.get_last_error()
	print("step(\"x\") -> %s, get_last_error: %s" % [r, err])
	check(r == null and err.find("step") >= 0 and err.find("String") >= 0, "step(\"x\") refused")
	w.step(DT)
	check(w.get_last_error() == "", "a good call clears the error")
	check(w.get_position() == null and w.get_last_error().find("got 0 arguments") >= 0, "missing argument refused")
	check(w.get_position(123456789) == null and w.get_last_error().find("PP_ERR_INVALID_HANDLE") >= 0,
		"stale handle: %s" % w.get_last_error())
	check(w.add_body_image(w, Vector2()) == null and w.get_last_error().find("expected Image") >= 0,
		"a non-Image object refused: %s" % w.get_last_error())
	var gone = Node.new()
	gone.free()
	check(w.add_body_image(gone, Vector2()) == null and w.get_last_error().find("freed") >= 0,
		"a freed object refused: %s" % w.get_last_error())
	check(w.add_body_mask(solid_mask(4, 4), 5, 4, Vector2()) == null,
		"mask of the wrong size refused: %s" % w.get_last_error())
	check(w.add_body_mask(solid_mask(4, 4), 4, 4, Vector2(), "floppy") == null,
		"unknown body type refused: %s" % w.get_last_error())
	check(w.paint_circle(crate, fallen, 3.0, 300) == null, "weight 300 refused: %s" % w.get_last_error())
	check(w.step(5.0) == null and w.get_last_error().find("PP_ERR_INVALID_ARGUMENT") >= 0,
		"step(5.0) refused by PhysPix: %s" % w.get_last_error())

	# An erase and a paint of the same circle inside the crate: the mass comes back.
	var centre = w.get_position(crate)
	var dug = w.erase_circle(crate, centre, 4.0)
	var mass_dug = w.get_mass(crate)
	var painted = w.paint_circle(crate, centre, 4.0, 255)
	check(is_int(painted) and dug > 0 and painted == dug and mass_dug == 576.0 - dug and w.get_mass(crate) == 576.0,
		"erase_circle then paint_circle in the crate: %s and %s pixels, mass 576 -> %s -> %s"
			% [dug, painted, mass_dug, w.get_mass(crate)])

	# Scene files and snapshots, in a folder of their own under user:// (run.sh puts it in build/godot).
	var tmp_user = "user://physpix_test_%d" % OS.get_process_id()
	var tmp = OS.get_user_data_dir() + "/physpix_test_%d" % OS.get_process_id()  # the same, as a plain path
	var dir = Directory.new()
	check(dir.make_dir_recursive(tmp) == OK and write_text(tmp + "/scene.json", SCENE) == OK
		and write_text(tmp + "/bad.json", BAD_SCENE) == OK, "wrote scene.json and bad.json into %s" % tmp)

	# load_scene replaces the object's world: an int from before it is stale.
	var sw = PhysPixWorld.new()
	var old = sw.add_body_mask(solid_mask(4, 4), 4, 4, Vector2())
	var loaded = sw.load_scene(tmp_user + "/scene.json")
	check(loaded == true and sw.get_last_error() == "", "load_scene(\"%s/scene.json\") -> %s %s"
		% [tmp_user, loaded, sw.get_last_error()])
	var scene_crate = body_of_mass(sw, 1024.0)
	check(sw.get_bodies().size() == 2 and scene_crate != null, "the scene's 2 bodies, the crate of mass 1024: %s"
		% [sw.get_bodies()])
	check(sw.get_position(old) == null and sw.get_last_error().find("PP_ERR_INVALID_HANDLE") >= 0,
		"a body int from before load_scene is stale: %s" % sw.get_last_error())
	var cam = sw.get_camera()
	check(typeof(cam) == TYPE_DICTIONARY and cam["center"] == Vector2(200, 300) and cam["zoom"] == 2.0
		and cam["size"] == Vector2(400, 300), "get_camera gives the scene's camera: %s" % [cam])
	check(sw.get_time() == 0.0, "get_time of a new scene: %s" % sw.get_time())
	steps(sw, 120)
	var scene_rest = sw.get_position(scene_crate)
	print("scene crate after 2 s: position %s, time %s" % [scene_rest, sw.get_time()])
	check(abs(sw.get_time() - 2.0) < 1e-4, "get_time after 120 steps of 1/60 s: %s" % sw.get_time())
	check(abs(scene_rest.y + 16.0 - 380.0) <= 1.5 and abs(scene_rest.x - 200.0) <= 1.0,
		"the scene's crate rests on the ground: bottom %.2f within 1.5 px of 380" % (scene_rest.y + 16.0))

	# A malformed scene (a plain path this time) is refused; the world stays as it was.
	var bad = sw.load_scene(tmp + "/bad.json")
	var bad_err = sw.get_last_error()
	check(bad == null and bad_err.find("load_scene") >= 0 and bad_err.find("bodies[0].density: expected a number > 0") >= 0,
		"malformed scene refused: %s" % bad_err)
	check(sw.get_bodies().size() == 2 and sw.get_position(scene_crate) == scene_rest,
		"after the failed load_scene the scene's world is still there")
	var missing = "res://no_such_scene.json"
	check(sw.load_scene(missing) == null and sw.get_last_error().find(ProjectSettings.globalize_path(missing)) >= 0
		and sw.get_last_error().find("PP_ERR_IO") >= 0, "a res:// path is globalized: %s" % sw.get_last_error())
	check(sw.load_scene(42) == null and sw.get_last_error().find("expected String") >= 0,
		"load_scene(42) refused: %s" % sw.get_last_error())
	check(sw.load_snapshot("") == null and sw.get_last_error().find("empty path") >= 0,
		"load_snapshot(\"\") refused: %s" % sw.get_last_error())
	check(sw.save_snapshot(tmp) == null and sw.get_last_error().find("save_snapshot") >= 0,
		"save_snapshot into a folder that is no snapshot refused: %s" % sw.get_last_error())
	# Loaded again, the object's world takes the first world's slot back: ints of both earlier worlds stay stale.
	check(sw.load_scene(tmp_user + "/scene.json") == true, "load_scene again: %s" % sw.get_last_error())
	check(sw.get_position(old) == null and sw.get_last_error().find("PP_ERR_INVALID_HANDLE") >= 0,
		"an int from two worlds ago is stale: %s" % sw.get_last_error())
	check(sw.get_position(scene_crate) == null and sw.get_last_error().find("PP_ERR_INVALID_HANDLE") >= 0,
		"an int from the last world is stale: %s" % sw.get_last_error())
	check(body_of_mass(sw, 1024.0) != null, "the new world's crate answers")

	# A snapshot after 30 steps, loaded into a second object, continues exactly as the original.
	var orig = PhysPixWorld.new()
	orig.load_scene(tmp + "/scene.json")
	steps(orig, 30)
	var snap = tmp + "/snap"
	var saved_at = orig.get_time()
	var at_save = orig.get_position(body_of_mass(orig, 1024.0))
	var saved = orig.save_snapshot(snap)
	check(saved == true and dir.file_exists(snap + "/world.json"), "save_snapshot(\"%s\") -> %s %s"
		% [snap, saved, orig.get_last_error()])
	steps(orig, 60)
	var copy = PhysPixWorld.new()
	check(copy.load_snapshot(snap) == true and copy.get_time() == saved_at,
		"load_snapshot into a second PhysPixWorld: time %s == %s %s" % [copy.get_time(), saved_at, copy.get_last_error()])
	steps(copy, 60)
	var crate_a = body_of_mass(orig, 1024.0)
	var crate_b = body_of_mass(copy, 1024.0)
	var pa = orig.get_position(crate_a)
	var pb = copy.get_position(crate_b)
	print("crate at the snapshot %s, 60 steps on: original %s, loaded %s" % [at_save, pa, pb])
	check(crate_b != null and pa == pb and orig.get_angle(crate_a) == copy.get_angle(crate_b)
		and orig.get_linear_velocity(crate_a) == copy.get_linear_velocity(crate_b),
		"the loaded crate's position, angle and velocity == the original's")
	check(pa != at_save, "and it moved after the snapshot (%s -> %s), so the comparison means something" % [at_save, pa])
	check(remove_tree(tmp), "removed %s" % tmp)

	# The same in memory: save_state, 60 steps, restore_state and 60 steps again; load_state into a third object.
	var mem_orig = orig.save_state()
	var mem_hash = orig.get_hash()
	check(typeof(mem_orig) == TYPE_RAW_ARRAY and mem_orig.size() > 0 and is_int(mem_hash),
		"save_state() -> %d bytes, get_hash() -> %s %s" % [mem_orig.size(), mem_hash, orig.get_last_error()])
	steps(orig, 60)
	var mem_first = orig.get_position(crate_a)
	check(orig.restore_state(mem_orig) == true and orig.get_hash() == mem_hash,
		"restore_state: the hash as saved %s" % orig.get_last_error())
	steps(orig, 60)
	check(orig.get_position(crate_a) == mem_first, "restored, 60 steps on: %s == %s" % [orig.get_position(crate_a), mem_first])
	var mem_copy = PhysPixWorld.new()
	check(mem_copy.load_state(mem_orig) == true and mem_copy.get_hash() == mem_hash,
		"load_state into a third PhysPixWorld hashes as saved %s" % mem_copy.get_last_error())
	var mem_cut = mem_orig.subarray(0, 63)
	check(orig.restore_state(mem_cut) == null and orig.get_last_error().find("PP_ERR_FORMAT") >= 0,
		"cut state bytes refused: %s" % orig.get_last_error())

	test_rays_and_queries()
	test_explode_and_casts()
	test_sensor()
	test_landing_and_impulses()
	test_contact_events_switch()
	test_one_way()
	check(test_native_gains() == true, "test_native_gains ran to its end (no script error)")
	check(test_joints() == true, "test_joints ran to its end (no script error)")
	check(test_wheel_and_motor_joints() == true, "test_wheel_and_motor_joints ran to its end (no script error)")
	check(test_handle_kinds() == true, "test_handle_kinds ran to its end (no script error)")
	check(test_pixel_calls_with_huge_arguments() == true, "test_pixel_calls_with_huge_arguments ran to its end")
	check(test_settings_at_creation() == true, "test_settings_at_creation ran to its end (no script error)")
	check(test_debug_draw() == true, "test_debug_draw ran to its end (no script error)")

	# Each PhysPixWorld owns one pp_world, freed with the Reference: more than PP_MAX_WORLDS (4096)
	# made and dropped in turn must all succeed.
	var made = 0
	for i in range(5000):
		var scratch = PhysPixWorld.new()
		scratch.step(DT)
		if scratch.get_last_error() != "":
			print(scratch.get_last_error())
			break
		made += 1
	check(made == 5000, "%d worlds made and dropped one after another (the destructor frees each)" % made)

	finish()
