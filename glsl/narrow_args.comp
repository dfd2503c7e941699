// Between the tiles pass and the sums pass, one invocation: the indirect dispatches of the sums pass (a
// workgroup per mixed tile) and of the strips pass (one per mixed or full tile), as 2D grids of at most
// u_count workgroups a row (group_index).
layout(local_size_x = 1) in;

void put_groups(uint at, uint groups)
{
    uint gx = min(groups, u_count);
    lists[at] = gx;
    lists[at + 1u] = gx == 0u ? 0u : (groups + gx - 1u) / gx;
    lists[at + 2u] = 1u;
}

void main()
{
    put_groups(L_SUMS_ARGS, mixed_count());
    put_groups(L_STRIPS_ARGS, mixed_count() + full_count());
}
