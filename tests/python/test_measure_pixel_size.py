"""scripts/measure_pixel_size.py on a drawn press: the contact circle's radius and the pixel size."""
import json
import subprocess
import sys

import numpy as np
import pytest

import touchcloud


def write_ppm(path, image):
    """A BGR uint8 image as a binary PPM, which OpenCV (and so image_reader) reads."""
    h, w, _ = image.shape
    path.write_bytes(b"P6\n%d %d\n255\n" % (w, h) + image[:, :, ::-1].tobytes())


@pytest.mark.parametrize("arguments, expected", [(["--diameter-mm", "4.8"], 0.06),
                                                 (["--ball-radius-mm", "4", "--depth-mm", "0.5"], 0.0484122918)])
def test_a_drawn_contact_gives_its_radius_and_the_pixel_size(source, tmp_path, arguments, expected):
    reference = np.full((240, 320, 3), 120, np.uint8)
    press = reference.copy()
    v, u = np.mgrid[0:240, 0:320]
    inside = (u - 150.3) ** 2 + (v - 110.6) ** 2 <= 40 ** 2
    press[inside] = (170, 90, 140)
    write_ppm(tmp_path / "press.ppm", press)
    write_ppm(tmp_path / "reference.ppm", reference)
    out = subprocess.run([sys.executable, str(source / "scripts/measure_pixel_size.py"), str(tmp_path / "press.ppm"),
                          str(tmp_path / "reference.ppm"), "--json"] + arguments,
                         capture_output=True, text=True, check=True)
    result = json.loads(out.stdout)
    assert result["centre_px"] == pytest.approx([150.3, 110.6], abs=0.3)
    assert result["radius_px"] == pytest.approx(40, abs=0.5)
    assert result["mm_per_px"] == pytest.approx(expected, rel=0.015)


def test_no_contact_is_an_error(source, tmp_path):
    reference = np.full((240, 320, 3), 120, np.uint8)
    write_ppm(tmp_path / "press.ppm", reference)
    write_ppm(tmp_path / "reference.ppm", reference)
    out = subprocess.run([sys.executable, str(source / "scripts/measure_pixel_size.py"), str(tmp_path / "press.ppm"),
                          str(tmp_path / "reference.ppm"), "--diameter-mm", "5"], capture_output=True, text=True)
    assert out.returncode == 2 and "no contact found" in out.stderr
