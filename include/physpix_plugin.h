/* PhysPix as an engine plugin, modelled on Godot's GDExtension: a manifest names the library and
 * its entry symbol; the entry receives the host's interface and fills the plugin's, which lists
 * classes and their typed methods and runs them through one generic call over tagged variants.
 * Only plain data and function pointers cross the boundary, so any host language can drive it. */
#ifndef PHYSPIX_PLUGIN_H
#define PHYSPIX_PLUGIN_H

#include "physpix.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The plugin-interface version this header describes; a host built for a newer one is refused.
#define PP_PLUGIN_INTERFACE_VERSION 1

/* The manifest (plugin/physpix.plugin, installed as PREFIX/lib/physpix.plugin) is an INI file in the format of
 * Godot's .gdextension: [configuration] entry_symbol and compatibility_minimum (the oldest interface version a
 * host must implement), and [libraries] one path per platform (linux.x86_64, linux.arm64), relative to the
 * manifest. Methods return one value; compound results come through getters, as contacts do
 * (get_contact_count, then get_contact_point(i) …), and raycast answers whether it hit, then get_ray_body,
 * get_ray_point, get_ray_normal and get_ray_fraction describe the hit; query_point, query_aabb and query_circle
 * answer a count and get_query_body(i) the bodies. set_body_options(is_sensor, one_way, one_way_direction)
 * applies to the bodies that later add_body* calls make. Joints are INTs (the pp_joint id): add_joint takes a
 * PhysPixBody, or the PhysPixWorld itself for the static world, for each body, set_joint_options applies to later
 * joints, and the PhysPixWorld's *_joint_* methods take the int. Units are those of physpix.h: px, s, rad. */

/// The entry symbol's default name, as written in plugin/physpix.plugin.
#define PP_PLUGIN_ENTRY_SYMBOL "pp_plugin_entry"

/// What a variant holds.
typedef enum pp_variant_type {
    PP_VARIANT_NIL = 0,    ///< nothing
    PP_VARIANT_BOOL = 1,   ///< as.boolean, 0 or 1
    PP_VARIANT_INT = 2,    ///< as.integer
    PP_VARIANT_FLOAT = 3,  ///< as.real (an INT argument is accepted where FLOAT is declared)
    PP_VARIANT_VEC2 = 4,   ///< as.vec2, px or px/s per the method
    PP_VARIANT_STRING = 5, ///< as.string, UTF-8, NUL-terminated
    PP_VARIANT_BYTES = 6,  ///< as.bytes, a byte buffer
    PP_VARIANT_OBJECT = 7, ///< as.object, an object id made by the plugin; 0 is never valid
    PP_VARIANT_ERROR = 8,  ///< as.error, a failed call's status and message (returned only)
    PP_VARIANT_TYPE_FORCE_U32 = 0x7fffffff
} pp_variant_type;

/// A tagged value passed to and returned from plugin calls (24 bytes).
typedef struct pp_variant {
    pp_variant_type type; ///< which member of `as` is valid
    uint32_t reserved;    ///< zero
    union {
        uint32_t boolean; ///< BOOL
        int64_t integer;  ///< INT
        double real;      ///< FLOAT
        pp_vec2 vec2;     ///< VEC2
        uint64_t object;  ///< OBJECT
        struct {
            const char *data; ///< UTF-8 text with a terminating NUL
            int64_t length;   ///< bytes before the NUL
        } string;             ///< STRING
        struct {
            const uint8_t *data; ///< the bytes
            int64_t length;      ///< how many, bytes
        } bytes;                 ///< BYTES
        struct {
            pp_status status;    ///< why the call failed
            uint32_t reserved;   ///< zero
            const char *message; ///< what failed and why, NUL-terminated
        } error;                 ///< ERROR
    } as;
} pp_variant;

/// Initialisation levels, run upward by initialize and downward by deinitialize.
typedef enum pp_plugin_level {
    PP_PLUGIN_LEVEL_CORE = 0,    ///< process-wide state
    PP_PLUGIN_LEVEL_SERVERS = 1, ///< services the scene level uses
    PP_PLUGIN_LEVEL_SCENE = 2,   ///< classes become creatable
    PP_PLUGIN_LEVEL_EDITOR = 3,  ///< editor-only features (none in PhysPix)
    PP_PLUGIN_LEVEL_FORCE_U32 = 0x7fffffff
} pp_plugin_level;

/// One argument of a method.
typedef struct pp_plugin_arg {
    const char *name;       ///< argument name, e.g. "dt"
    pp_variant_type type;   ///< expected type
    uint32_t reserved;      ///< zero
    const char *class_name; ///< OBJECT arguments: the class expected; otherwise NULL
} pp_plugin_arg;

/// One method of a class.
typedef struct pp_plugin_method {
    const char *name;            ///< method name, e.g. "step"
    const char *doc;             ///< one line with units
    pp_variant_type return_type; ///< type of a successful result
    int32_t arg_count;           ///< number of arguments
    const pp_plugin_arg *args;   ///< arg_count arguments
    const char *return_class;    ///< OBJECT results: the class returned; otherwise NULL
} pp_plugin_method;

/// One class the plugin provides.
typedef struct pp_plugin_class {
    const char *name;                 ///< class name, e.g. "PhysPixWorld"
    const char *base;                 ///< the host class it derives from, e.g. "RefCounted"
    const char *doc;                  ///< one line
    uint32_t instantiable;            ///< nonzero: object_create makes one; zero: only methods return them
    int32_t method_count;             ///< number of methods
    const pp_plugin_method *methods;  ///< method_count methods
} pp_plugin_class;

/// Log function a host provides: level 0 debug, 1 info, 2 warning, 3 error; message valid during the call.
typedef void (*pp_host_log_fn)(int level, const char *message, void *user);

/// What the host hands the entry function.
typedef struct pp_host_interface {
    uint32_t struct_size;       ///< sizeof(pp_host_interface) as the host was built
    uint32_t interface_version; ///< PP_PLUGIN_INTERFACE_VERSION the host was built for
    const char *host_name;      ///< for messages, e.g. "physpix reference host"
    pp_host_log_fn log;         ///< may be NULL
    void *user;                 ///< passed back to log
} pp_host_interface;

/// What the entry function fills. Returned STRING, BYTES and ERROR variants are the plugin's: the
/// host releases each with variant_clear (harmless on any variant); arguments stay the host's.
typedef struct pp_plugin_interface {
    uint32_t struct_size;           ///< sizeof(pp_plugin_interface) as the plugin was built
    uint32_t interface_version;     ///< PP_PLUGIN_INTERFACE_VERSION the plugin implements
    const char *name;               ///< "PhysPix"
    uint32_t library_version;       ///< pp_version() of the library behind it
    pp_plugin_level minimum_level;  ///< the level that must be initialised before classes are used
    /// Initialise one level; levels go up one at a time from CORE.
    pp_status (*initialize)(pp_plugin_level level);
    /// Deinitialise one level, highest first; SCENE destroys every object still alive.
    void (*deinitialize)(pp_plugin_level level);
    int32_t class_count;            ///< number of classes
    const pp_plugin_class *classes; ///< class_count classes, valid until the library is unloaded
    /// Create an object of an instantiable class: ret is OBJECT, or ERROR.
    void (*object_create)(const char *class_name, pp_variant *ret);
    /// Destroy an object and what it owns (a world's bodies; a body's pixels): ret is NIL, or ERROR.
    void (*object_destroy)(uint64_t object, pp_variant *ret);
    /// Call a method by name with argc arguments: ret is the method's result, or ERROR.
    void (*call)(uint64_t object, const char *method, const pp_variant *args, int32_t argc, pp_variant *ret);
    /// Release what a returned variant owns and make it NIL.
    void (*variant_clear)(pp_variant *v);
} pp_plugin_interface;

/// The entry function named by the manifest's entry_symbol: PP_OK, or PP_ERR_UNSUPPORTED (logged) for an
/// interface version the plugin does not implement, PP_ERR_ABI for a struct_size it does not know.
typedef pp_status (*pp_plugin_entry_fn)(const pp_host_interface *host, pp_plugin_interface *out);

/// The PhysPix plugin's entry function (exported by libphyspix_plugin.so).
PP_API pp_status pp_plugin_entry(const pp_host_interface *host, pp_plugin_interface *out);

#ifdef __cplusplus
}
#endif

#endif /* PHYSPIX_PLUGIN_H */
