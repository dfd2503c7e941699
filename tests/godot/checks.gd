extends SceneTree
# What the Godot test scripts share: a check that prints its line, a tolerance, a texture of one colour, a body
# node, and the ending run.sh reads.

var failures = 0


func check(cond, what):
	print(("ok   " if cond else "FAIL ") + what)
	if not cond:
		failures += 1


# An ImageTexture w × h of one colour.
func texture(w, h, colour = Color(0.8, 0.6, 0.2)):
	var img = Image.new()
	img.create(w, h, false, Image.FORMAT_RGBA8)
	img.fill(colour)
	var t = ImageTexture.new()
	t.create_from_image(img, 0)
	return t


# A PhysPixBody2D node drawing tex at `at`, with the given properties, added under parent.
func add_body(parent, name, tex, at, options = {}):
	var b = load("res://addons/physpix/physpix_body_2d.gd").new()
	b.name = name
	b.texture = tex
	b.position = at
	for k in options:
		b.set(k, options[k])
	parent.add_child(b)
	return b


func near(a, b, tol):
	return abs(a - b) <= tol


# Prints "RESULT: PASS" and quits 0 if every check held; otherwise says how many failed and quits 1.
func finish():
	if failures == 0:
		print("RESULT: PASS")
		quit(0)
	else:
		print("RESULT: FAIL (%d checks)" % failures)
		quit(1)
