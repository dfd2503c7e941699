"""Issue 45 through Python: World.move_character in a game loop (the host keeps the position and velocity), the
ground it reports, and the library's errors for bad input."""
import math

import pytest

import physpix
from physpix import BodyType, CharacterMove, World
from pphelpers import raises_from_library, rect

DT = 1.0 / 60.0
G = 980.0


def walk(world, position, speed, frames, **fields):
    """A game loop: each frame the walk asked for, gravity added to the vertical velocity the last move left (none
    when grounded). Returns every frame's CharacterMove."""
    moves, vy = [], 0.0
    for _ in range(frames):
        m = world.move_character(position, (speed, vy + G * DT), DT, **fields)
        position, vy = m.position, 0.0 if m.grounded else m.velocity[1]
        moves.append(m)
    return moves


def test_on_flat_ground_a_character_walks_grounded_at_constant_height_and_covers_speed_times_time():
    world = World(gravity=(0, G))
    ground = rect(world, 800, 40, type=BodyType.STATIC, position=(400, 320))  # top y = 300
    foot = 8 + 8  # the default capsule: radius 8 px, half_height 8 px
    start = (100.0, 300 - foot - 0.01)
    speed, frames = 150.0, 120
    moves = walk(world, start, speed, frames)
    for i, m in enumerate(moves):
        assert isinstance(m, CharacterMove)
        assert m.grounded, f"frame {i}: in the air at {m.position}"
        assert abs(m.position[1] - start[1]) <= 0.5, f"frame {i}: height {m.position[1]}, started at {start[1]}"
        assert m.ground_body == ground
        assert m.ground_normal == pytest.approx((0, -1), abs=1e-3)
        assert m.ground_velocity == pytest.approx((0, 0), abs=1e-6)
        assert m.velocity[0] == pytest.approx(speed)
    walked, want = moves[-1].position[0] - start[0], speed * frames * DT
    assert abs(walked - want) <= 0.02 * want, f"walked {walked} px, expected {want}"
    world.close()


def test_in_the_air_a_character_falls_as_gravity_says_and_a_wall_takes_its_velocity_into_it():
    world = World(gravity=(0, G))
    wall = rect(world, 20, 400, type=BodyType.STATIC, position=(300, 200))  # left face x = 290
    m = world.move_character((100, 100), (0, 300), 0.1, radius=6, half_height=0)
    assert not m.grounded and m.ground_body is None and m.ground_normal == (0, 0)
    assert m.position == pytest.approx((100, 130), abs=1e-3) and m.velocity == pytest.approx((0, 300))
    # Toward the wall at 1000 px/s for 0.5 s: it stops touching it, the velocity into the wall gone.
    m = world.move_character((200, 100), (1000, 0), 0.5, radius=6, half_height=0, snap_distance=0)
    assert 290 - 6 - 0.5 <= m.position[0] <= 290 - 6 + 0.5, m.position
    assert abs(m.velocity[0]) < 1e-3 and m.surfaces >= 1
    # A mask that misses the wall's category lets it through.
    m = world.move_character((200, 100), (1000, 0), 0.5, radius=6, half_height=0, mask_bits=0)
    assert m.position[0] == pytest.approx(700) and m.surfaces == 0
    assert wall.position == (300, 200), "nothing in the world moves"
    world.close()


def test_bad_input_raises_the_library_error_naming_the_call_and_the_field():
    world = World(gravity=(0, G))
    e = raises_from_library(physpix.InvalidArgumentError, ["radius"], world.move_character, (0, 0), (1, 0), DT,
                            radius=0)
    assert e.message.startswith("World.move_character"), e.message
    raises_from_library(physpix.InvalidArgumentError, ["max_slope"], world.move_character, (0, 0), (1, 0), DT,
                        max_slope=2)
    raises_from_library(physpix.InvalidArgumentError, ["half_height"], world.move_character, (0, 0), (1, 0), DT,
                        half_height=-1)
    raises_from_library(physpix.InvalidArgumentError, ["dt"], world.move_character, (0, 0), (1, 0), math.nan)
    raises_from_library(physpix.InvalidArgumentError, ["position"], world.move_character, (math.inf, 0), (1, 0), DT)
    raises_from_library(physpix.InvalidArgumentError, ["PP_MAX_SPEED"], world.move_character, (0, 0), (2e6, 0), DT)
    with pytest.raises(TypeError, match="radiu"):
        world.move_character((0, 0), (1, 0), DT, radiu=3)
    with pytest.raises(TypeError, match="struct_size"):
        world.move_character((0, 0), (1, 0), DT, struct_size=4)
    world.close()
    raises_from_library(physpix.InvalidHandleError, ["world"], world.move_character, (0, 0), (1, 0), DT)
