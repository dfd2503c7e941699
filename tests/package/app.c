/* A program built against an installed PhysPix (tests/package/test_package.py): a crate falls onto a
 * static ground and comes to rest on it. Prints the library's version; exit 0 only if the crate rests. */
#include <physpix.h>

#include <stdio.h>
#include <string.h>

int main(void)
{
    static uint8_t ground_mask[16 * 256], crate_mask[16 * 16];
    memset(ground_mask, 1, sizeof ground_mask);
    memset(crate_mask, 1, sizeof crate_mask);

    pp_world_def wd = pp_world_def_default();
    pp_world w;
    if (pp_world_create(&wd, &w) != PP_OK) return fprintf(stderr, "%s\n", pp_last_error()), 1;
    pp_body_def gd = pp_body_def_default();
    gd.type = PP_BODY_STATIC;
    gd.width = 256, gd.height = 16, gd.mask = ground_mask;
    gd.position = (pp_vec2){128, 208};          /* top surface at y = 200 */
    pp_body_def cd = pp_body_def_default();
    cd.width = 16, cd.height = 16, cd.mask = crate_mask;
    cd.position = (pp_vec2){128, 100};
    pp_body ground, crate;
    if (pp_body_create(w, &gd, &ground) != PP_OK || pp_body_create(w, &cd, &crate) != PP_OK)
        return fprintf(stderr, "%s\n", pp_last_error()), 1;
    for (int i = 0; i < 120; i++)
        if (pp_world_step(w, 1.0f / 60) != PP_OK) return fprintf(stderr, "%s\n", pp_last_error()), 1;
    pp_vec2 p;
    if (pp_body_get_position(w, crate, &p) != PP_OK) return 1;
    unsigned v = pp_version();
    printf("physpix %u.%u.%u crate y %.2f\n", v / 10000, v / 100 % 100, v % 100, p.y);
    pp_world_destroy(w);
    return p.y > 190.0f && p.y < 193.0f ? 0 : 1;   /* centre 8 px above the surface, within the slop */
}
