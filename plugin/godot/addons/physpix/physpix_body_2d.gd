extends Sprite
class_name PhysPixBody2D
# A PhysPix body drawn as a Sprite. Under a PhysPixWorld2D it makes its body when ready, from its texture
# (alpha >= alpha_threshold is solid) or its collision_mask, at its pose; the world moves it each physics
# frame. An edit redraws the rows it changed from the body's pixels, so holes show at once; the
# texture is then this node's own ImageTexture, never the shared resource it started from.

export(Texture) var collision_mask = null  # white opaque pixels are solid; overrides the texture's alpha
export(Texture) var weights = null  # grey level (red channel) 0..255: relative mass of each pixel
export(String, "dynamic", "static", "kinematic") var body_type = "dynamic"
export var density = 1.0 setget set_density  # mass of one solid pixel of weight 255
export var friction = 0.6 setget set_friction  # Coulomb coefficient; pairs use sqrt(fa·fb)
export var restitution = 0.0 setget set_restitution  # 0..1; pairs use the larger
export var gravity_scale = 1.0 setget set_gravity_scale  # dynamic bodies only
export var fixed_rotation = false
export var is_sensor = false  # reports sensor_begin/end on the world, collides with nothing
export var one_way = false  # a platform bodies land on from above and pass from below
export var detach_islands = false  # static bodies: islands an edit cuts loose fall as pieces
export(int, 1, 255) var alpha_threshold = 128
export var linear_velocity = Vector2()  # at creation, px/s
export var angular_velocity = 0.0  # at creation, rad/s

var body = 0  # the native body int; 0 before the body is made and after it is destroyed
var world_node = null  # the PhysPixWorld2D it belongs to
var _own_texture = false  # texture is this node's ImageTexture, drawn from the body's pixels
var _picture = null  # the Image that texture shows, once it is its own
var _texture_flags = 0  # of its own texture: no mipmaps (rows are updated in place); filter as the original had


func _ready():
	if body != 0 or Engine.editor_hint:
		return  # a piece: its world made it; in the editor the world draws the body nodes itself
	world_node = _find_world()
	if world_node == null:
		push_error("PhysPixBody2D %s: no PhysPixWorld2D above it" % name)
		return
	_make_body()


func _find_world():
	var n = get_parent()
	while n != null and not n.has_method("_drain_events"):
		n = n.get_parent()
	return n


func _make_body():
	var spec = world_node._body_spec(self)
	if spec == null:
		push_error("PhysPixBody2D %s: neither a texture nor a collision_mask to take its bitmap from" % name)
		return
	var w = world_node.get_world()
	var b = w.add_body_image(spec[0], spec[1], body_type, spec[2])
	if b == null:
		push_error("PhysPixBody2D %s: %s" % [name, w.get_last_error()])
		return
	body = b
	if gravity_scale != 1.0 and body_type == "dynamic":
		w.set_gravity_scale(body, gravity_scale)
	if texture != null and texture.flags & Texture.FLAG_FILTER:
		_texture_flags |= Texture.FLAG_FILTER
	world_node._register(self)


func _notification(what):
	if what == NOTIFICATION_PREDELETE and body != 0 and is_instance_valid(world_node) and world_node.world != null:
		world_node._unregister(self)
		world_node.world.destroy_body(body)
		body = 0


# ---- edits: positions are global, radii px ----

# Erases this body's pixels within radius of a global point; the hole shows at once. Returns how many.
func erase_circle(center, radius):
	var at = world_node.to_local(center)
	var n = world_node.world.erase_circle(body, at, radius)
	world_node._drain_events()  # first: a body erased whole has no pixels left to draw
	_redraw_circle(at, radius)
	return n


# Makes solid, with weight 1..255, this body's pixels within radius of a global point. Returns how many.
func paint_circle(center, radius, weight = 255):
	var at = world_node.to_local(center)
	var n = world_node.world.paint_circle(body, at, radius, weight)
	_redraw_circle(at, radius)
	return n


# ---- motion: vectors global, forces mass·px/s², impulses mass·px/s ----

# At a global point, or at the node's origin (the body's pivot) without one.
func apply_impulse(impulse, point = null):
	world_node.world.apply_impulse(body, _world_vector(impulse), _world_point(point))


func apply_force(force, point = null):
	world_node.world.apply_force(body, _world_vector(force), _world_point(point))


func apply_torque(torque):
	world_node.world.apply_torque(body, torque)


func set_velocity(linear, angular):
	world_node.world.set_velocity(body, _world_vector(linear), angular)


func _world_vector(v):
	return world_node.global_transform.basis_xform_inv(v)


func _world_point(p):
	return world_node.to_local(p) if p != null else world_node.world.get_position(body)


func get_linear_velocity():
	return world_node.global_transform.basis_xform(world_node.world.get_linear_velocity(body))


func get_angular_velocity():
	return world_node.world.get_angular_velocity(body)


func get_mass():
	return world_node.world.get_mass(body)


# ---- settable at run time ----

func set_density(v):
	density = v
	_send("set_density", v)


func set_friction(v):
	friction = v
	_send("set_friction", v)


func set_restitution(v):
	restitution = v
	_send("set_restitution", v)


func set_gravity_scale(v):
	gravity_scale = v
	_send("set_gravity_scale", v)


# Passes a property's new value to the body, once there is one.
func _send(setter, value):
	if body != 0:
		world_node.world.call(setter, body, value)


# ---- drawing the body's pixels ----

# The rows a circle (world frame) may have changed: its box in the bitmap, a pixel of margin.
func _redraw_circle(at, radius):
	if body == 0 or texture == null:
		return
	var w = world_node.world
	var local = w.get_transform(body).affine_inverse().xform(at) + w.get_pivot(body)
	var height = int(w.get_size(body).y)
	var y0 = int(clamp(floor(local.y - radius - 1), 0, height))
	var y1 = int(clamp(ceil(local.y + radius + 1), 0, height))
	if y1 > y0:
		_redraw_rows(y0, y1 - y0)


func _redraw_all():
	if body != 0 and texture != null:
		_redraw_rows(0, int(world_node.world.get_size(body).y))


# Copies rows y..y+rows-1 of the body's look into the picture and shows it. Only those rows are read from
# PhysPix; the texture is sent whole, since Godot 3.2's GLES2 renderer has no partial texture update.
func _redraw_rows(y, rows):
	if not _own_texture:
		_take_texture(texture.get_data())
	var w = world_node.world
	var width = int(w.get_size(body).x)
	var strip = Image.new()
	strip.create_from_data(width, rows, false, Image.FORMAT_RGBA8, w.read_rgba(body, y, rows))
	_picture.blit_rect(strip, Rect2(0, 0, width, rows), Vector2(0, y))
	texture.set_data(_picture)


# Draws into an ImageTexture of this node's own: the picture it started from where that has the body's size
# (its soft edges stay until an edit reaches them), else the body's pixels. The origin stays on the pivot.
func _take_texture(picture):
	var w = world_node.world
	var size = w.get_size(body)
	var look = Image.new()
	if picture != null and picture.get_size() == size:
		look = picture.duplicate()
		if look.is_compressed():
			look.decompress()
		look.convert(Image.FORMAT_RGBA8)
	else:
		look.create_from_data(int(size.x), int(size.y), false, Image.FORMAT_RGBA8, w.read_rgba(body))
	var tex = ImageTexture.new()
	tex.create_from_image(look, _texture_flags)
	texture = tex
	_picture = look
	_own_texture = true
	centered = true
	offset = size / 2 - w.get_pivot(body)


func _copy_settings(parent):
	for p in ["body_type", "density", "friction", "restitution", "gravity_scale", "fixed_rotation", "is_sensor",
			"one_way", "detach_islands", "alpha_threshold", "z_index", "z_as_relative", "modulate", "self_modulate",
			"material", "use_parent_material", "light_mask", "_texture_flags"]:
		set(p, parent.get(p))
