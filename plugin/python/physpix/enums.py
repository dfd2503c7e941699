"""The public enums of physpix.h as IntEnums that also equal and print as their lower-case names, and its flags."""
from enum import IntEnum


class NamedEnum(IntEnum):
    """An IntEnum whose members compare equal to their value and to their lower-case name, as the package takes
    them: ``body.type == "dynamic"`` and ``body.type == BodyType.DYNAMIC`` and ``body.type == 0`` all hold. str()
    and format() give the name ("dynamic"); repr() stays ``<BodyType.DYNAMIC: 0>``. The hash is the value's, so
    a member finds int keys in a dict or set; a name does not (a str's hash is not the int's)."""

    def __eq__(self, other: object) -> bool:
        if isinstance(other, str):
            return other.lower() == self.name.lower()
        return int.__eq__(self, other)  # NotImplemented for what is neither an int nor a str

    def __ne__(self, other: object) -> bool:
        equal = self.__eq__(other)
        return equal if equal is NotImplemented else not equal

    __hash__ = IntEnum.__hash__

    def __str__(self) -> str:
        return self.name.lower()

    def __format__(self, spec: str) -> str:
        try:
            return format(str(self), spec)   # "{:>10}" pads the name
        except ValueError:
            return int.__format__(self, spec)  # "{:d}", "{:x}": the value


class Status(NamedEnum):
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


class Backend(NamedEnum):
    """pp_backend: which collision backend runs the narrowphase."""
    AUTO = 0
    CPU = 1
    GPU = 2


class NormalMethod(NamedEnum):
    """pp_normal_method: how a contact normal is estimated."""
    AREA_GRADIENT = 0
    KERNEL = 1


class ContactMode(NamedEnum):
    """pp_contact_mode: how many contact points a colliding pair produces."""
    MANIFOLD = 0
    CENTROID = 1


class Preset(NamedEnum):
    """pp_preset: a named point on the measured speed/accuracy trade."""
    FAST = 1
    BALANCED = 2
    ACCURATE = 3


class BodyType(NamedEnum):
    """pp_body_type: how a body moves."""
    DYNAMIC = 0
    STATIC = 1
    KINEMATIC = 2


class EventType(NamedEnum):
    """pp_event_type: what an event reports."""
    BODY_SPLIT = 1
    BODY_DESTROYED = 2
    CONTACT_BEGIN = 3
    CONTACT_END = 4
    SENSOR_BEGIN = 5
    SENSOR_END = 6
    JOINT_BROKEN = 7


class JointType(NamedEnum):
    """pp_joint_type: what a joint holds."""
    REVOLUTE = 1
    PRISMATIC = 2
    DISTANCE = 3
    WELD = 4
    MOUSE = 5
    WHEEL = 6
    MOTOR = 7


class EditType(NamedEnum):
    """pp_edit_type: what a timed edit does."""
    ERASE_CIRCLE = 1
    PAINT_CIRCLE = 2


class DebugKind(NamedEnum):
    """pp_debug_kind: what a World.debug_draw segment shows."""
    OUTLINE = 1
    AABB = 2
    CONTACT = 3
    NORMAL = 4
    JOINT = 5
    CENTER = 6
    VELOCITY = 7


#: PP_DEBUG_DRAW_OUTLINES: each body's solid-pixel boundary, on the pixel squares' edges (World.debug_draw flags).
DEBUG_DRAW_OUTLINES = 1 << 0
#: PP_DEBUG_DRAW_AABBS: each body's world bounds.
DEBUG_DRAW_AABBS = 1 << 1
#: PP_DEBUG_DRAW_CONTACTS: a cross at each contact point and its normal.
DEBUG_DRAW_CONTACTS = 1 << 2
#: PP_DEBUG_DRAW_JOINTS: anchor to anchor, and each anchor to its body's centre of mass.
DEBUG_DRAW_JOINTS = 1 << 3
#: PP_DEBUG_DRAW_CENTERS: the centre of mass with the body's axes.
DEBUG_DRAW_CENTERS = 1 << 4
#: PP_DEBUG_DRAW_VELOCITIES: each moving body's velocity.
DEBUG_DRAW_VELOCITIES = 1 << 5
#: PP_DEBUG_DRAW_ALL: every flag.
DEBUG_DRAW_ALL = 0x3F


#: PP_CELL_A: the first body is solid in a debug_collision cell.
CELL_A = 1
#: PP_CELL_B: the second body is solid in the cell.
CELL_B = 2
#: PP_CELL_CRITICAL: an intersection cell with a neighbour outside the intersection.
CELL_CRITICAL = 4
