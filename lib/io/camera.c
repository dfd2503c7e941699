/* Cameras beside the worlds: one entry a world slot, keyed by the world's id, so that a world that never
 * set one, or a new world in a destroyed one's slot, reads the default without any clean-up. A world is
 * used from one thread at a time, and so is its entry. */
#include "camera.h"
#include "status.h"
#include "world.h"

#include <math.h>

static struct {
    uint64_t world_id;       /* whose camera it is; 0 for none */
    pp_camera camera;
} cameras[PP_MAX_WORLDS];

pp_camera camera_of(const world *wd)
{
    if (cameras[wd->slot].world_id == wd->handle.id)
        return cameras[wd->slot].camera;
    return (pp_camera){{480.0f, 270.0f}, 1.0f, 960, 540};
}

pp_status camera_set(const world *wd, const pp_camera *c, const char *fn)
{
    if (!isfinite(c->center.x) || !isfinite(c->center.y) || !(c->zoom > 0) || !isfinite(c->zoom))
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: center must be finite and zoom finite and > 0", fn);
    if (c->width < 1 || c->height < 1 || c->width > PP_MAX_BITMAP_SIDE || c->height > PP_MAX_BITMAP_SIDE)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: size %dx%d (width × height) must be within 1..%d px", fn,
                       (int)c->width, (int)c->height, PP_MAX_BITMAP_SIDE);
    cameras[wd->slot].world_id = wd->handle.id;
    cameras[wd->slot].camera = *c;
    return PP_OK;
}

PP_API pp_status pp_world_get_camera(pp_world w, pp_camera *out)
{
    const world *wd = world_lookup(w, "pp_world_get_camera");
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!out)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "pp_world_get_camera: out is NULL");
    *out = camera_of(wd);
    return PP_OK;
}

PP_API pp_status pp_world_set_camera(pp_world w, const pp_camera *c)
{
    static const char *fn = "pp_world_set_camera";
    const world *wd = world_lookup(w, fn);
    if (!wd)
        return PP_ERR_INVALID_HANDLE;
    if (!c)
        return pp_fail(PP_ERR_INVALID_ARGUMENT, "%s: camera is NULL", fn);
    return camera_set(wd, c, fn);
}
