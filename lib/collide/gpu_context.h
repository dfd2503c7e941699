/* The process's one GLES 3.1 compute context, made without a window through EGL, with the GL
 * entry points loaded at run time (libEGL.so.1 and libGLESv2.so.2 are opened on first use, so a
 * CPU-only program needs neither). One context serves every world; GPU work is serialised. */
#ifndef PP_GPU_CONTEXT_H
#define PP_GPU_CONTEXT_H

#include "physpix.h"

#define EGL_EGL_PROTOTYPES 0
#define GL_GLES_PROTOTYPES 0
#include <GLES3/gl31.h>

#include <stdbool.h>
#include <stdint.h>

#define GPU_GL_FUNCS(X)                                                                                 \
    X(PFNGLGETSTRINGPROC, GetString) X(PFNGLGETINTEGERVPROC, GetIntegerv)                               \
    X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v) X(PFNGLGETERRORPROC, GetError)                             \
    X(PFNGLCREATESHADERPROC, CreateShader) X(PFNGLSHADERSOURCEPROC, ShaderSource)                       \
    X(PFNGLCOMPILESHADERPROC, CompileShader) X(PFNGLGETSHADERIVPROC, GetShaderiv)                       \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog) X(PFNGLDELETESHADERPROC, DeleteShader)               \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram) X(PFNGLATTACHSHADERPROC, AttachShader)                     \
    X(PFNGLLINKPROGRAMPROC, LinkProgram) X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                         \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog) X(PFNGLDELETEPROGRAMPROC, DeleteProgram)           \
    X(PFNGLUSEPROGRAMPROC, UseProgram) X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)               \
    X(PFNGLUNIFORM1UIPROC, Uniform1ui) X(PFNGLUNIFORM1IPROC, Uniform1i)                                 \
    X(PFNGLGENBUFFERSPROC, GenBuffers) X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                         \
    X(PFNGLBINDBUFFERPROC, BindBuffer) X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                       \
    X(PFNGLBUFFERDATAPROC, BufferData) X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                         \
    X(PFNGLCOPYBUFFERSUBDATAPROC, CopyBufferSubData) X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange)         \
    X(PFNGLUNMAPBUFFERPROC, UnmapBuffer) X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                   \
    X(PFNGLDISPATCHCOMPUTEINDIRECTPROC, DispatchComputeIndirect) X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)

typedef struct gpu_gl {
#define GPU_GL_MEMBER(type, name) type name;
    GPU_GL_FUNCS(GPU_GL_MEMBER)
#undef GPU_GL_MEMBER
} gpu_gl;

/* The compute programs, one per file in glsl/. */
typedef enum gpu_program_id {
    GPU_PROG_NARROW_TILES,
    GPU_PROG_NARROW_ARGS,
    GPU_PROG_NARROW_SUMS,
    GPU_PROG_NARROW_NORMAL,
    GPU_PROG_NARROW_STRIPS,
    GPU_PROG_NARROW_FINISH,
    GPU_PROG_COUNT
} gpu_program_id;

/* Shader sources generated from glsl/ at build time (build/gen/glsl_sources.c). */
typedef struct gpu_shader_source {
    const char *name, *text;
} gpu_shader_source;
extern const gpu_shader_source gpu_shader_sources[];
extern const int gpu_shader_source_count;

/* What the context can do, fixed after bring-up. */
typedef struct gpu_info {
    const char *renderer;       /* GL_RENDERER */
    const char *platform;       /* the EGL platform that gave the display */
    bool software;              /* a CPU rasteriser (llvmpipe, softpipe, swrast) */
    int64_t max_ssbo_bytes;     /* GL_MAX_SHADER_STORAGE_BLOCK_SIZE */
    int32_t max_groups_x;       /* GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] */
} gpu_info;

/* Bring the context up once (later calls return the first outcome), lock it and make it current
 * on this thread. On failure: PP_ERR_UNSUPPORTED, and pp_last_error() names the EGL/GL step. */
pp_status gpu_acquire(const char *fn, const gpu_gl **gl, const gpu_info **info);

/* Whether the context is, or would be, a CPU rasteriser. Where EGL lists only Mesa's software device this is
 * told without making the context (tens of ms, and its programs compiled, that AUTO would never use); otherwise
 * the context is brought up as gpu_acquire does, with its failures. */
pp_status gpu_probe_software(const char *fn, bool *software);

/* Whether the context has been brought up (the tests' view of what AUTO's probe spared). */
bool gpu_is_up(void);

/* Make the context not current and unlock it. */
void gpu_release(void);

/* A compiled program of the current context. */
GLuint gpu_program(gpu_program_id id);

#endif
