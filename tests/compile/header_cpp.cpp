// The public headers compile as C++17 with -Werror and keeps the C layout.
#include "physpix.h"
#include "physpix_plugin.h"
#include <type_traits>

static_assert(sizeof(pp_vec2) == 8, "pp_vec2 layout");
static_assert(sizeof(pp_contact) == 48, "pp_contact layout");
static_assert(sizeof(pp_debug_segment) == 32 && sizeof(pp_debug_kind) == 4, "pp_debug_segment layout");
static_assert(sizeof(pp_event) == 56, "pp_event layout");
static_assert(sizeof(pp_raycast_hit) == 32, "pp_raycast_hit layout");
static_assert(std::is_trivially_copyable<pp_body_def>::value, "plain data");
static_assert(sizeof(pp_variant) == 24, "pp_variant layout");
static_assert(std::is_trivially_copyable<pp_plugin_interface>::value, "plain data");
static_assert(std::is_trivially_copyable<pp_step_stats>::value, "plain data");

int physpix_header_cpp_check() { return static_cast<int>(sizeof(pp_world_def)); }
