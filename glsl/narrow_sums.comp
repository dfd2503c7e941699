// Pass 2, one workgroup per mixed 16×16 tile of a pair's inner grid (the full ones were summed by the tiles
// pass): intersection count and centroid sums, and the normal estimator (cell_sums in narrow_cpu.h). Samples of the tile and its
// two-cell ring are shared; sums meet in shared memory, then one 64-bit add per tile.
layout(local_size_x = 16, local_size_y = 16) in;

uniform int u_method; // 0 area gradient, 1 kernel

const int HALO = TILE + 2 * RING;
shared uint cells[HALO * HALO];
shared int s_sum[5];

uint cell_at(int x, int y) { return cells[(y + RING) * HALO + x + RING]; }

void main()
{
    uint tile = group_index();
    if (tile >= mixed_count())
        return;
    uint pi = tile_pair(tile);
    Pair p = pairs[pi];
    ivec2 o = tile_origin(p, tile);
    int ex = p.size.x + 2 * RING, ey = p.size.y + 2 * RING;
    uint lid = gl_LocalInvocationIndex;
    if (lid < 5u)
        s_sum[lid] = 0;
    for (uint h = lid; h < uint(HALO * HALO); h += 256u) {
        int ci = o.x + int(h) % HALO, cj = o.y + int(h) / HALO;
        cells[h] = (ci < ex && cj < ey) ? sample_cell(p, ci, cj) : 0u;
    }
    barrier();

    int lx = int(gl_LocalInvocationID.x), ly = int(gl_LocalInvocationID.y);
    int x = o.x + lx, y = o.y + ly;
    uint c = cell_at(lx, ly);
    if (x < p.size.x && y < p.size.y && (c & 1u) != 0u) {
        int gx = 0, gy = 0;
        if (u_method == 0) {
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int w = (dx != 0 && dy != 0) ? 1 : 2;
                    int cov = int(cell_at(lx + dx, ly + dy) >> 2);
                    gx += w * dx * cov;
                    gy += w * dy * cov;
                }
            if (gx != 0 || gy != 0) {
                int cover = 0;
                for (int dy = -2; dy <= 2; dy++)
                    for (int dx = -2; dx <= 2; dx++)
                        cover += int(cell_at(lx + dx, ly + dy) & 1u);
                gx *= cover;
                gy *= cover;
            }
        } else if ((c & 2u) != 0u) {
            int kx = 0, ky = 0;
            bool critical = false;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    uint n = cell_at(lx + dx, ly + dy);
                    critical = critical || (n & 3u) != 3u;
                    int v = int((n >> 1) & 1u) - int(n & 1u);
                    kx += v * dx;
                    ky += v * dy;
                }
            if (critical) {
                gx = kx;
                gy = ky;
            }
        }
        if ((c & 2u) != 0u) {
            atomicAdd(s_sum[0], 1);
            atomicAdd(s_sum[1], x);
            atomicAdd(s_sum[2], y);
        }
        if (gx != 0)
            atomicAdd(s_sum[3], gx);
        if (gy != 0)
            atomicAdd(s_sum[4], gy);
    }
    barrier();
    if (lid < 5u)
        atomic_add64(pi * R_STRIDE + 2u * lid, s_sum[lid]);
}
