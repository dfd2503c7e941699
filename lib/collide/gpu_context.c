/* EGL bring-up without a window and the GL loader. Display: a hardware device through
 * EGL_EXT_platform_device, else Mesa's surfaceless platform, else the default display; then a
 * GLES 3.1 context with no surface, and the compute programs compiled once. */
#include "gpu_context.h"
#include "status.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <dlfcn.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GPU_EGL_FUNCS(X)                                                                                \
    X(PFNEGLGETPROCADDRESSPROC, GetProcAddress) X(PFNEGLQUERYSTRINGPROC, QueryString)                   \
    X(PFNEGLGETDISPLAYPROC, GetDisplay) X(PFNEGLINITIALIZEPROC, Initialize)                             \
    X(PFNEGLTERMINATEPROC, Terminate) X(PFNEGLBINDAPIPROC, BindAPI)                                     \
    X(PFNEGLCHOOSECONFIGPROC, ChooseConfig) X(PFNEGLCREATECONTEXTPROC, CreateContext)                   \
    X(PFNEGLMAKECURRENTPROC, MakeCurrent) X(PFNEGLGETERRORPROC, GetError)

static struct {
#define GPU_EGL_MEMBER(type, name) type name;
    GPU_EGL_FUNCS(GPU_EGL_MEMBER)
#undef GPU_EGL_MEMBER
    PFNEGLGETPLATFORMDISPLAYEXTPROC GetPlatformDisplayEXT;
    PFNEGLQUERYDEVICESEXTPROC QueryDevicesEXT;
    PFNEGLQUERYDEVICESTRINGEXTPROC QueryDeviceStringEXT;
} egl;

static pthread_mutex_t gpu_lock = PTHREAD_MUTEX_INITIALIZER;
static bool tried;
static pp_status outcome;
static char failure[400];
static EGLDisplay display = EGL_NO_DISPLAY;
static EGLContext context = EGL_NO_CONTEXT;
static gpu_gl gl;
static gpu_info info;
static GLuint programs[GPU_PROG_COUNT];
static const char *program_names[GPU_PROG_COUNT] = {"narrow_tiles", "narrow_args",   "narrow_sums",
                                                    "narrow_normal", "narrow_strips", "narrow_finish"};

/* Record why bring-up failed; every later GPU request reports the same reason. */
static pp_status __attribute__((format(printf, 1, 2))) bring_up_failed(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(failure, sizeof failure, fmt, ap);
    va_end(ap);
    return PP_ERR_UNSUPPORTED;
}

static bool has_extension(const char *list, const char *name)
{
    const size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    return false;
}

static pp_status load_libraries(void)
{
    static bool loaded;
    if (loaded)
        return PP_OK;
    /* PHYSPIX_LIBEGL names another EGL (a vendor's, outside the loader's path). */
    const char *egl_name = getenv("PHYSPIX_LIBEGL") ? getenv("PHYSPIX_LIBEGL") : "libEGL.so.1";
    void *libegl = dlopen(egl_name, RTLD_NOW | RTLD_LOCAL);
    if (!libegl)
        return bring_up_failed("cannot load %s (%s)", egl_name, dlerror());
    void *libgles = dlopen("libGLESv2.so.2", RTLD_NOW | RTLD_LOCAL);
    if (!libgles)
        return bring_up_failed("cannot load libGLESv2.so.2 (%s)", dlerror());
#define GPU_EGL_LOAD(type, name)                                                                        \
    if (!(egl.name = (type)dlsym(libegl, "egl" #name)))                                                 \
        return bring_up_failed("%s lacks egl" #name, egl_name);
    GPU_EGL_FUNCS(GPU_EGL_LOAD)
#undef GPU_EGL_LOAD
#define GPU_GL_LOAD(type, name)                                                                         \
    if (!(gl.name = (type)dlsym(libgles, "gl" #name)) && !(gl.name = (type)egl.GetProcAddress("gl" #name))) \
        return bring_up_failed("libGLESv2.so.2 lacks gl" #name);
    GPU_GL_FUNCS(GPU_GL_LOAD)
#undef GPU_GL_LOAD
    egl.GetPlatformDisplayEXT = (PFNEGLGETPLATFORMDISPLAYEXTPROC)egl.GetProcAddress("eglGetPlatformDisplayEXT");
    egl.QueryDevicesEXT = (PFNEGLQUERYDEVICESEXTPROC)egl.GetProcAddress("eglQueryDevicesEXT");
    egl.QueryDeviceStringEXT = (PFNEGLQUERYDEVICESTRINGEXTPROC)egl.GetProcAddress("eglQueryDeviceStringEXT");
    loaded = true;
    return PP_OK; /* the libraries stay loaded for the life of the process */
}

/* Whether EGL lists its devices and every one is Mesa's software device. A GPU driver lists one device per GPU,
 * and Mesa one per render node it drives, so then any context this process can make is a CPU rasteriser. */
static bool only_software_devices(void)
{
    const char *client = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!egl.QueryDevicesEXT || !egl.QueryDeviceStringEXT || !has_extension(client, "EGL_EXT_device_enumeration"))
        return false;
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!egl.QueryDevicesEXT(16, devices, &n) || n < 1)
        return false;
    for (EGLint i = 0; i < n; i++)
        if (!has_extension(egl.QueryDeviceStringEXT(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
            return false;
    return true;
}

static bool initialize(EGLDisplay d, const char *platform)
{
    EGLint major, minor;
    if (d == EGL_NO_DISPLAY || !egl.Initialize(d, &major, &minor))
        return false;
    display = d;
    info.platform = platform;
    return true;
}

/* A hardware device first (a GPU driver offers one per GPU; Mesa's software device is skipped
 * here and reached through the surfaceless platform instead), then surfaceless, then default. */
static pp_status open_display(void)
{
    const char *client = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (egl.GetPlatformDisplayEXT && egl.QueryDevicesEXT && has_extension(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[16];
        EGLint n = 0;
        if (egl.QueryDevicesEXT(16, devices, &n)) {
            for (EGLint i = 0; i < n; i++) {
                const char *ext = egl.QueryDeviceStringEXT ? egl.QueryDeviceStringEXT(devices[i], EGL_EXTENSIONS) : "";
                if (has_extension(ext, "EGL_MESA_device_software"))
                    continue;
                if (initialize(egl.GetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL), "device"))
                    return PP_OK;
            }
        }
    }
    if (egl.GetPlatformDisplayEXT && has_extension(client, "EGL_MESA_platform_surfaceless") &&
        initialize(egl.GetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL), "surfaceless"))
        return PP_OK;
    if (initialize(egl.GetDisplay(EGL_DEFAULT_DISPLAY), "default"))
        return PP_OK;
    return bring_up_failed("no EGL display: the device, surfaceless and default platforms all failed "
                           "(EGL error 0x%x)", (unsigned)egl.GetError());
}

static pp_status create_context(void)
{
    if (!egl.BindAPI(EGL_OPENGL_ES_API))
        return bring_up_failed("eglBindAPI(EGL_OPENGL_ES_API) failed (EGL error 0x%x)", (unsigned)egl.GetError());
    const char *ext = egl.QueryString(display, EGL_EXTENSIONS);
    if (!has_extension(ext, "EGL_KHR_surfaceless_context"))
        return bring_up_failed("the EGL display lacks EGL_KHR_surfaceless_context");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(ext, "EGL_KHR_no_config_context")) {
        const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
        EGLint n = 0;
        if (!egl.ChooseConfig(display, want, &config, 1, &n) || n < 1)
            return bring_up_failed("eglChooseConfig found no GLES 3 config (EGL error 0x%x)",
                                   (unsigned)egl.GetError());
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 1, EGL_NONE};
    context = egl.CreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (context == EGL_NO_CONTEXT)
        return bring_up_failed("eglCreateContext for GLES 3.1 failed (EGL error 0x%x)", (unsigned)egl.GetError());
    if (!egl.MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        return bring_up_failed("eglMakeCurrent failed (EGL error 0x%x)", (unsigned)egl.GetError());
    return PP_OK;
}

static pp_status compile_program(gpu_program_id id)
{
    const char *text = NULL;
    for (int i = 0; i < gpu_shader_source_count; i++)
        if (!strcmp(gpu_shader_sources[i].name, program_names[id]))
            text = gpu_shader_sources[i].text;
    if (!text)
        return bring_up_failed("shader %s is not built in", program_names[id]);
    char log[256] = "";
    GLint ok = 0;
    const GLuint sh = gl.CreateShader(GL_COMPUTE_SHADER);
    gl.ShaderSource(sh, 1, &text, NULL);
    gl.CompileShader(sh);
    gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        gl.GetShaderInfoLog(sh, sizeof log, NULL, log);
        gl.DeleteShader(sh);
        return bring_up_failed("compiling glsl/%s.comp failed: %s", program_names[id], log);
    }
    const GLuint prog = gl.CreateProgram();
    gl.AttachShader(prog, sh);
    gl.LinkProgram(prog);
    gl.DeleteShader(sh);
    gl.GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        gl.GetProgramInfoLog(prog, sizeof log, NULL, log);
        gl.DeleteProgram(prog);
        return bring_up_failed("linking glsl/%s.comp failed: %s", program_names[id], log);
    }
    programs[id] = prog;
    return PP_OK;
}

static pp_status bring_up(void)
{
    pp_status st;
    if ((st = load_libraries()) || (st = open_display()) || (st = create_context()))
        return st;
    info.renderer = (const char *)gl.GetString(GL_RENDERER);
    info.renderer = info.renderer ? info.renderer : "unknown";
    info.software = strstr(info.renderer, "llvmpipe") || strstr(info.renderer, "softpipe") ||
                    strstr(info.renderer, "swrast") || strstr(info.renderer, "lavapipe");
    GLint v = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &v);
    info.max_ssbo_bytes = v;
    gl.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &v);
    info.max_groups_x = v;
    for (int id = 0; id < GPU_PROG_COUNT; id++)
        if ((st = compile_program((gpu_program_id)id)))
            return st;
    pp_log(1, "physpix: GPU backend on %s (EGL %s platform)", info.renderer, info.platform);
    return PP_OK;
}

pp_status gpu_acquire(const char *fn, const gpu_gl **out_gl, const gpu_info **out_info)
{
    pthread_mutex_lock(&gpu_lock);
    if (!tried) {
        tried = true;
        outcome = bring_up();
        if (outcome) {
            pp_log(2, "physpix: no GPU backend: %s", failure);
            if (display != EGL_NO_DISPLAY)
                egl.MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
    } else if (!outcome && !egl.MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        const long code = (long)egl.GetError();
        pthread_mutex_unlock(&gpu_lock);
        return pp_fail(PP_ERR_UNSUPPORTED, "%s: eglMakeCurrent failed (EGL error 0x%lx)", fn, code);
    }
    if (outcome) {
        pthread_mutex_unlock(&gpu_lock);
        return pp_fail(outcome, "%s: no GLES 3.1 compute context: %s", fn, failure);
    }
    *out_gl = &gl;
    *out_info = &info;
    return PP_OK;
}

pp_status gpu_probe_software(const char *fn, bool *software)
{
    pthread_mutex_lock(&gpu_lock);
    static int listed = -1; /* only_software_devices(), asked once */
    if (!tried && listed < 0)
        listed = load_libraries() == PP_OK && only_software_devices();
    const bool told = !tried && listed == 1;
    pthread_mutex_unlock(&gpu_lock);
    if (told) {
        *software = true;
        return PP_OK;
    }
    const gpu_gl *g;
    const gpu_info *i;
    const pp_status st = gpu_acquire(fn, &g, &i);
    if (st)
        return st;
    *software = i->software;
    gpu_release();
    return PP_OK;
}

bool gpu_is_up(void)
{
    pthread_mutex_lock(&gpu_lock);
    const bool up = tried && !outcome;
    pthread_mutex_unlock(&gpu_lock);
    return up;
}

void gpu_release(void)
{
    egl.MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    pthread_mutex_unlock(&gpu_lock);
}

GLuint gpu_program(gpu_program_id id) { return programs[id]; }
