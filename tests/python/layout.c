/* Prints the size and field offsets of every public struct of physpix.h as JSON, so that the
 * Python tests can check the ctypes mirror against what the C compiler lays out. */
#include "physpix.h"

#include <stddef.h>
#include <stdio.h>

static int first_struct = 1, first_field;

static void begin(const char *name, size_t size)
{
    printf("%s\n  \"%s\": {\"size\": %zu, \"fields\": [", first_struct ? "{" : ",", name, size);
    first_struct = 0;
    first_field = 1;
}

static void field(const char *name, size_t offset, size_t size)
{
    printf("%s\n    [\"%s\", %zu, %zu]", first_field ? "" : ",", name, offset, size);
    first_field = 0;
}

static void end(void) { printf("]}"); }

#define S(T) begin(#T, sizeof(T))
#define F(T, f) field(#f, offsetof(T, f), sizeof(((T *)0)->f))

int main(void)
{
    S(pp_vec2); F(pp_vec2, x); F(pp_vec2, y); end();
    S(pp_world); F(pp_world, id); end();
    S(pp_body); F(pp_body, id); end();
    S(pp_joint); F(pp_joint, id); end();

    S(pp_world_def);
    F(pp_world_def, struct_size); F(pp_world_def, gravity); F(pp_world_def, substeps);
    F(pp_world_def, solver_iterations); F(pp_world_def, exact_solver); F(pp_world_def, backend);
    F(pp_world_def, normal_method); F(pp_world_def, contact_mode); F(pp_world_def, raster_stride);
    F(pp_world_def, pixels_per_meter); F(pp_world_def, contact_slop); F(pp_world_def, contact_erp);
    F(pp_world_def, contact_cfm); F(pp_world_def, bounce_threshold); F(pp_world_def, allow_sleep);
    F(pp_world_def, sleep_linear_speed); F(pp_world_def, sleep_angular_speed); F(pp_world_def, sleep_time);
    F(pp_world_def, continuous); F(pp_world_def, max_correction_speed);
    F(pp_world_def, worker_threads); F(pp_world_def, contact_events); F(pp_world_def, exact_island_rows);
    end();

    S(pp_body_def);
    F(pp_body_def, struct_size); F(pp_body_def, type); F(pp_body_def, position); F(pp_body_def, angle);
    F(pp_body_def, custom_pivot); F(pp_body_def, pivot); F(pp_body_def, linear_velocity);
    F(pp_body_def, angular_velocity); F(pp_body_def, density); F(pp_body_def, friction);
    F(pp_body_def, restitution); F(pp_body_def, linear_damping); F(pp_body_def, angular_damping);
    F(pp_body_def, category_bits); F(pp_body_def, mask_bits); F(pp_body_def, fixed_rotation);
    F(pp_body_def, width); F(pp_body_def, height); F(pp_body_def, rgba); F(pp_body_def, mask);
    F(pp_body_def, weights); F(pp_body_def, alpha_threshold); F(pp_body_def, detach_islands);
    F(pp_body_def, user_data); F(pp_body_def, bullet); F(pp_body_def, is_sensor); F(pp_body_def, one_way);
    F(pp_body_def, one_way_direction);
    end();

    S(pp_contact);
    F(pp_contact, a); F(pp_contact, b); F(pp_contact, point); F(pp_contact, normal); F(pp_contact, depth);
    F(pp_contact, pixel_count); F(pp_contact, normal_impulse); F(pp_contact, reserved);
    end();

    S(pp_event);
    F(pp_event, type); F(pp_event, reserved); F(pp_event, body); F(pp_event, other); F(pp_event, point);
    F(pp_event, normal); F(pp_event, approach_speed); F(pp_event, reserved2); F(pp_event, joint);
    end();

    S(pp_raycast_hit);
    F(pp_raycast_hit, body); F(pp_raycast_hit, point); F(pp_raycast_hit, normal); F(pp_raycast_hit, fraction);
    F(pp_raycast_hit, reserved);
    end();

    S(pp_step_stats);
    F(pp_step_stats, broadphase_ms); F(pp_step_stats, narrowphase_ms); F(pp_step_stats, solver_ms);
    F(pp_step_stats, total_ms); F(pp_step_stats, bodies); F(pp_step_stats, awake_bodies); F(pp_step_stats, pairs);
    F(pp_step_stats, contacts); F(pp_step_stats, pixels_tested); F(pp_step_stats, backend);
    F(pp_step_stats, swept_stops); F(pp_step_stats, threads);
    end();

    S(pp_camera); F(pp_camera, center); F(pp_camera, zoom); F(pp_camera, width); F(pp_camera, height); end();

    S(pp_timed_edit);
    F(pp_timed_edit, time); F(pp_timed_edit, type); F(pp_timed_edit, weight); F(pp_timed_edit, body);
    F(pp_timed_edit, center); F(pp_timed_edit, radius); F(pp_timed_edit, reserved);
    end();

    S(pp_explosion_def);
    F(pp_explosion_def, struct_size); F(pp_explosion_def, position); F(pp_explosion_def, radius);
    F(pp_explosion_def, falloff); F(pp_explosion_def, impulse_per_length); F(pp_explosion_def, erase_radius);
    F(pp_explosion_def, mask_bits); F(pp_explosion_def, erase_mask_bits);
    end();

    S(pp_character_def);
    F(pp_character_def, struct_size); F(pp_character_def, radius); F(pp_character_def, half_height);
    F(pp_character_def, step_height); F(pp_character_def, snap_distance); F(pp_character_def, max_slope);
    F(pp_character_def, mask_bits);
    end();

    S(pp_character_move);
    F(pp_character_move, position); F(pp_character_move, velocity); F(pp_character_move, grounded);
    F(pp_character_move, ground_normal); F(pp_character_move, ground_body); F(pp_character_move, ground_velocity);
    F(pp_character_move, surfaces);
    end();

    S(pp_body_state);
    F(pp_body_state, body); F(pp_body_state, position); F(pp_body_state, angle); F(pp_body_state, linear_velocity);
    F(pp_body_state, angular_velocity); F(pp_body_state, awake); F(pp_body_state, user_data);
    end();

    S(pp_joint_def);
    F(pp_joint_def, struct_size); F(pp_joint_def, type); F(pp_joint_def, body_a); F(pp_joint_def, body_b);
    F(pp_joint_def, anchor_a); F(pp_joint_def, anchor_b); F(pp_joint_def, axis); F(pp_joint_def, collide_connected);
    F(pp_joint_def, enable_limit); F(pp_joint_def, lower); F(pp_joint_def, upper); F(pp_joint_def, enable_motor);
    F(pp_joint_def, motor_speed); F(pp_joint_def, max_motor_force); F(pp_joint_def, min_length);
    F(pp_joint_def, max_length); F(pp_joint_def, spring_hertz); F(pp_joint_def, spring_damping_ratio);
    F(pp_joint_def, max_force); F(pp_joint_def, break_force); F(pp_joint_def, reserved);
    F(pp_joint_def, user_data); F(pp_joint_def, target); F(pp_joint_def, angular_hertz);
    F(pp_joint_def, angular_damping_ratio); F(pp_joint_def, break_torque); F(pp_joint_def, linear_offset);
    F(pp_joint_def, angular_offset); F(pp_joint_def, max_torque); F(pp_joint_def, correction_factor);
    F(pp_joint_def, reserved2);
    end();

    S(pp_collision_view);
    F(pp_collision_view, width); F(pp_collision_view, height); F(pp_collision_view, origin);
    F(pp_collision_view, step_x); F(pp_collision_view, step_y); F(pp_collision_view, normal);
    F(pp_collision_view, intersection); F(pp_collision_view, critical);
    end();

    S(pp_debug_segment);
    F(pp_debug_segment, a); F(pp_debug_segment, b); F(pp_debug_segment, rgba); F(pp_debug_segment, kind);
    F(pp_debug_segment, body);
    end();

    S(pp_allocator); F(pp_allocator, alloc); F(pp_allocator, realloc); F(pp_allocator, free); F(pp_allocator, user);
    end();

    /* The enums, whose size ctypes takes on trust. */
    S(pp_status); end();
    S(pp_backend); end();
    S(pp_normal_method); end();
    S(pp_contact_mode); end();
    S(pp_body_type); end();
    S(pp_event_type); end();
    S(pp_edit_type); end();
    S(pp_joint_type); end();
    printf("\n}\n");
    return 0;
}
