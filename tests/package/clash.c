/* Linked statically against libphyspix.a (tests/package/test_package.py): it defines names that the
 * library uses internally, and calls entry points whose objects use them. It links only if the archive
 * keeps its internals local. */
#include <physpix.h>

#include <stdio.h>

int read_int(void) { return 2; }
int parse_json(void) { return 3; }
int world_lookup(void) { return 5; }
int body_free(void) { return 7; }

int main(void)
{
    pp_world_def wd = pp_world_def_default();
    pp_world w, scene;
    if (pp_world_create(&wd, &w) != PP_OK) return 1;
    pp_status s = pp_world_load_scene("/nonexistent/scene.json", &scene);   /* reaches the scene reader */
    printf("%d %s\n", read_int() * parse_json() * world_lookup() * body_free(), pp_status_name(s));
    return pp_world_destroy(w) == PP_OK && s == PP_ERR_IO ? 0 : 1;
}
