// Pass 3, one invocation per pair: the Q14 normal from the integer sums (np_quantize_normal in
// narrowphase.c), the strip range across it, and the strips cleared for pass 4.
layout(local_size_x = 64) in;

uvec2 abs64(uvec2 v)
{
    if ((v.y & 0x80000000u) == 0u)
        return v;
    uint lo = ~v.x + 1u;
    return uvec2(lo, ~v.y + (lo == 0u ? 1u : 0u));
}

bool greater64(uvec2 a, uvec2 b) { return a.y > b.y || (a.y == b.y && a.x > b.x); }

uint shift_right64(uvec2 v, int s)
{
    if (s == 0)
        return v.x;
    return s >= 32 ? v.y >> uint(s - 32) : (v.x >> uint(s)) | (v.y << uint(32 - s));
}

uvec2 mul32x32(uint a, uint b)
{
    uvec2 r;
    umulExtended(a, b, r.y, r.x);
    return r;
}

// round(2^14·a/√r2) exactly: the k with (2k−1)²·r2 ≤ 2^30·a² < (2k+1)²·r2.
int round_unit_q14(uint a, uint r2)
{
    uvec2 target = uvec2((a * a) << 30, (a * a) >> 2);
    int k = clamp(int(float(ONE) * float(a) / sqrt(float(r2)) + 0.5), 0, ONE);
    while (k > 0 && greater64(mul32x32(uint((2 * k - 1) * (2 * k - 1)), r2), target))
        k--;
    while (!greater64(mul32x32(uint((2 * k + 1) * (2 * k + 1)), r2), target))
        k++;
    return k;
}

void main()
{
    uint pi = invocation_index();
    if (pi >= u_count)
        return;
    uint r = pi * R_STRIDE;
    Pair p = pairs[pi];
    if (results[r + R_COUNT] == 0u && results[r + R_COUNT + 1u] == 0u) {
        results[r + R_NSTRIPS] = 0u;
        return;
    }
    uvec2 gx = uvec2(results[r + R_GX], results[r + R_GX + 1u]);
    uvec2 gy = uvec2(results[r + R_GY], results[r + R_GY + 1u]);
    int nqx = p.size.z, nqy = p.size.w;
    if (gx != uvec2(0u) || gy != uvec2(0u)) {
        uvec2 ax = abs64(gx), ay = abs64(gy), m = greater64(ax, ay) ? ax : ay;
        int msb = m.y != 0u ? 32 + findMSB(m.y) : findMSB(m.x);
        int s = max(msb - 14, 0);
        uint x = shift_right64(ax, s), y = shift_right64(ay, s), r2 = x * x + y * y;
        nqx = round_unit_q14(x, r2);
        nqy = round_unit_q14(y, r2);
        nqx = (gx.y & 0x80000000u) != 0u ? -nqx : nqx;
        nqy = (gy.y & 0x80000000u) != 0u ? -nqy : nqy;
    }
    int lo = 0x7fffffff, hi = -0x7fffffff - 1;
    for (int k = 0; k < 4; k++) {
        int x = (k & 1) != 0 ? p.size.x - 1 : 0, y = (k >> 1) != 0 ? p.size.y - 1 : 0;
        int b = (-x * nqy + y * nqx + ONE / 2) >> 14; // round(t), ties up: the corner's own strip
        lo = min(lo, b);
        hi = max(hi, b);
    }
    int n = hi - lo + 1;
    results[r + R_NQX] = uint(nqx);
    results[r + R_NQY] = uint(nqy);
    results[r + R_TMIN] = uint(lo);
    results[r + R_NSTRIPS] = uint(n);
    for (int i = 0; i < n; i++) {
        strips[p.q2.z + 3 * i] = 0x7fffffff;
        strips[p.q2.z + 3 * i + 1] = -0x7fffffff - 1;
        strips[p.q2.z + 3 * i + 2] = 0;
    }
}
