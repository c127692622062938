"""A camera's lens distortion as Gazebo applies it (devices/lens_distortion): Brown's model
about the lens centre, its inversion, and the remap of an image: a straight line bends as k1
says (barrel: towards the centre), the centre pixel stays, nothing distorts without terms, a
crop stretches a barrel's black border away; the map undone with OpenCV's plumb_bob model of
D = (k1, k2, p1, p2, k3) gives the image back."""
import numpy as np
import pytest

from tutorial_turtlebot.sim.devices.lens_distortion import DistortionMap, distort, undistort
from tutorial_turtlebot.sim.files.plugins.camera_types import LensDistortion

BARREL = LensDistortion(k1=-0.2, k2=0.05, k3=0.01, p1=0.002, p2=-0.001)


def test_distort_is_browns_model_and_undistort_inverts_it():
    u, v = np.array([0.1, 0.5, 0.9]), np.array([0.2, 0.5, 0.7])
    ud, vd = distort(u, v, BARREL)
    x, y = u - 0.5, v - 0.5
    r2 = x * x + y * y
    radial = 1 - 0.2 * r2 + 0.05 * r2 ** 2 + 0.01 * r2 ** 3
    assert ud == pytest.approx(0.5 + x * radial + -0.001 * (r2 + 2 * x * x) + 2 * 0.002 * x * y)
    assert vd == pytest.approx(0.5 + y * radial + 0.002 * (r2 + 2 * y * y) + 2 * -0.001 * x * y)
    assert (ud[1], vd[1]) == (0.5, 0.5)
    back = undistort(ud, vd, BARREL)
    assert back[0] == pytest.approx(u, abs=1e-9) and back[1] == pytest.approx(v, abs=1e-9)


def line_image(size=101, row=15):
    image = np.full((size, size, 3), 255, dtype=np.uint8)
    image[row] = 0
    image[size // 2, size // 2] = (200, 100, 50)     # not dark in red
    return image


def dark_rows(image, col):
    return np.flatnonzero(image[:, col, 0] < 128)


@pytest.mark.parametrize("k1, bends_to_centre", [(-0.3, True), (0.3, False)])
def test_a_straight_line_bends_as_k1_says_and_the_centre_pixel_stays(k1, bends_to_centre):
    image = line_image()
    out = DistortionMap(LensDistortion(k1=k1), 101, 101).apply(image)
    middle = dark_rows(out, 50).mean()
    edge = dark_rows(out, 10).mean()
    # the line's middle moves least; its ends, farther from the centre, move more
    assert abs(middle - 15) < abs(edge - 15)
    assert (edge > middle) == bends_to_centre      # barrel: the ends towards the centre row
    assert out[50, 50].tolist() == [200, 100, 50]


def test_no_terms_leave_the_image_as_it_is():
    image = line_image()
    assert (DistortionMap(LensDistortion(), 101, 101).apply(image) == image).all()


def test_a_barrel_leaves_black_corners_unless_cropped():
    image = np.full((40, 60, 3), 200, dtype=np.uint8)
    plain = DistortionMap(LensDistortion(k1=-0.3), 60, 40).apply(image)
    cropped = DistortionMap(LensDistortion(k1=-0.3, crop=True), 60, 40).apply(image)
    assert plain[0, 0].tolist() == [0, 0, 0] and plain[20, 30].tolist() == [200, 200, 200]
    assert (cropped[1:-1, 1:-1] > 150).all()


def opencv_undistort(image, d):
    """cv::undistort of ``image`` (one channel) with K of f = width, cx = (width - 1) / 2 and
    D = ``d`` (k1, k2, p1, p2, k3): each pixel's normalized point distorted with D, sampled
    bilinearly; and where that lies inside the image."""
    height, width = image.shape
    k1, k2, p1, p2, k3 = d
    f, c = float(width), (width - 1) / 2.0
    cols, rows = np.meshgrid(np.arange(width), np.arange(height))
    x, y = (cols - c) / f, (rows - c) / f
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    u = f * (x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)) + c
    v = f * (y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y) + c
    inside = (u >= 0) & (u < width - 1) & (v >= 0) & (v < height - 1)
    u0 = np.clip(np.floor(u).astype(int), 0, width - 2)
    v0 = np.clip(np.floor(v).astype(int), 0, height - 2)
    fu, fv = np.clip(u - u0, 0, 1), np.clip(v - v0, 0, 1)
    s = image.astype(float)
    out = (s[v0, u0] * (1 - fu) * (1 - fv) + s[v0, u0 + 1] * fu * (1 - fv)
           + s[v0 + 1, u0] * (1 - fu) * fv + s[v0 + 1, u0 + 1] * fu * fv)
    return out, inside


def test_opencv_plumb_bob_with_d_in_camera_info_order_undoes_the_distortion_best():
    """D = (k1, k2, p1, p2, k3), as CameraInfo carries it, undistorts the image to the
    original; D a little off in any term (or in another order) does it worse."""
    size = 160
    cols, rows = np.meshgrid(np.arange(size), np.arange(size))
    smooth = (127 + 100 * np.sin(cols / 6.0) * np.cos(rows / 9.0)).astype(np.uint8)
    lens = LensDistortion(k1=-0.2, k2=0.05, k3=0.02, p1=0.01, p2=-0.01)
    distorted = DistortionMap(lens, size, size).apply(np.stack([smooth] * 3, -1))[:, :, 0]
    d = [lens.k1, lens.k2, lens.p1, lens.p2, lens.k3]

    def error(coefficients):
        fixed, inside = opencv_undistort(distorted, coefficients)
        keep = inside[8:-8, 8:-8]
        return np.abs(fixed[8:-8, 8:-8] - smooth[8:-8, 8:-8])[keep].mean()
    best = error(d)
    assert best < 2.0
    for i in range(5):
        for step in (0.02, -0.02):
            off = list(d)
            off[i] += step
            assert error(off) > best, (i, step)
    assert error([lens.k1, lens.k2, lens.k3, lens.p1, lens.p2]) > best   # SDF's order: wrong
