// Pass 1, one invocation per tile of every pair's grid: whether the tile adds nothing, is all intersection
// (every cell and neighbour in both bodies) or is mixed, from the rasters' 8×8 occupancy counts, which follow
// each mask in the mask buffer. It is np_classify_tiles (lib/collide/narrow_tiled.c) tile by tile: what its
// halving finds of a rectangle holds for each tile in it. A full tile's count and coordinate sums are added in
// closed form; mixed and full tiles are listed for the passes after it.
layout(local_size_x = 64) in;

const int EMPTY = 0, FULL = 1, MIXED = 2; // raster_state
const int RTILE = 8;                      // RASTER_TILE

// raster_tile_state: tile (tx, ty)'s count, bytes after the mask's rows.
int raster_tile(ivec4 r, int tx, int ty)
{
    uint at = uint(r.x + r.z * r.w) * 4u + uint(ty * ((r.y + RTILE - 1) / RTILE) + tx);
    int n = int((masks[at >> 2] >> (8u * (at & 3u))) & 255u);
    int w = min(r.y - tx * RTILE, RTILE), h = min(r.z - ty * RTILE, RTILE);
    return n == 0 ? EMPTY : n == w * h ? FULL : MIXED;
}

// scan_bits: whether pixels [x0, x1) × [y0, y1) hold a solid one and a hole.
void scan_bits(ivec4 r, int x0, int y0, int x1, int y1, inout bool solid, inout bool hole)
{
    for (int y = y0; y < y1 && !(solid && hole); y++)
        for (int w = x0 >> 5; w <= (x1 - 1) >> 5; w++) {
            int a = max(x0 - 32 * w, 0), b = min(x1 - 32 * w, 32);
            uint m = (b - a == 32 ? 0xffffffffu : (1u << uint(b - a)) - 1u) << uint(a);
            uint v = masks[uint(r.x + y * r.w + w)];
            solid = solid || (v & m) != 0u;
            hole = hole || (v & m) != m;
        }
}

// raster_rect_state: pixels [x0, x1) × [y0, y1), those outside the bitmap holes.
int rect_state(ivec4 r, int x0, int y0, int x1, int y1)
{
    bool solid = false, hole = x0 < 0 || y0 < 0 || x1 > r.y || y1 > r.z;
    x0 = max(x0, 0), y0 = max(y0, 0), x1 = min(x1, r.y), y1 = min(y1, r.z);
    if (x0 >= x1 || y0 >= y1)
        return EMPTY;
    for (int ty = y0 / RTILE; ty <= (y1 - 1) / RTILE && !(solid && hole); ty++)
        for (int tx = x0 / RTILE; tx <= (x1 - 1) / RTILE && !(solid && hole); tx++) {
            int st = raster_tile(r, tx, ty);
            int ax = tx * RTILE, ay = ty * RTILE, ex = min(ax + RTILE, r.y), ey = min(ay + RTILE, r.z);
            int cx0 = max(ax, x0), cy0 = max(ay, y0), cx1 = min(ex, x1), cy1 = min(ey, y1);
            if (st == MIXED && (cx0 > ax || cy0 > ay || cx1 < ex || cy1 < ey)) {
                scan_bits(r, cx0, cy0, cx1, cy1, solid, hole);
            } else {
                solid = solid || st != EMPTY;
                hole = hole || st != FULL;
            }
        }
    return !solid ? EMPTY : hole ? MIXED : FULL;
}

// ref_state: the reference's pixels under inner cells c = [x0, x1) × [y0, y1) grown by g cells.
int ref_state(Pair p, ivec4 c, int g)
{
    int s = p.grid.x, off = p.grid.y;
    return rect_state(p.ra, (p.grid.z + c.x - g) * s + off, (p.grid.w + c.y - g) * s + off,
                      (p.grid.z + c.z - 1 + g) * s + off + 1, (p.grid.w + c.w - 1 + g) * s + off + 1);
}

// other_state: the other body's pixels that the samples of those cells grown by g can read.
int other_state(Pair p, ivec4 c, int g)
{
    ivec2 lo = ivec2(0x7fffffff), hi = ivec2(-0x7fffffff - 1);
    for (int k = 0; k < 4; k++) {
        int ci = ((k & 1) != 0 ? c.z - 1 + g : c.x - g) + RING, cj = ((k >> 1) != 0 ? c.w - 1 + g : c.y - g) + RING;
        ivec2 q = ivec2(p.q.x + ci * p.q.z + cj * p.q2.x, p.q.y + ci * p.q.w + cj * p.q2.y);
        lo = min(lo, q), hi = max(hi, q);
    }
    lo = (lo - 32768) >> 16, hi = (hi - 32768) >> 16;
    return rect_state(p.rb, lo.x, lo.y, hi.x + 2, hi.y + 2);
}

// The pair whose grid holds batch tile t: the last whose first tile is at most t.
uint pair_of_tile(uint t)
{
    uint lo = 0u, hi = lists[L_PAIRS] - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if (uint(pairs[mid].q2.w) <= t)
            lo = mid;
        else
            hi = mid - 1u;
    }
    return lo;
}

void main()
{
    uint t = invocation_index();
    if (t >= lists[L_GRID_TILES])
        return;
    uint pi = pair_of_tile(t);
    Pair p = pairs[pi];
    int own = int(t) - p.q2.w;
    ivec2 o = grid_tile_origin(p, own);
    ivec4 c = ivec4(o, min(o.x + TILE, p.size.x), min(o.y + TILE, p.size.y)); // cut by the grid
    // cells_state: every term needs a reference cell, and coverage of the other on the cells or around them.
    int ref = ref_state(p, c, 0);
    if (ref == EMPTY)
        return;
    int other = other_state(p, c, 1);
    if (other == EMPTY)
        return;
    bool full = ref == FULL && other == FULL && ref_state(p, c, 1) == FULL;
    uint entry;
    if (full) {
        // add_full_sums: the kernel finds no critical cell and the gradient's coverage differences are zero.
        int w = c.z - c.x, h = c.w - c.y;
        atomic_add64(pi * R_STRIDE + R_COUNT, w * h);
        atomic_add64(pi * R_STRIDE + R_SX, h * (w * (c.x + c.z - 1) / 2));
        atomic_add64(pi * R_STRIDE + R_SY, w * (h * (c.y + c.w - 1) / 2));
        entry = lists[L_GRID_TILES] - 1u - atomicAdd(results[tile_counts() + 1u], 1u);
    } else {
        entry = atomicAdd(results[tile_counts()], 1u);
    }
    tiles[2u * entry] = pi;
    tiles[2u * entry + 1u] = uint(own) | (full ? TILE_FULL : 0u);
}
