"""Mass, centre of mass and inertia from the pixels, against numpy sums (each pixel a unit square)."""
import numpy as np
import pytest

import physpix
from pphelpers import rect


def pixel_sums(solid, weights=None, density=1.0):
    """Mass, centre (x, y) and inertia of a bitmap summed here pixel by pixel."""
    wt = solid.astype(np.float64) if weights is None else solid * (weights / 255.0)
    j, i = np.mgrid[0:solid.shape[0], 0:solid.shape[1]]
    m = wt.sum()
    cx, cy = (wt * (i + 0.5)).sum() / m, (wt * (j + 0.5)).sum() / m
    inertia = (wt * ((i + 0.5 - cx) ** 2 + (j + 0.5 - cy) ** 2 + 1.0 / 6.0)).sum()
    return density * m, (cx, cy), density * inertia


def test_mass_is_pixel_count_times_density(space):
    mask = np.random.default_rng(7).random((37, 53)) < 0.6
    b = space.create_body(mask=mask, density=2.5)
    assert b.mass == 2.5 * np.count_nonzero(mask)


def test_filled_rectangle_is_exact(space):
    b = rect(space, 30, 20, density=2.0)
    assert b.mass == pytest.approx(1200.0, abs=1e-3)
    assert b.center_of_mass == pytest.approx((15.0, 10.0), abs=1e-4)
    assert b.inertia == pytest.approx(1200.0 * (30 ** 2 + 20 ** 2) / 12.0, rel=1e-5)


def test_weights_scale_each_pixel(space):
    rng = np.random.default_rng(11)
    mask = np.ones((24, 40), dtype=np.uint8)
    weights = rng.integers(1, 256, size=mask.shape, dtype=np.uint8)
    b = space.create_body(mask=mask, weights=weights, density=3.0)
    assert b.mass == pytest.approx(weights.sum() / 255.0 * 3.0, rel=1e-5)
    m, c, inertia = pixel_sums(mask.astype(bool), weights, 3.0)
    assert b.center_of_mass == pytest.approx(c, abs=1e-3)
    assert b.inertia == pytest.approx(inertia, rel=1e-4)


def test_l_shape_centre_and_inertia_against_numpy(space):
    mask = np.zeros((60, 40), dtype=bool)
    mask[:, :12] = True   # the upright
    mask[48:, :] = True   # the foot
    b = space.create_body(mask=mask, angle=0.3, position=(200, 200))
    m, c, inertia = pixel_sums(mask)
    assert b.mass == pytest.approx(m, rel=1e-6)
    assert b.center_of_mass == pytest.approx(c, abs=1e-3)
    assert b.inertia == pytest.approx(inertia, rel=1e-4)


def test_sprite_alpha_threshold_decides_solid_pixels(space):
    rgba = np.zeros((16, 16, 4), dtype=np.uint8)
    rgba[..., 3] = np.arange(256, dtype=np.uint8).reshape(16, 16)
    b = space.create_body(rgba=rgba)  # default alpha_threshold 128: alpha ≥ 128 is solid
    assert b.mass == 128.0
    assert np.array_equal(b.read_mask(), (rgba[..., 3] >= 128).astype(np.uint8))
    b2 = space.create_body(rgba=rgba, alpha_threshold=200)
    assert b2.mass == 56.0


def test_any_mask_dtype_nonzero_is_solid(space):
    mask = np.array([[0.0, 0.5, 0.0], [2.0, -1.0, 0.0]])
    b = space.create_body(mask=mask)
    assert b.mass == 3.0
    assert b.read_mask().tolist() == [[0, 1, 0], [1, 1, 0]]
    assert b.size == (3, 2)


def test_edits_change_mass_by_pixels_times_density(space):
    b = rect(space, 64, 40, density=2.5, position=(200, 200), angle=0.3)
    m0 = b.mass
    erased = b.erase_circle((205, 195), 9.5)
    assert erased > 200
    assert m0 - b.mass == pytest.approx(erased * 2.5, abs=1e-3)
    assert b.erase_circle((205, 195), 9.5) == 0
    assert int(b.read_mask().sum()) == 64 * 40 - erased
    painted = b.paint_circle((205, 195), 9.5, weight=51)
    assert painted == erased
    assert b.mass == pytest.approx(m0 - erased * 2.5 * (1 - 51 / 255), rel=1e-5)


def test_write_pixels_with_weights(space):
    b = rect(space, 20, 10)
    b.write_pixels(-2, -2, np.zeros((4, 4)))  # clipped: only the 2×2 inside is cleared
    assert b.mass == pytest.approx(196.0, abs=1e-4)
    b.write_pixels(0, 0, np.ones((2, 2)), weights=np.full((2, 2), 51, dtype=np.uint8))
    assert b.mass == pytest.approx(196.0 + 4 * 0.2, abs=1e-4)
    assert b.read_mask().sum() == 200


def test_read_weights_gives_the_plane_the_mass_comes_from(space):
    rng = np.random.default_rng(5)
    mask = rng.random((12, 18)) < 0.7
    weights = rng.integers(1, 256, size=mask.shape, dtype=np.uint8)
    b = space.create_body(mask=mask, weights=weights, density=2.0)
    got = b.read_weights()
    assert got.shape == (12, 18) and got.dtype == np.uint8
    assert np.array_equal(got, np.where(mask, weights, 0))
    m, c, inertia = pixel_sums(got > 0, got, 2.0)
    assert b.mass == pytest.approx(m, rel=1e-5)
    assert b.center_of_mass == pytest.approx(c, abs=1e-3)
    # Without a plane, solid pixels read 255; painting writes its weight where it reaches.
    plain = rect(space, 10, 6, position=(100, 100))
    assert np.array_equal(plain.read_weights(), np.full((6, 10), 255, dtype=np.uint8))
    assert plain.paint_circle((95.5, 97.5), 0.4, weight=40) == 1
    want = np.full((6, 10), 255, dtype=np.uint8)
    want[0, 0] = 40
    assert np.array_equal(plain.read_weights(), want)
    plain.destroy()
    with pytest.raises(physpix.InvalidHandleError):
        plain.read_weights()
