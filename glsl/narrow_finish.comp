// Pass 5, one invocation per pair: the first and last strips holding intersection cells and the
// deepest cover overall and in each half between them (strips_summary in narrow_cpu.c).
layout(local_size_x = 64) in;

int deepest_in(int base, int from, int to)
{
    int best = 0;
    for (int b = from; b <= to; b++)
        best = max(best, strips[base + 3 * b + 2]);
    return best;
}

void main()
{
    uint pi = invocation_index();
    if (pi >= u_count)
        return;
    uint r = pi * R_STRIDE;
    int n = int(results[r + R_NSTRIPS]);
    if (n == 0)
        return;
    int base = pairs[pi].q2.z;
    int first = 0, last = n - 1;
    while (strips[base + 3 * first] > strips[base + 3 * first + 1])
        first++;
    while (strips[base + 3 * last] > strips[base + 3 * last + 1])
        last--;
    int mid = first + (last - first) / 2;
    results[r + R_FIRST] = uint(first);
    results[r + R_LAST] = uint(last);
    results[r + R_FIRST_MIN] = uint(strips[base + 3 * first]);
    results[r + R_FIRST_MAX] = uint(strips[base + 3 * first + 1]);
    results[r + R_LAST_MIN] = uint(strips[base + 3 * last]);
    results[r + R_LAST_MAX] = uint(strips[base + 3 * last + 1]);
    results[r + R_COVER_ALL] = uint(deepest_in(base, 0, n - 1));
    results[r + R_COVER_LO] = uint(deepest_in(base, first, mid));
    results[r + R_COVER_HI] = uint(deepest_in(base, mid + 1, last));
}
