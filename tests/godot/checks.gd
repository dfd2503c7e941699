extends SceneTree
# What the Godot test scripts share: a check that prints its line, a tolerance, and the ending run.sh reads.

var failures = 0


func check(cond, what):
	print(("ok   " if cond else "FAIL ") + what)
	if not cond:
		failures += 1


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
