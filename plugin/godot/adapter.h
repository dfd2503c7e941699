/* What the PhysPixWorld class's files share: one call's checked arguments, the method table's entry,
 * the error reporting every method uses, and the methods that live outside physpix_godot.c. */
#ifndef PHYSPIX_GODOT_ADAPTER_H
#define PHYSPIX_GODOT_ADAPTER_H

#include "gdn.h"
#include "physpix.h"

#define CLASS_NAME "PhysPixWorld"
#define MAX_ARGS 8
#define PATH_SIZE 4096 /* a path argument's UTF-8 bytes, with the terminating NUL */

typedef struct world_inst {
    pp_world world;  /* id 0 if pp_world_create failed; every call then reports the stale handle */
    char error[512]; /* why the last call failed, "" if it succeeded */
} world_inst;

/* One argument after its type was checked, read as its spec letter says. */
typedef struct arg {
    const godot_variant *var;
    int64_t i;
    float f;
    pp_vec2 v;
    pp_body body;
    pp_joint joint;
    pp_body_type type;
    godot_object *object;
    const char *path; /* 'p': the call's path buffer, res:// and user:// made absolute */
} arg;

struct method_def;

/* One call of a method: who, which, and the checked arguments. */
typedef struct call {
    world_inst *self;
    const struct method_def *def;
    int argc;
    arg a[MAX_ARGS];
    char *path; /* PATH_SIZE bytes for the one path argument a method may have (not zeroed per call) */
} call;

typedef godot_variant (*method_fn)(call *c);

/* A GDScript-facing method (the table is methods_gen.h, generated from plugin/api/physpix_api.json). spec has one letter an argument, those after '|' optional:
 * i int, f float (an int is accepted), v Vector2, b body (int), t body type ("dynamic",
 * "static" or "kinematic"), p path (String; res:// and user://
 * become filesystem paths through ProjectSettings.globalize_path, others are used as given),
 * m collision mask bits (int, 0..0xffffffff), o body options, d world settings, J a joint's def and C a character's
 * (Dictionary, see fields.c), j joint (int),
 * B bool, I an Image or a Texture with a readable image (see pixels.c), M PoolByteArray. */
typedef struct method_def {
    const char *name;
    const char *spec;
    method_fn fn;
    const char *usage; /* quoted in error messages */
} method_def;


/* fail() and ok() are macros so that the engine's "At: file:line" names the check that failed. */
#define fail(...) fail_at(__FILE__, __LINE__, __VA_ARGS__)
#define ok(c, status) ok_at(__FILE__, __LINE__, c, status)

/* Records and prints why the call failed; returns false so checks read `return cond || fail(...)`. */
__attribute__((format(printf, 4, 5))) bool fail_at(const char *file, int line, call *c, const char *fmt, ...);
/* True on PP_OK; otherwise records the status and PhysPix's own message. */
bool ok_at(const char *file, int line, call *c, pp_status s);

/* A res:// or user:// path through ProjectSettings.globalize_path into out: its length (size or more: it did not
 * fit), 0 if the engine could not globalize it. */
size_t globalize_path(const char *given, char *out, size_t size);
/* A body's int for GDScript (0 stays 0: "no body" in events). */
godot_variant body_int(pp_body b);
/* True if w × h is a bitmap size PhysPix takes; otherwise records why. */
bool bitmap_size_ok(call *c, int64_t w, int64_t h);
/* Creates a body from def (width, height and its planes set): position args[first], type args[first + 1]
 * (default dynamic), options args[first + 2] (default none); its int, or nil on failure. */
godot_variant make_body(call *c, int first, pp_body_def *def);

/* A body's planes read from its options, malloc'd; freed by the caller once the body is made. */
typedef struct body_planes {
    uint8_t *mask, *weights;
} body_planes;

/* fields.c: Dictionaries of def fields. The world's settings (a "preset" first, then any pp_world_def field)
 * into a def, and back; a body's options (pp_body_def fields, plus "pivot", "collision_mask" and "weights")
 * into a def whose width and height are set. */
bool fields_world_def(call *c, const godot_variant *dict, pp_world_def *out);
godot_variant fields_world_dict(const pp_world_def *def);
bool fields_body_def(call *c, const godot_variant *dict, pp_body_def *def, body_planes *planes);
/* A joint's def: "type" (required, a lower-case name) picks pp_joint_def_default's defaults, then any other
 * pp_joint_def field; bodies and user_data are ints (body 0 is the static world). */
bool fields_joint_def(call *c, const godot_variant *dict, pp_joint_def *out);
/* A character's def: pp_character_def fields over the def's values (move_character). */
bool fields_character_def(call *c, const godot_variant *dict, pp_character_def *def);

/* pixels.c: Images and Textures in, a body's pixels out and in. */
bool pixels_bind(char *err, size_t err_size);
bool pixels_is_image_or_texture(godot_object *object);
/* One byte a pixel of the def's size into *out (malloc'd) from a PoolByteArray (as it is) or an Image or Texture:
 * a mask is 1 where alpha >= def->alpha_threshold and the brightest channel >= 128 (white on black or on
 * transparent), weights are the red channel (a grey image's level). */
bool pixels_plane(call *c, const godot_variant *src, const char *what, const pp_body_def *def, bool mask,
                  uint8_t **out);
godot_variant add_body_image(call *c);
godot_variant read_mask(call *c);
godot_variant read_weights(call *c);
godot_variant read_rgba(call *c);
godot_variant write_pixels(call *c);

#endif
