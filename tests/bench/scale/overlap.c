/* The overlap curve: two 256 px boxes overlapping by d px, one collision query timed alone:
 * pp_world_collide on the raster pair against dCollide on ODE's two analytic boxes. */
#include "physpix.h"
#include "scale.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { SIDE = 256, MAX_CONTACTS = 8 };
/// Timed batches per point; each batch is about BATCH_MS long.
#define BATCHES 25
#define BATCH_MS 1.0
/// Rotation of the upper box in the rotated variant, rad.
#define TURN 0.3

static int check(pp_status st, const char *what)
{
    if (st == PP_OK)
        return 0;
    fprintf(stderr, "bench_scale: %s failed: %s: %s\n", what, pp_status_name(st), pp_last_error());
    return -1;
}

/* The lower box a, static, top edge at y = 0; the upper box b pushed d px into it: aligned,
 * b is shifted 64 px sideways so that no edges coincide; rotated, its lowest corner goes in. */
static void place(double d, int rotated, bench_box *a, bench_box *b)
{
    *a = (bench_box){.x = 0.0, .y = SIDE * 0.5, .w = SIDE, .h = SIDE, .is_static = 1};
    double reach = rotated ? SIDE * 0.5 * (cos(TURN) + sin(TURN)) : SIDE * 0.5; /* centre to lowest point */
    *b = (bench_box){.x = rotated ? 0.0 : 64.0, .y = d - reach, .w = SIDE, .h = SIDE, .angle = rotated ? TURN : 0.0};
}

/* Median µs of one pp_world_collide over batches of calls; contacts and pixels of one call. */
static int time_raster(pp_world w, pp_body a, pp_body b, int batches, double *us, int *contacts, int *pixels)
{
    pp_contact out[MAX_CONTACTS];
    int32_t n = 0;
    double t0 = bench_now_ms();
    for (int k = 0; k < 3; k++) /* warm the world's buffers; the last call sizes the batches */
        if (check(pp_world_collide(w, a, b, out, MAX_CONTACTS, &n), "pp_world_collide") != 0)
            return -1;
    double one_ms = (bench_now_ms() - t0) / 3.0;
    int reps = one_ms > 0 ? (int)(BATCH_MS / one_ms) + 1 : 1000;
    double *batch_us = malloc((size_t)batches * sizeof *batch_us);
    if (!batch_us)
        return -1;
    for (int k = 0; k < batches; k++) {
        t0 = bench_now_ms();
        for (int r = 0; r < reps; r++)
            pp_world_collide(w, a, b, out, MAX_CONTACTS, &n);
        batch_us[k] = (bench_now_ms() - t0) * 1e3 / reps;
    }
    *us = bench_median(batch_us, batches);
    *contacts = n;
    *pixels = n > 0 ? out[0].pixel_count : 0;
    free(batch_us);
    return 0;
}

/* Median µs of one dCollide, its batches sized from a first short batch. */
static int time_analytic(const bench_box *a, const bench_box *b, const bench_settings *set, int batches, double *us,
                         int *contacts)
{
    double first;
    if (bench_ode_collide_us(a, b, set, 1, 200, &first, contacts) != 0)
        return -1;
    int reps = first > 0 ? (int)(BATCH_MS * 1e3 / first) + 1 : 1000;
    return bench_ode_collide_us(a, b, set, batches, reps, us, contacts);
}

int scale_curve_overlap(const scale_ctx *ctx)
{
    static const int depths[] = {1, 2, 4, 8, 16, 32, 64, 128};
    static const char *const variants[] = {"aligned", "rotated"};
    const int batches = ctx->quick ? 5 : BATCHES;

    pp_world_def def = pp_world_def_default();
    def.gravity = (pp_vec2){0, 0};
    pp_world w = {0};
    if (check(pp_world_create(&def, &w), "pp_world_create") != 0)
        return -1;
    uint8_t *mask = malloc((size_t)SIDE * SIDE);
    int rc = mask ? 0 : -1;
    pp_body body[2] = {{0}, {0}};
    bench_box box[2];
    place(1, 0, &box[0], &box[1]);
    for (int i = 0; i < 2 && rc == 0; i++) {
        memset(mask, 1, (size_t)SIDE * SIDE);
        pp_body_def bd = pp_body_def_default();
        bd.type = box[i].is_static ? PP_BODY_STATIC : PP_BODY_DYNAMIC;
        bd.position = (pp_vec2){(float)box[i].x, (float)box[i].y};
        bd.width = bd.height = SIDE;
        bd.mask = mask;
        rc = check(pp_body_create(w, &bd, &body[i]), "pp_body_create");
    }
    free(mask);

    printf("\n== overlap: two %d px solid boxes, the upper one pushed d px into the lower (static) one; one query "
           "timed alone ==\n   aligned: upper box shifted 64 px sideways; rotated: upper box turned %.1f rad, its "
           "lowest corner d px in\n   raster: pp_world_collide; analytic: dCollide of two dCreateBox; median of %d "
           "batches of about %.0f ms\n",
           SIDE, TURN, batches, BATCH_MS);
    printf("%-5s %-8s %9s %10s %8s %10s %8s %7s\n", "d", "variant", "overlap", "raster", "raster", "analytic",
           "analytic", "r/a");
    printf("%-5s %-8s %9s %10s %8s %10s %8s %7s\n", "px", "", "pixels", "us/call", "contacts", "us/call", "contacts",
           "");
    for (int v = 0; v < 2 && rc == 0; v++) {
        for (size_t k = 0; k < sizeof depths / sizeof depths[0] && rc == 0; k++) {
            place(depths[k], v, &box[0], &box[1]);
            rc = check(pp_body_set_transform(w, body[1], (pp_vec2){(float)box[1].x, (float)box[1].y},
                                             (float)box[1].angle),
                       "pp_body_set_transform");
            double us[2];
            int contacts[2], pixels = 0;
            if (rc == 0)
                rc = time_raster(w, body[0], body[1], batches, &us[0], &contacts[0], &pixels);
            if (rc == 0)
                rc = time_analytic(&box[0], &box[1], &ctx->set, batches, &us[1], &contacts[1]);
            if (rc != 0)
                break;
            printf("%-5d %-8s %9d %10.3f %8d %10.3f %8d %7.1f\n", depths[k], variants[v], pixels, us[0], contacts[0],
                   us[1], contacts[1], us[0] / us[1]);
            for (int e = 0; e < 2; e++) {
                scale_row row = {.curve = "overlap", .variant = variants[v], .x = depths[k],
                                 .engine = e == 0 ? "raster" : "analytic", .timed = batches, .ms = us[e] * 1e-3,
                                 .narrow_ms = us[e] * 1e-3, .contacts = contacts[e], .pairs = 1,
                                 .us_contact = contacts[e] > 0 ? us[e] / contacts[e] : 0.0, .us_pair = us[e],
                                 .ratio = e == 0 ? us[0] / us[1] : 1.0};
                snprintf(row.label, sizeof row.label, "%d", depths[k]);
                scale_emit(ctx, &row);
            }
        }
    }
    if (check(pp_world_destroy(w), "pp_world_destroy") != 0)
        rc = -1;
    return rc;
}
