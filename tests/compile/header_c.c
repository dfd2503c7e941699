/* The public headers compile as C11 with -Werror, and its structs have the documented layout. */
#include "physpix.h"
#include "physpix_plugin.h"
#include <stddef.h>

_Static_assert(sizeof(pp_vec2) == 8, "pp_vec2 layout");
_Static_assert(sizeof(pp_world) == 8 && sizeof(pp_body) == 8, "handle layout");
_Static_assert(sizeof(pp_contact) == 48, "pp_contact layout");
_Static_assert(sizeof(pp_debug_segment) == 32 && sizeof(pp_debug_kind) == 4, "pp_debug_segment layout");
_Static_assert(sizeof(pp_event) == 56 && offsetof(pp_event, joint) == 48, "pp_event layout");
_Static_assert(sizeof(pp_raycast_hit) == 32, "pp_raycast_hit layout");
_Static_assert(sizeof(pp_body_def) == 152, "pp_body_def layout");
_Static_assert(sizeof(pp_status) == 4 && sizeof(pp_body_type) == 4, "enums are 32-bit");
_Static_assert(offsetof(pp_world_def, struct_size) == 0, "struct_size first");
_Static_assert(sizeof(pp_variant) == 24 && offsetof(pp_variant, as) == 8, "pp_variant layout");
_Static_assert(offsetof(pp_host_interface, struct_size) == 0 && offsetof(pp_plugin_interface, struct_size) == 0,
               "struct_size first");
_Static_assert(offsetof(pp_body_def, struct_size) == 0, "struct_size first");
_Static_assert(sizeof(pp_joint) == 8 && sizeof(pp_joint_type) == 4, "joint handle and type");
_Static_assert(offsetof(pp_joint_def, struct_size) == 0 && sizeof(pp_joint_def) == 152 &&
               offsetof(pp_joint_def, target) == 112, "pp_joint_def layout (a def of the first 112 bytes is still taken)");

int physpix_header_c_check(void);
int physpix_header_c_check(void) { return (int)sizeof(pp_body_def) + (int)sizeof(pp_world_def); }
