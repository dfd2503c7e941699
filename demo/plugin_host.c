/* Manifest parsing and plugin loading for the reference host. The manifest is INI, as Godot's
 * .gdextension files are: [configuration] entry_symbol and compatibility_minimum, [libraries]
 * keyed by platform tag, paths relative to the manifest. */
#include "plugin_host.h"

#include <ctype.h>
#include <dlfcn.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static pp_status failf(char *err, size_t size, pp_status st, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static pp_status failf(char *err, size_t size, pp_status st, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, size, fmt, ap);
    va_end(ap);
    return st;
}

/* Trim spaces in place and drop one pair of surrounding double quotes. */
static char *trim_value(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = 0;
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s[n - 1] = 0;
        s++;
    }
    return s;
}

/* The manifest's folder joined with a relative path; absolute paths stay as they are. */
static int resolve(const char *manifest, const char *rel, char *out, size_t size)
{
    if (rel[0] == '/')
        return snprintf(out, size, "%s", rel) < (int)size;
    const char *slash = strrchr(manifest, '/');
    const int dir = slash ? (int)(slash - manifest) : 1;
    return snprintf(out, size, "%.*s/%s", dir, slash ? manifest : ".", rel) < (int)size;
}

pp_status host_manifest_read(const char *path, const char *platform, host_manifest *out, char *err, size_t err_size)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return failf(err, err_size, PP_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    memset(out, 0, sizeof *out);
    char line[1024], section[64] = "", library[4096] = "", compat[64] = "";
    int lineno = 0;
    pp_status st = PP_OK;
    while (st == PP_OK && fgets(line, sizeof line, f)) {
        lineno++;
        char *s = trim_value(line);
        if (*s == 0 || *s == ';' || *s == '#')
            continue;
        if (*s == '[') {
            char *end = strchr(s, ']');
            if (!end || end[1] != 0 || end - s - 1 >= (long)sizeof section)
                st = failf(err, err_size, PP_ERR_FORMAT, "%s:%d: malformed section header '%s'", path, lineno, s);
            else
                snprintf(section, sizeof section, "%.*s", (int)(end - s - 1), s + 1);
            continue;
        }
        char *eq = strchr(s, '=');
        if (!eq) {
            st = failf(err, err_size, PP_ERR_FORMAT, "%s:%d: expected key = value, got '%s'", path, lineno, s);
            continue;
        }
        *eq = 0;
        const char *key = trim_value(s), *value = trim_value(eq + 1);
        if (strcmp(section, "configuration") == 0 && strcmp(key, "entry_symbol") == 0)
            snprintf(out->entry_symbol, sizeof out->entry_symbol, "%s", value);
        else if (strcmp(section, "configuration") == 0 && strcmp(key, "compatibility_minimum") == 0)
            snprintf(compat, sizeof compat, "%s", value);
        else if (strcmp(section, "libraries") == 0 && strcmp(key, platform) == 0)
            snprintf(library, sizeof library, "%s", value);
    }
    fclose(f);
    if (st != PP_OK)
        return st;
    char *end = NULL;
    const unsigned long v = strtoul(compat, &end, 10);
    if (!out->entry_symbol[0])
        return failf(err, err_size, PP_ERR_FORMAT, "%s: [configuration] has no entry_symbol", path);
    if (!compat[0] || *end != 0 || v == 0 || v > 1000)
        return failf(err, err_size, PP_ERR_FORMAT,
                     "%s: [configuration] compatibility_minimum must be an interface version (1, 2, ...), got '%s'",
                     path, compat);
    out->compatibility_minimum = (uint32_t)v;
    if (!library[0])
        return failf(err, err_size, PP_ERR_UNSUPPORTED, "%s: [libraries] has no library for platform %s", path,
                     platform);
    if (!resolve(path, library, out->library, sizeof out->library))
        return failf(err, err_size, PP_ERR_LIMIT, "%s: library path too long", path);
    return PP_OK;
}

pp_status host_plugin_load(const char *manifest_path, const pp_host_interface *host, host_plugin *out, char *err,
                           size_t err_size)
{
    memset(out, 0, sizeof *out);
    out->level = -1;
    host_manifest m;
    pp_status st = host_manifest_read(manifest_path, HOST_PLATFORM, &m, err, err_size);
    if (st != PP_OK)
        return st;
    if (m.compatibility_minimum > host->interface_version)
        return failf(err, err_size, PP_ERR_UNSUPPORTED,
                     "%s: the plugin needs plugin interface %u or newer; this host implements %u", manifest_path,
                     (unsigned)m.compatibility_minimum, (unsigned)host->interface_version);
    void *lib = dlopen(m.library, RTLD_NOW | RTLD_LOCAL);
    if (!lib)
        return failf(err, err_size, PP_ERR_IO, "%s: cannot load %s: %s", manifest_path, m.library, dlerror());
    pp_plugin_entry_fn entry;
    *(void **)&entry = dlsym(lib, m.entry_symbol); /* POSIX's sanctioned cast from object to function pointer */
    if (!entry) {
        dlclose(lib);
        return failf(err, err_size, PP_ERR_FORMAT, "%s: %s has no entry symbol '%s'", manifest_path, m.library,
                     m.entry_symbol);
    }
    out->api.struct_size = sizeof out->api;
    st = entry(host, &out->api);
    if (st != PP_OK) {
        dlclose(lib);
        return failf(err, err_size, st, "%s: the plugin's entry refused this host (status %d; its log says why)",
                     manifest_path, (int)st);
    }
    out->library = lib;
    for (int level = PP_PLUGIN_LEVEL_CORE; level <= (int)out->api.minimum_level; level++) {
        st = out->api.initialize((pp_plugin_level)level);
        if (st != PP_OK) {
            host_plugin_unload(out);
            return failf(err, err_size, st, "%s: initialize(%d) failed", manifest_path, level);
        }
        out->level = level;
    }
    return PP_OK;
}

void host_plugin_unload(host_plugin *p)
{
    for (; p->library && p->level >= 0; p->level--)
        p->api.deinitialize((pp_plugin_level)p->level);
    if (p->library)
        dlclose(p->library);
    p->library = NULL;
}

const pp_plugin_class *host_plugin_class(const host_plugin *p, const char *name)
{
    for (int32_t i = 0; i < p->api.class_count; i++)
        if (strcmp(p->api.classes[i].name, name) == 0)
            return &p->api.classes[i];
    return NULL;
}

const char *host_type_name(pp_variant_type t)
{
    static const char *names[] = {"nil", "bool", "int", "float", "vec2", "string", "bytes", "object", "error"};
    return (uint32_t)t < sizeof names / sizeof names[0] ? names[t] : "unknown";
}
