/* Tile occupancy and the tiled narrowphase core: tile counts and region states against a
 * recount after random edits, and the tiled core against the dense core (the specification the
 * GPU twin also follows) field by field on thousands of random pairs. These reach the library's
 * private headers, so they run where the tests link its objects (make test-san defines
 * PP_TEST_PRIVATE); against the shared library, which exports only pp_*, they are skipped. */
#include "helpers.h"

PP_TEST_SUITE(tiles);

#ifdef PP_TEST_PRIVATE
#include "narrowphase.h"
#include "raster.h"

static uint64_t rng = 0x2545f4914f6cdd1dull;
static uint32_t rnd(void) {
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 32);
}
static double rnd01(void) { return rnd() / 4294967296.0; }
#define KINDS 9

static int rnd_in(int lo, int hi) { return lo + (int)(rnd() % (uint32_t)(hi - lo + 1)); }

/* Sides 1..max, log-uniform, with tile-edge sizes (15, 16, 17, 63, 64, 65) often. */
static int random_side(int max) {
    static const int edges[] = {1, 2, 15, 16, 17, 31, 32, 33, 63, 64, 65};
    if (rnd() % 4 == 0) return edges[rnd() % (sizeof edges / sizeof edges[0])];
    return 1 + (int)(exp(rnd01() * log((double)max)));
}

/* A w×h mask: full, empty, noise of random density, an ellipse, an ellipse with holes, stripes,
 * a rectangle at a random place, a terrain with hills, or blocks on the occupancy tiles' edges.
 * Caller frees. */
static uint8_t *random_mask(int w, int h, int *kind_out) {
    uint8_t *m = calloc((size_t)w * h, 1);
    cr_assert_not_null(m);
    const int kind = (int)(rnd() % KINDS);
    const int block = RASTER_TILE << (rnd() % 3) >> 1;
    const double density = rnd01(), phase = rnd01() * 6.28, period = 2 + rnd01() * 20;
    const int rx0 = rnd_in(0, w - 1), ry0 = rnd_in(0, h - 1), rx1 = rnd_in(rx0, w), ry1 = rnd_in(ry0, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const double u = (x + 0.5) / w * 2 - 1, v = (y + 0.5) / h * 2 - 1;
            uint8_t s = 0;
            switch (kind) {
            case 0: s = 1; break;
            case 1: s = 0; break;
            case 2: s = rnd01() < density; break;
            case 3: case 4: s = u * u + v * v <= 1.0; break;
            case 5: s = ((x + y) / 3) % 2 == 0; break;
            case 6: s = x >= rx0 && x < rx1 && y >= ry0 && y < ry1; break;
            case 7: s = y >= h * (0.4 + 0.2 * sin(x / period + phase)); break;
            default: s = (x / block + y / block) % 2 == 0; break;
            }
            m[(size_t)y * w + x] = s;
        }
    if (kind == 4)
        for (int k = 0; k < 4; k++) {
            const double cx = rnd01() * w, cy = rnd01() * h, r = (0.05 + 0.2 * rnd01()) * (w < h ? w : h);
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) < r * r)
                        m[(size_t)y * w + x] = 0;
        }
    if (kind_out) *kind_out = kind;
    return m;
}

static pp_raster raster_from(int w, int h, const uint8_t *mask) {
    pp_body_def d = pp_body_def_default();
    d.width = w, d.height = h, d.mask = mask;
    pp_raster r;
    PP_OK_OR_FAIL(raster_init("test", &r, &d));
    return r;
}

/* Every tile's count against a recount of its pixels; the bounds and total too. */
static void check_tiles(const pp_raster *r) {
    int64_t total = 0;
    cr_assert_eq(r->tiles_x, (r->width + RASTER_TILE - 1) / RASTER_TILE);
    cr_assert_eq(r->tiles_y, (r->height + RASTER_TILE - 1) / RASTER_TILE);
    for (int ty = 0; ty < r->tiles_y; ty++)
        for (int tx = 0; tx < r->tiles_x; tx++) {
            int n = 0, area = 0;
            for (int y = ty * RASTER_TILE; y < (ty + 1) * RASTER_TILE && y < r->height; y++)
                for (int x = tx * RASTER_TILE; x < (tx + 1) * RASTER_TILE && x < r->width; x++) {
                    n += raster_solid(r, x, y);
                    area++;
                }
            cr_assert_eq(r->tile_count[ty * r->tiles_x + tx], n, "tile (%d, %d) of a %d × %d raster counts %d, has %d",
                         tx, ty, r->width, r->height, r->tile_count[ty * r->tiles_x + tx], n);
            const raster_state want = n == 0 ? RASTER_EMPTY : n == area ? RASTER_FULL : RASTER_MIXED;
            cr_assert_eq(raster_tile_state(r, tx, ty), want, "tile (%d, %d): state %d, want %d", tx, ty,
                         raster_tile_state(r, tx, ty), want);
            total += n;
        }
    cr_assert_eq(r->solid_count, total);
}

/* raster_rect_state against reading every pixel of the region (outside the bitmap is empty). */
static void check_rect_state(const pp_raster *r, int64_t x0, int64_t y0, int64_t x1, int64_t y1) {
    bool solid = false, hole = false;
    for (int64_t y = y0; y < y1; y++)
        for (int64_t x = x0; x < x1; x++) {
            const bool s = x >= 0 && y >= 0 && x < r->width && y < r->height && raster_solid(r, (int32_t)x, (int32_t)y);
            solid |= s;
            hole |= !s;
        }
    const raster_state want = !solid ? RASTER_EMPTY : hole ? RASTER_MIXED : RASTER_FULL;
    const raster_state got = raster_rect_state(r, x0, y0, x1, y1);
    cr_assert_eq(got, want, "[%lld, %lld) × [%lld, %lld) of a %d × %d raster: state %d, want %d", (long long)x0,
                 (long long)x1, (long long)y0, (long long)y1, r->width, r->height, got, want);
}

Test(tiles, counts_and_region_states_stay_exact_through_random_edits, .timeout = 60) {
    int edits = 0;
    for (int round = 0; round < 200; round++) {
        const int w = random_side(300), h = random_side(300);
        uint8_t *m = random_mask(w, h, NULL);
        pp_raster r = raster_from(w, h, m);
        free(m);
        check_tiles(&r);
        for (int e = 0; e < 12; e++) {
            /* Paint or erase a disc (all writes go through raster_write), then recount. */
            const double cx = rnd01() * w, cy = rnd01() * h, rad = rnd01() * 0.4 * (w > h ? w : h);
            const bool solid = rnd() & 1;
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= rad * rad) {
                        raster_write(&r, x, y, solid, 255);
                        edits++;
                    }
            raster_edit_done(&r, 0, h);
            check_tiles(&r);
            for (int q = 0; q < 20; q++) {
                const int64_t x0 = rnd_in(-20, w + 5), y0 = rnd_in(-20, h + 5);
                const int64_t x1 = x0 + rnd_in(0, q < 10 ? 20 : w + 20), y1 = y0 + rnd_in(0, q < 10 ? 20 : h + 20);
                check_rect_state(&r, x0, y0, x1, y1);
            }
        }
        raster_free(&r);
    }
    cr_assert_gt(edits, 100000, "only %d pixel writes", edits);
}

Test(tiles, memory_counts_the_mask_the_counts_and_the_weight_plane) {
    uint8_t *m = rect_mask(100, 40);
    pp_raster r = raster_from(100, 40, m);
    /* 2 words × 40 rows, int32 row and column counts, a byte per tile. */
    const int64_t tiles = (int64_t)((100 + RASTER_TILE - 1) / RASTER_TILE) * ((40 + RASTER_TILE - 1) / RASTER_TILE);
    const int64_t mask_only = 2 * 8 * 40 + 4 * (100 + 40) + tiles;
    cr_assert_eq(sizeof *r.tile_count, 1);
    cr_assert_eq(raster_memory_bytes(&r), mask_only);
    PP_OK_OR_FAIL(raster_ensure_weights("test", &r));
    cr_assert_eq(raster_memory_bytes(&r), mask_only + 100 * 40);
    raster_free(&r);
    free(m);
}

/* Field by field: the first field that differs, or NULL. */
static const char *core_diff(const np_core *a, const np_core *b, long long *va, long long *vb) {
#define FIELD(f) if (a->f != b->f) return *va = (long long)a->f, *vb = (long long)b->f, #f;
    FIELD(count) FIELD(sx) FIELD(sy) FIELD(gx) FIELD(gy) FIELD(nqx) FIELD(nqy) FIELD(tmin) FIELD(nstrips)
    FIELD(first) FIELD(last) FIELD(first_min) FIELD(first_max) FIELD(last_min) FIELD(last_max) FIELD(cover_all)
    FIELD(cover_lo) FIELD(cover_hi)
#undef FIELD
    return NULL;
}

/* A pose: angle random or a multiple of 90° (exact axis steps), position random or on the grid. */
static np_body random_pose(const pp_raster *r, double x, double y) {
    const double a = rnd() % 3 == 0 ? (rnd() % 4) * (M_PI / 2) : rnd01() * 2 * M_PI;
    if (rnd() % 3 == 0) x = floor(x), y = floor(y);
    return (np_body){.raster = r, .pos = {x, y}, .pivot = {r->width / 2.0, r->height / 2.0}, .c = cos(a), .s = sin(a)};
}

Test(tiles, the_tiled_core_matches_the_dense_core_on_random_pairs, .timeout = 120) {
    np_scratch dense = {0}, tiled = {0};
    int pairs = 0, touching = 0, deep = 0, differ = 0, kinds[KINDS] = {0};
    for (int i = 0; i < 5000; i++) {
        int side[4], kind_a, kind_b;
        /* Every other pair of bodies 24..160 px, for deep overlaps with full and empty tiles. */
        for (int k = 0; k < 4; k++) side[k] = i % 2 ? rnd_in(24, 160) : random_side(i % 50 == 0 ? 400 : 160);
        uint8_t *ma = random_mask(side[0], side[1], &kind_a), *mb = random_mask(side[2], side[3], &kind_b);
        kinds[kind_a]++, kinds[kind_b]++;
        pp_raster ra = raster_from(side[0], side[1], ma), rb = raster_from(side[2], side[3], mb);
        /* Random single-pixel edits make mixed tiles in otherwise full or empty bodies. */
        for (int e = rnd() % 4; e > 0; e--) {
            pp_raster *r = e % 2 ? &ra : &rb;
            raster_write(r, rnd_in(0, r->width - 1), rnd_in(0, r->height - 1), rnd() & 1, 255);
            raster_edit_done(r, 0, r->height);
        }
        const np_body a = random_pose(&ra, 1000, 1000);
        const np_body b = random_pose(&rb, 1000 + (rnd01() - 0.5) * 0.7 * (side[0] + side[2]),
                                      1000 + (rnd01() - 0.5) * 0.7 * (side[1] + side[3]));
        for (int m = 0; m < 2; m++) {
            const pp_normal_method method = m ? PP_NORMAL_KERNEL : PP_NORMAL_AREA_GRADIENT;
            const np_settings set = {method, PP_CONTACT_MANIFOLD, 1 << (rnd() % 3)};
            np_pair p;
            if (!np_pair_setup(&set, &a, &b, &p)) continue;
            np_core want, got;
            PP_OK_OR_FAIL(narrow_cpu_core_dense(&set, &p, &dense, &want));
            /* Run once to size the scratch, then again over poisoned planes: a cell it reads but
             * did not sample shows up as a difference. */
            PP_OK_OR_FAIL(narrow_cpu_core(&set, &p, &tiled, &got));
            memset(tiled.cells, 0x5a, (size_t)tiled.cells_cap);
            PP_OK_OR_FAIL(narrow_cpu_core(&set, &p, &tiled, &got));
            long long va, vb;
            const char *f = core_diff(&got, &want, &va, &vb);
            /* The strips too, beyond the fields np_core keeps of them. */
            if (!f && want.count > 0 &&
                memcmp(tiled.strips, dense.strips, sizeof(int32_t) * NP_STRIP_FIELDS * (size_t)want.nstrips) != 0)
                f = "strips", va = vb = 0;
            if (f && differ++ < 5)
                cr_log_error("pair %d (%dx%d kind %d vs %dx%d kind %d, %s, stride %d): %s tiled %lld, dense %lld", i,
                             side[0], side[1], kind_a, side[2], side[3], kind_b, m ? "kernel" : "gradient",
                             set.stride, f, va, vb);
            pairs++;
            touching += want.count > 0;
            deep += want.count > 400;
        }
        raster_free(&ra), raster_free(&rb);
        free(ma), free(mb);
    }
    np_scratch_free(&dense), np_scratch_free(&tiled);
    cr_log_info("tiled core: %d pairs, %d touching, %d with over 400 intersection cells, %d differ", pairs, touching,
                deep, differ);
    cr_assert_eq(differ, 0, "%d of %d pairs differ", differ, pairs);
    cr_assert_gt(touching, pairs / 3, "only %d of %d pairs touch", touching, pairs);
    cr_assert_gt(deep, pairs / 20, "only %d of %d pairs overlap deeply", deep, pairs);
    for (int k = 0; k < KINDS; k++) cr_assert_gt(kinds[k], 100, "mask kind %d drawn only %d times", k, kinds[k]);
}

/* Set a pair up with and without np_pair_setup's filter: a pair it drops has no cell in both (the dense core on
 * np_pair_grid's grid counts none). 1 if it was dropped, 0 if set up, −1 if no grid. */
static int dropped_pair(const np_body *a, const np_body *b, np_scratch *dense, int i)
{
    const np_settings set = {PP_NORMAL_AREA_GRADIENT, PP_CONTACT_MANIFOLD, 1 << (rnd() % 3)};
    np_pair p;
    if (!np_pair_grid(&set, a, b, &p))
        return -1;
    const bool kept = np_pair_setup(&set, a, b, &p);
    np_core core;
    PP_OK_OR_FAIL(narrow_cpu_core_dense(&set, &p, dense, &core));
    cr_assert(kept || core.count == 0, "pair %d (%dx%d and %dx%d, stride %d) dropped with %lld cells in both", i,
              a->raster->width, a->raster->height, b->raster->width, b->raster->height, set.stride,
              (long long)core.count);
    return !kept;
}

Test(tiles, a_pair_dropped_at_set_up_has_no_intersection_cell) {
    /* Boxes side by side, a gap of −1..2 px between them along a random axis of the first, turned by a little or
     * by multiples of 90°; then crates over a terrain whose upper half is air, their boxes inside the terrain's.
     * Exactly adjacent boxes on the pixel grid are dropped, and so are crates hovering 1 px over the ground. */
    np_scratch dense = {0};
    int grids = 0, dropped = 0, adjacent = 0, hovering = 0, hovering_dropped = 0;
    for (int i = 0; i < 4000; i++) {
        int kind;
        const int w0 = rnd_in(4, 64), h0 = rnd_in(4, 64), w1 = rnd_in(4, 64), h1 = rnd_in(4, 64);
        uint8_t *ma = i % 2 ? rect_mask(w0, h0) : random_mask(w0, h0, &kind), *mb = rect_mask(w1, h1);
        pp_raster ra = raster_from(w0, h0, ma), rb = raster_from(w1, h1, mb);
        const bool square = i % 4 < 2; /* both on the pixel grid, no turn: the gap is exact */
        const double turn_a = square ? 0 : (rnd01() - 0.5) * 0.2 + (rnd() % 4) * (M_PI / 2);
        const double turn_b = square ? 0 : turn_a + (rnd01() - 0.5) * 0.2;
        const int axis = rnd() % 4;
        const double gap = square ? rnd_in(-1, 2) : (rnd01() * 3 - 1);
        const double along = (axis % 2 ? w0 + w1 : h0 + h1) / 2.0 + gap, across = square ? rnd_in(-8, 8) : rnd01() * 16 - 8;
        const double ux = axis == 0 ? 0 : axis == 1 ? 1 : axis == 2 ? 0 : -1, uy = axis == 0 ? 1 : axis == 2 ? -1 : 0;
        const double c = cos(turn_a), sn = sin(turn_a);
        const double lx = ux * along - uy * across, ly = uy * along + ux * across; /* in a's frame */
        const np_body a = {.raster = &ra, .pos = {100, 100}, .pivot = {w0 / 2.0, h0 / 2.0}, .c = c, .s = sn};
        const np_body b = {.raster = &rb, .pos = {100 + c * lx - sn * ly, 100 + sn * lx + c * ly},
                           .pivot = {w1 / 2.0, h1 / 2.0}, .c = cos(turn_b), .s = sin(turn_b)};
        const int d = dropped_pair(&a, &b, &dense, i);
        grids += d >= 0, dropped += d > 0;
        if (square && gap == 0 && i % 2) {
            adjacent++;
            cr_assert_eq(d, 1, "pair %d: boxes sharing an edge were set up", i);
        }
        raster_free(&ra), raster_free(&rb);
        free(ma), free(mb);
    }
    uint8_t *terrain = rect_mask(256, 128);
    memset(terrain, 0, 256 * 64); /* rows 0..63 air: the ground's top at y = 64 */
    pp_raster rt = raster_from(256, 128, terrain);
    for (int i = 0; i < 1000; i++) {
        const int w = rnd_in(4, 48), h = rnd_in(4, 48);
        uint8_t *m = rect_mask(w, h);
        pp_raster rb = raster_from(w, h, m);
        const double turn = i % 2 ? 0 : (rnd01() - 0.5) * 0.1, over = i % 2 ? rnd_in(-1, 3) : rnd01() * 4 - 1;
        const np_body ground = {.raster = &rt, .pos = {0, 0}, .pivot = {0, 0}, .c = 1, .s = 0};
        const np_body crate = {.raster = &rb, .pos = {rnd_in(40, 200), 64 - over - h / 2.0},
                               .pivot = {w / 2.0, h / 2.0}, .c = cos(turn), .s = sin(turn)};
        const int d = dropped_pair(&ground, &crate, &dense, 4000 + i);
        grids += d >= 0, dropped += d > 0;
        if (i % 2 && over == 1) {
            hovering++;
            hovering_dropped += d > 0;
        }
        raster_free(&rb);
        free(m);
    }
    raster_free(&rt);
    free(terrain);
    np_scratch_free(&dense);
    cr_log_info("set-up filter: %d grids, %d dropped, %d adjacent boxes, %d of %d hovering crates", grids, dropped,
                adjacent, hovering_dropped, hovering);
    cr_assert_gt(adjacent, 100, "only %d adjacent pairs", adjacent);
    cr_assert_gt(hovering, 50, "only %d hovering crates", hovering);
    cr_assert_eq(hovering_dropped, hovering, "%d of %d crates 1 px over the ground set up", hovering - hovering_dropped,
                 hovering);
    cr_assert_gt(dropped, grids / 4, "only %d of %d pairs dropped", dropped, grids);
}

#else

Test(tiles, run_where_the_tests_link_the_library_objects) {
    cr_skip_test("tile and tiled-core tests use private headers: make test-san runs them");
}

#endif
