// Pass 4, over the mixed and full tiles: coverage tent-splatted onto the two nearest strips, and
// each intersection cell's projection on the normal into its own strip (strips_along). A mixed
// tile has one invocation per inner cell. A full tile's cells are all in both bodies at coverage
// 256: one invocation per line of it (along the axis on which the tangent coordinate changes
// least, as strips_full walks) adds a run of cells in one strip by one atomic; the sums are integers,
// so the same as cell by cell.
layout(local_size_x = 16, local_size_y = 16) in;

int g_base, g_n;

void add_cover(int b, int w)
{
    if (b >= 0 && b < g_n && w != 0)
        atomicAdd(strips[g_base + 3 * b + 2], w);
}

void add_own(int b, int lo, int hi)
{
    atomicMin(strips[g_base + 3 * b], lo);
    atomicMax(strips[g_base + 3 * b + 1], hi);
}

void full_line(Pair p, ivec2 o, int nqx, int nqy, int lo)
{
    int line = int(gl_LocalInvocationIndex);
    if (line >= TILE)
        return;
    bool along_x = abs(nqy) <= abs(nqx);
    ivec2 at = o + (along_x ? ivec2(0, line) : ivec2(line, 0)), step = along_x ? ivec2(1, 0) : ivec2(0, 1);
    if (at.x >= p.size.x || at.y >= p.size.y)
        return;
    int m = along_x ? min(TILE, p.size.x - o.x) : min(TILE, p.size.y - o.y);
    int run = 0, lower = 0, upper = 0; // the run's strip b0 and its two covers
    int own = 0, own_lo = 0, own_hi = 0;
    for (int k = 0; k < m; k++, at += step) {
        int ts = -at.x * nqy + at.y * nqx;
        int b0 = (ts >> 14) - lo, w1 = (ts & (ONE - 1)) >> 6;
        if (k == 0 || b0 != run) {
            if (k > 0) {
                add_cover(run, lower);
                add_cover(run + 1, upper);
            }
            run = b0, lower = 0, upper = 0;
        }
        lower += 256 - w1;
        upper += w1;
        int ob = b0 + (w1 >= 128 ? 1 : 0), pr = at.x * nqx + at.y * nqy;
        if (k == 0 || ob != own) {
            if (k > 0)
                add_own(own, own_lo, own_hi);
            own = ob, own_lo = pr, own_hi = pr;
        } else {
            own_lo = min(own_lo, pr);
            own_hi = max(own_hi, pr);
        }
    }
    add_cover(run, lower);
    add_cover(run + 1, upper);
    add_own(own, own_lo, own_hi);
}

void main()
{
    uint i = group_index();
    if (i >= mixed_count() + full_count())
        return;
    uint tile = tile_entry(i);
    uint pi = tile_pair(tile);
    Pair p = pairs[pi];
    uint r = pi * R_STRIDE;
    g_n = int(results[r + R_NSTRIPS]);
    g_base = p.q2.z;
    if (g_n == 0)
        return;
    int nqx = int(results[r + R_NQX]), nqy = int(results[r + R_NQY]), lo = int(results[r + R_TMIN]);
    if (tile_full(tile)) {
        full_line(p, tile_origin(p, tile), nqx, nqy, lo);
        return;
    }
    ivec2 xy = tile_origin(p, tile) + ivec2(gl_LocalInvocationID.xy);
    if (xy.x >= p.size.x || xy.y >= p.size.y)
        return;
    uint c = sample_cell(p, xy.x + RING, xy.y + RING);
    int cov = int(c >> 2);
    if ((c & 1u) == 0u || cov == 0)
        return;
    int ts = -xy.x * nqy + xy.y * nqx; // strip b is centred on t = b
    int b0 = (ts >> 14) - lo, w1 = (ts & (ONE - 1)) >> 6;
    add_cover(b0, (cov * (256 - w1)) >> 8);
    add_cover(b0 + 1, (cov * w1) >> 8);
    if ((c & 2u) != 0u)
        add_own(b0 + (w1 >= 128 ? 1 : 0), xy.x * nqx + xy.y * nqy, xy.x * nqx + xy.y * nqy);
}
