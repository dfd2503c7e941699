"""The public enums of physpix.h as IntEnums (members are also accepted as lower-case strings), and its flags."""
from enum import IntEnum


class Status(IntEnum):
    """pp_status: the result of every call that can fail."""
    OK = 0
    INVALID_ARGUMENT = 1
    INVALID_HANDLE = 2
    OUT_OF_MEMORY = 3
    IO = 4
    FORMAT = 5
    UNSUPPORTED = 6
    LIMIT = 7
    ABI = 8


class Backend(IntEnum):
    """pp_backend: which collision backend runs the narrowphase."""
    AUTO = 0
    CPU = 1
    GPU = 2


class NormalMethod(IntEnum):
    """pp_normal_method: how a contact normal is estimated."""
    AREA_GRADIENT = 0
    KERNEL = 1


class ContactMode(IntEnum):
    """pp_contact_mode: how many contact points a colliding pair produces."""
    MANIFOLD = 0
    CENTROID = 1


class Preset(IntEnum):
    """pp_preset: a named point on the measured speed/accuracy trade."""
    FAST = 1
    BALANCED = 2
    ACCURATE = 3


class BodyType(IntEnum):
    """pp_body_type: how a body moves."""
    DYNAMIC = 0
    STATIC = 1
    KINEMATIC = 2


class EventType(IntEnum):
    """pp_event_type: what an event reports."""
    BODY_SPLIT = 1
    BODY_DESTROYED = 2
    CONTACT_BEGIN = 3
    CONTACT_END = 4
    SENSOR_BEGIN = 5
    SENSOR_END = 6
    JOINT_BROKEN = 7


class JointType(IntEnum):
    """pp_joint_type: what a joint holds."""
    REVOLUTE = 1
    PRISMATIC = 2
    DISTANCE = 3
    WELD = 4
    MOUSE = 5


class EditType(IntEnum):
    """pp_edit_type: what a timed edit does."""
    ERASE_CIRCLE = 1
    PAINT_CIRCLE = 2


#: PP_CELL_A: the first body is solid in a debug_collision cell.
CELL_A = 1
#: PP_CELL_B: the second body is solid in the cell.
CELL_B = 2
#: PP_CELL_CRITICAL: an intersection cell with a neighbour outside the intersection.
CELL_CRITICAL = 4
