// Pass 3, one invocation per inner cell: coverage tent-splatted onto the two nearest strips, and
// each intersection cell's projection on the normal into its own strip (strips_along).
layout(local_size_x = 16, local_size_y = 16) in;

void main()
{
    uint tile = group_index();
    if (tile >= u_count)
        return;
    uint pi = tiles[tile];
    Pair p = pairs[pi];
    uint r = pi * R_STRIDE;
    int n = int(results[r + R_NSTRIPS]);
    ivec2 xy = tile_origin(p, tile) + ivec2(gl_LocalInvocationID.xy);
    if (n == 0 || xy.x >= p.size.x || xy.y >= p.size.y)
        return;
    uint c = sample_cell(p, xy.x + RING, xy.y + RING);
    int cov = int(c >> 2);
    if ((c & 1u) == 0u || cov == 0)
        return;
    int nqx = int(results[r + R_NQX]), nqy = int(results[r + R_NQY]), lo = int(results[r + R_TMIN]);
    int ts = -xy.x * nqy + xy.y * nqx; // strip b is centred on t = b
    int b0 = (ts >> 14) - lo, w1 = (ts & (ONE - 1)) >> 6;
    int base = p.q2.z;
    if (b0 >= 0)
        atomicAdd(strips[base + 3 * b0 + 2], (cov * (256 - w1)) >> 8);
    if (b0 + 1 < n)
        atomicAdd(strips[base + 3 * (b0 + 1) + 2], (cov * w1) >> 8);
    if ((c & 2u) != 0u) {
        int own = base + 3 * (b0 + (w1 >= 128 ? 1 : 0)), pr = xy.x * nqx + xy.y * nqy;
        atomicMin(strips[own], pr);
        atomicMax(strips[own + 1], pr);
    }
}
