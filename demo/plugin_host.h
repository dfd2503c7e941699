/* The reference host's loader: read a plugin manifest (INI), check compatibility, dlopen the
 * library for this platform, call its entry and initialise it up to the level it needs. */
#ifndef PP_PLUGIN_HOST_H
#define PP_PLUGIN_HOST_H

#include "physpix_plugin.h"

#include <stddef.h>
#include <string.h>

/// This host's platform tag in a manifest's [libraries] section, e.g. "linux.x86_64".
#if defined(__linux__) && defined(__x86_64__)
#define HOST_PLATFORM "linux.x86_64"
#elif defined(__linux__) && defined(__aarch64__)
#define HOST_PLATFORM "linux.arm64"
#else
#define HOST_PLATFORM "unknown"
#endif

/// What a manifest says, with the library path resolved against the manifest's folder.
typedef struct host_manifest {
    char entry_symbol[128];         ///< [configuration] entry_symbol
    uint32_t compatibility_minimum; ///< [configuration] compatibility_minimum: the oldest interface version it needs
    char library[4096];             ///< [libraries] <platform>, as a path usable from the current directory
} host_manifest;

/// A loaded and initialised plugin.
typedef struct host_plugin {
    void *library;            ///< dlopen handle
    pp_plugin_interface api;  ///< what the entry filled
    int level;                ///< highest level initialised, -1 if none
} host_plugin;

/// Parse a manifest for `platform`; on failure err receives "<path>:<line>: what is wrong".
pp_status host_manifest_read(const char *path, const char *platform, host_manifest *out, char *err, size_t err_size);

/// Load the plugin a manifest names with `host` as the host interface; on failure err says why and nothing stays loaded.
pp_status host_plugin_load(const char *manifest_path, const pp_host_interface *host, host_plugin *out, char *err,
                           size_t err_size);

/// Deinitialise every level and unload the library.
void host_plugin_unload(host_plugin *p);

/// Variants to pass as arguments (the data stays the caller's): a float, an int, a vec2 (px), a string, bytes, an object.
#define V_FLOAT(x) ((pp_variant){.type = PP_VARIANT_FLOAT, .as.real = (x)})
#define V_INT(x) ((pp_variant){.type = PP_VARIANT_INT, .as.integer = (x)})
#define V_VEC2(x, y) ((pp_variant){.type = PP_VARIANT_VEC2, .as.vec2 = {(float)(x), (float)(y)}})
#define V_STR(s) ((pp_variant){.type = PP_VARIANT_STRING, .as.string = {(s), (int64_t)strlen(s)}})
#define V_BYTES(p, n) ((pp_variant){.type = PP_VARIANT_BYTES, .as.bytes = {(p), (int64_t)(n)}})
#define V_OBJ(o) ((pp_variant){.type = PP_VARIANT_OBJECT, .as.object = (o)})

/// A variant type's name as the plugin's messages spell it ("float", "vec2", ...).
const char *host_type_name(pp_variant_type t);

/// The class of that name, or NULL.
const pp_plugin_class *host_plugin_class(const host_plugin *p, const char *name);

#endif
