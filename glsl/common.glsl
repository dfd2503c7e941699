#version 310 es
// Shared by every narrowphase pass (prepended at build time). The C twin is lib/collide/narrow_cpu.c
// (the dense core) with narrow_cpu.h; every decision is integer so both give the same bits.
precision highp float;
precision highp int;

// One pair, 24 ints (lib/collide/narrow_gpu.c gpu_pair).
struct Pair {
    ivec4 ra;   // reference mask: first word, width, height, 32-bit words per row
    ivec4 rb;   // other mask, likewise
    ivec4 grid; // stride s, offset, i0, j0
    ivec4 size; // inner cells nx, ny; fallback normal nqx, nqy (Q14)
    ivec4 q;    // 16.16 sample point of plane cell (0, 0), step per column (x, y)
    ivec4 q2;   // step per row (x, y), first strip word, first tile of the batch's grid tiles
};

layout(std430, binding = 0) readonly buffer Masks { uint masks[]; };
layout(std430, binding = 1) readonly buffer Pairs { Pair pairs[]; };
// Two words a tile that adds something: its pair, and its index in the pair's grid of tiles, TILE_FULL on a
// tile whose every cell and neighbour lie in both bodies (narrow_tiles.comp). The mixed tiles fill it from
// the front, the full ones from the back.
layout(std430, binding = 2) buffer Tiles { uint tiles[]; };
layout(std430, binding = 3) buffer Results { uint results[]; };
layout(std430, binding = 4) buffer Strips { int strips[]; };
// The batch's grid tiles and pairs, then the sums and the strips passes' indirect dispatches (narrow_args.comp).
layout(std430, binding = 5) buffer Lists { uint lists[]; };

uniform uint u_count; // pairs in a per-pair pass; narrow_args: the most workgroups a row

// Results: 24 words per pair (np_core), 64-bit sums as (low, high).
const uint R_COUNT = 0u, R_SX = 2u, R_SY = 4u, R_GX = 6u, R_GY = 8u;
const uint R_NQX = 10u, R_NQY = 11u, R_TMIN = 12u, R_NSTRIPS = 13u, R_FIRST = 14u, R_LAST = 15u;
const uint R_FIRST_MIN = 16u, R_FIRST_MAX = 17u, R_LAST_MIN = 18u, R_LAST_MAX = 19u;
const uint R_COVER_ALL = 20u, R_COVER_LO = 21u, R_COVER_HI = 22u, R_STRIDE = 24u;
const int RING = 2, TILE = 16, ONE = 16384;
const uint L_GRID_TILES = 0u, L_PAIRS = 1u, L_SUMS_ARGS = 2u, L_STRIPS_ARGS = 5u;

// The mixed and full tiles' counts follow the pairs' results (so they come back in the same read).
uint tile_counts() { return lists[L_PAIRS] * R_STRIDE; }
uint mixed_count() { return results[tile_counts()]; }
uint full_count() { return results[tile_counts() + 1u]; }

// The workgroup's index among the dispatch's (a 2D grid when there are more than 65535).
uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// The invocation's index among the dispatch's, in a pass of workgroups of 64 (the tiles and per-pair passes).
uint invocation_index() { return group_index() * 64u + gl_LocalInvocationIndex; }

bool solid(ivec4 r, int x, int y)
{
    if (uint(x) >= uint(r.y) || uint(y) >= uint(r.z))
        return false;
    uint w = masks[uint(r.x) + uint(y * r.w + (x >> 5))];
    return ((w >> uint(x & 31)) & 1u) != 0u;
}

// Plane cell (ci, cj), packed: bit 0 the reference, bit 1 the other, bits 2.. the other's
// bilinear coverage 0..256 (sample_planes and coverage_fixed in narrow_cpu.c).
uint sample_cell(Pair p, int ci, int cj)
{
    int px = (p.grid.z - RING + ci) * p.grid.x + p.grid.y;
    int py = (p.grid.w - RING + cj) * p.grid.x + p.grid.y;
    uint a = solid(p.ra, px, py) ? 1u : 0u;
    int qx = p.q.x + cj * p.q2.x + ci * p.q.z; // wraps like the CPU's int64 where the result fits
    int qy = p.q.y + cj * p.q2.y + ci * p.q.w;
    uint b = solid(p.rb, qx >> 16, qy >> 16) ? 2u : 0u;
    int hx = qx - 32768, hy = qy - 32768;
    int x = hx >> 16, y = hy >> 16;
    uint cov = 0u;
    if (x >= -1 && y >= -1 && x < p.rb.y && y < p.rb.z) {
        uint fx = uint((hx >> 8) & 255), fy = uint((hy >> 8) & 255);
        uint m00 = solid(p.rb, x, y) ? 1u : 0u, m10 = solid(p.rb, x + 1, y) ? 1u : 0u;
        uint m01 = solid(p.rb, x, y + 1) ? 1u : 0u, m11 = solid(p.rb, x + 1, y + 1) ? 1u : 0u;
        cov = (m00 * (256u - fx) * (256u - fy) + m10 * fx * (256u - fy) + m01 * (256u - fx) * fy + m11 * fx * fy) >> 8;
    }
    return a | b | (cov << 2);
}

const uint TILE_FULL = 0x80000000u;

// Entry i of the mixed tiles followed by the full ones.
uint tile_entry(uint i)
{
    uint mixed = mixed_count();
    return i < mixed ? i : lists[L_GRID_TILES] - full_count() + (i - mixed);
}

uint tile_pair(uint entry) { return tiles[2u * entry]; }
bool tile_full(uint entry) { return (tiles[2u * entry + 1u] & TILE_FULL) != 0u; }

// The first inner cell of grid tile t of pair p.
ivec2 grid_tile_origin(Pair p, int t)
{
    int tiles_x = (p.size.x + TILE - 1) / TILE;
    return ivec2(t % tiles_x, t / tiles_x) * TILE;
}

ivec2 tile_origin(Pair p, uint entry) { return grid_tile_origin(p, int(tiles[2u * entry + 1u] & ~TILE_FULL)); }

// 64-bit integer add of a 32-bit signed value by two 32-bit atomics: the carry out of the low
// word is known from the value the atomic saw, so concurrent adds still sum exactly.
void atomic_add64(uint at, int v)
{
    if (v == 0)
        return;
    uint lo = uint(v), hi = v < 0 ? 0xffffffffu : 0u;
    uint old = atomicAdd(results[at], lo);
    hi += (old + lo < old) ? 1u : 0u;
    if (hi != 0u)
        atomicAdd(results[at + 1u], hi);
}
