"""Clouds and meshes written by the tools users have, read back exactly.

Open3D (Debian's python3-open3d) and PCL's command-line tools (pcl-tools)
write PCD and PLY clouds and PLY, STL and OBJ meshes in every encoding they
offer, with the attribute layouts they use (Open3D: double x, y, z with
normals and colours; PCL: float fields, padding, a camera element, VTK's
empty face element). Every cloud goes through `touchcloud score`, a
pipeline's `cloud_reader` and `touchcloud.read_cloud`, and must give the
coordinates that were written, as float32, bit for bit; every mesh must
give the same ground truth as the reference mesh. Without open3d or
pcl-tools the suite skips on a developer's machine and fails in CI
(TOUCHCLOUD_CI or CI set), where scripts/install-deps.sh installs both.
"""
import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import touchcloud

CLI = pathlib.Path(os.environ.get("TOUCHCLOUD_CLI", pathlib.Path(__file__).parents[4] / "build/bin/touchcloud"))
IN_CI = bool(os.environ.get("TOUCHCLOUD_CI") or os.environ.get("CI"))


def missing(what):
    message = what + " is not installed (scripts/install-deps.sh installs it)"
    if IN_CI:
        pytest.fail(message + "; CI runs this suite")
    pytest.skip(message)


@pytest.fixture(scope="module")
def o3d():
    try:
        import open3d
    except ImportError:
        missing("python3-open3d")
    return open3d


@pytest.fixture(scope="module")
def pcl_tools():
    tools = {name: shutil.which(name) for name in ("pcl_converter", "pcl_pcd2ply")}
    if not all(tools.values()):
        missing("pcl-tools (" + ", ".join(n for n, p in tools.items() if not p) + ")")
    return tools


def pcl(tool, *args):
    subprocess.run([tool, *map(str, args)], check=True, capture_output=True)


def o3d_cloud(o3d, xyz, rng, attributes):
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(xyz))
    if attributes:
        cloud.normals = o3d.utility.Vector3dVector(rng.integers(-8, 9, xyz.shape) / 8.0)
        cloud.colors = o3d.utility.Vector3dVector(rng.integers(0, 256, xyz.shape) / 255.0)
    return cloud


@pytest.fixture(scope="module")
def clouds(o3d, pcl_tools, tmp_path_factory):
    """{group: (expected float32 points, [files])}: `exact` coordinates are
    multiples of 1/8 with at most 5 significant digits, so every text
    encoding carries them whole; `fine` ones are doubles no float holds,
    written in the binary encodings only."""
    folder = tmp_path_factory.mktemp("clouds")
    rng = np.random.default_rng(45)
    exact = rng.integers(-760, 760, (150, 3)) / 8.0
    fine = rng.normal(scale=40.0, size=(150, 3)) + 1e-9
    groups = {"exact": (exact.astype(np.float32), []), "fine": (fine.astype(np.float32), [])}

    def add(group, path):
        groups[group][1].append(path)
        return path

    for group, xyz in (("exact", exact), ("fine", fine)):
        for attributes in (False, True):
            cloud = o3d_cloud(o3d, xyz, rng, attributes)
            tag = f"{group}_o3d{'_rich' if attributes else ''}"
            for ascii_text in ((False, True) if group == "exact" else (False,)):
                for ext, compressed in ((".ply", False), (".pcd", False), (".pcd", True)):
                    if ascii_text and compressed:
                        continue
                    name = f"{tag}_{'ascii' if ascii_text else 'compressed' if compressed else 'binary'}{ext}"
                    assert o3d.io.write_point_cloud(str(folder / name), cloud, write_ascii=ascii_text,
                                                    compressed=compressed)
                    add(group, folder / name)

    # PCL's tools, from Open3D's files: VTK's PLY (float x, y, z, an empty
    # face element), PCL's PLY writer (a camera element after the points),
    # PCD with padding fields, ASCII and binary_compressed PCD.
    rich = folder / "exact_o3d_rich_binary.pcd"
    for fmt in ("binary", "ascii"):
        pcl(pcl_tools["pcl_converter"], "-f", fmt, rich, add("exact", folder / f"exact_pcl_vtk_{fmt}.ply"))
        pcl(pcl_tools["pcl_converter"], "-f", fmt, rich, add("exact", folder / f"exact_pcl_{fmt}.pcd"))
    pcl(pcl_tools["pcl_converter"], "-f", "binary_compressed", rich, add("exact", folder / "exact_pcl_compressed.pcd"))
    pcl(pcl_tools["pcl_converter"], folder / "exact_o3d_rich_binary.ply", add("exact", folder / "exact_pcl_padded.pcd"))
    for fmt in ("0", "1"):
        pcl(pcl_tools["pcl_pcd2ply"], "-format", fmt, "-use_camera", "1", rich,
            add("exact", folder / f"exact_pcl_camera_{fmt}.ply"))

    # Big-endian PLY, properties in another order and of other types.
    layout = np.dtype([("intensity", ">u2"), ("z", ">f8"), ("y", ">f4"), ("x", ">f8"), ("label", ">i1")])
    rows = np.zeros(len(exact), layout)
    rows["x"], rows["y"], rows["z"] = exact[:, 0], exact[:, 1], exact[:, 2]
    header = ("ply\nformat binary_big_endian 1.0\ncomment written by this test\nelement vertex %d\n"
              "property ushort intensity\nproperty double z\nproperty float y\nproperty double x\n"
              "property char label\nend_header\n" % len(exact))
    add("exact", folder / "exact_big_endian.ply").write_bytes(header.encode() + rows.tobytes())
    return groups


def test_python_reads_every_cloud_exactly(clouds):
    for group, (expected, files) in clouds.items():
        for f in files:
            np.testing.assert_array_equal(touchcloud.read_cloud(str(f)), expected, err_msg=f.name)


def test_score_reads_every_cloud_exactly(clouds, tmp_path):
    for group, (expected, files) in clouds.items():
        reference = tmp_path / f"{group}_reference.pcd"
        touchcloud.write_cloud(str(reference), expected)
        r = subprocess.run([CLI, "score", "--gt", reference, *files, "--json"], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        rows = json.loads(r.stdout)
        assert [pathlib.Path(row["estimate"]).name for row in rows] == [f.name for f in files]
        for row in rows:
            assert row["status"] == "ok", row
            assert row["estimate_points"] == len(expected), row["estimate"]
            assert row["metrics"]["chamfer_est_to_gt_mm"] == 0, row["estimate"]
            assert row["metrics"]["hausdorff_mm"] == 0, row["estimate"]


def test_cloud_reader_reads_every_cloud_exactly(clouds, tmp_path):
    files = [(expected, f) for expected, fs in clouds.values() for f in fs]
    stages = []
    for i, (_, f) in enumerate(files):
        stages.append(f"  - id: read{i}\n    plugin: cloud_reader\n    params: {{path: '{f}'}}\n"
                      f"  - id: write{i}\n    plugin: cloud_writer\n    params: {{path: out{i}.pcd}}\n"
                      f"    inputs: {{cloud: read{i}.cloud}}\n")
    (tmp_path / "read_all.yaml").write_text("pipeline: read_all\nstages:\n" + "".join(stages))
    r = subprocess.run([CLI, "run", tmp_path / "read_all.yaml", "--out", tmp_path / "out", "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for i, (expected, f) in enumerate(files):
        np.testing.assert_array_equal(touchcloud.read_cloud(str(tmp_path / "out" / f"out{i}.pcd")), expected,
                                      err_msg=f.name)


@pytest.fixture(scope="module")
def meshes(o3d, pcl_tools, tmp_path_factory):
    """A 7 x 7 height field (vertices at multiples of 1/8 mm, at most 5
    significant digits) as every tool writes it; the first is the reference."""
    folder = tmp_path_factory.mktemp("meshes")
    rng = np.random.default_rng(7)
    x, y = np.meshgrid(np.arange(7) * 6.5, np.arange(7) * 6.5)
    vertices = np.column_stack([x.ravel() - 19.5, y.ravel() - 19.5, rng.integers(0, 80, 49) / 8.0])
    triangles = [(r * 7 + c, r * 7 + c + 1, r * 7 + c + 8) for r in range(6) for c in range(6)]
    triangles += [(r * 7 + c, r * 7 + c + 8, r * 7 + c + 7) for r in range(6) for c in range(6)]
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(vertices), o3d.utility.Vector3iVector(triangles))
    mesh.compute_vertex_normals()
    files = []
    for name, ascii_text in (("o3d_binary.ply", False), ("o3d_ascii.ply", True), ("o3d_binary.stl", False),
                             ("o3d.obj", True)):
        assert o3d.io.write_triangle_mesh(str(folder / name), mesh, write_ascii=ascii_text)
        files.append(folder / name)
    for name, fmt in (("pcl_vtk_ascii.ply", "ascii"), ("pcl_vtk_binary.ply", "binary"), ("pcl_ascii.stl", "ascii"),
                      ("pcl_binary.stl", "binary"), ("pcl.obj", "ascii")):
        pcl(pcl_tools["pcl_converter"], "-f", fmt, folder / "o3d_binary.ply", folder / name)
        files.append(folder / name)
    return vertices.astype(np.float32), files


def test_every_mesh_gives_the_reference_ground_truth(meshes, tmp_path):
    vertices, files = meshes
    estimate = tmp_path / "estimate.pcd"
    touchcloud.write_cloud(str(estimate), vertices + np.float32(0.5))

    def score(mesh):
        r = subprocess.run([CLI, "score", "--gt", mesh, estimate, "--json", "--seed", "3", "--samples", "20000"],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        row = json.loads(r.stdout)[0]
        assert row["status"] == "ok", row
        return row

    reference = score(files[0])
    assert reference["ground_truth"]["triangles"] == 72
    for mesh in files[1:]:
        row = score(mesh)
        for key in ("triangles", "area_mm2", "points"):
            assert row["ground_truth"][key] == reference["ground_truth"][key], (mesh.name, key)
        assert row["metrics"] == reference["metrics"], mesh.name


def test_a_ply_mesh_read_as_a_cloud_gives_its_vertices(meshes):
    vertices, files = meshes
    for mesh in files:
        if mesh.suffix == ".ply":
            np.testing.assert_array_equal(touchcloud.read_cloud(str(mesh)), vertices, err_msg=mesh.name)
