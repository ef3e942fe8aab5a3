# The Python module against the command line: the same meshes and reports, numpy in and mesh out, errors
# as exceptions with the command line's exit codes, the GIL released during the work.
# SPDX-License-Identifier: GPL-3.0-or-later
import filecmp
import json
import threading
import time

import numpy as np
import pytest

import contour4d


def same_folder(a, b):
    """Every file of folder a is in b with the same bytes, and the other way round."""
    cmp = filecmp.dircmp(a, b)
    assert not cmp.left_only and not cmp.right_only, (cmp.left_only, cmp.right_only)
    _, mismatch, errors = filecmp.cmpfiles(a, b, cmp.common_files, shallow=False)
    assert not mismatch and not errors, (mismatch, errors)
    for sub in cmp.common_dirs:
        same_folder(a / sub, b / sub)


def ellipse_contours(frames=2, slices=6, spacing=6.0, rng=None):
    """A shrinking ellipsoid of random axes as a list of contour dicts (frame, slice, time_ms, points (n, 3))."""
    rng = rng or np.random.default_rng(1)
    a, b = 20 * rng.uniform(0.8, 1.2), 14 * rng.uniform(0.8, 1.2)
    contours = []
    for f in range(frames):
        scale = 1.0 - 0.15 * f / max(frames - 1, 1)
        for s in range(slices):
            z = (s - (slices - 1) / 2) * spacing
            r = np.sqrt(max(1 - (z / (slices * spacing / 2 + 2)) ** 2, 0.05))
            t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
            pts = np.stack([a * scale * r * np.cos(t), b * scale * r * np.sin(t), np.full_like(t, z)], axis=1)
            contours.append({"frame": f, "slice": s, "label": "lv-endo", "time_ms": 40.0 * f, "points": pts})
    return contours


def test_import_and_version():
    assert contour4d.__version__ == "0.1.0"
    assert issubclass(contour4d.InvalidInput, contour4d.Error)
    assert issubclass(contour4d.Error, RuntimeError)


def test_read_returns_arrays_per_contour(phantoms):
    ph = phantoms("left-heart")
    r = contour4d.read(ph / "contours.json")
    assert r["format"] == "contour4d-json" and r["frames"] == 3 and r["space"] in ("LPS", "RAS", "unknown")
    on_disk = json.loads((ph / "contours.json").read_text())
    assert len(r["contours"]) == sum(len(f["contours"]) for f in on_disk["frames"])
    c = r["contours"][0]
    assert c["points"].ndim == 2 and c["points"].shape[1] == 3 and c["points"].dtype == np.float64
    assert {"frame", "slice", "label", "time_ms", "offset_mm"} <= set(c)


def test_reconstruct_writes_what_the_cli_writes(phantoms, cli, tmp_path):
    ph = phantoms("left-heart")
    cli("reconstruct", ph / "contours.json", "-o", tmp_path / "cli", "--threads", 2)
    res = contour4d.reconstruct(ph / "contours.json", output=tmp_path / "py", threads=1)
    same_folder(tmp_path / "cli", tmp_path / "py")  # mesh.pvd, frames/*.vtp|obj, report.json: byte-identical
    loaded = contour4d.load(tmp_path / "cli")
    assert res["positions"].shape == loaded["positions"].shape == (3, res["positions"].shape[1], 3)
    np.testing.assert_array_equal(res["positions"], loaded["positions"])  # VTP holds Float64: exact
    np.testing.assert_array_equal(res["triangles"], loaded["triangles"])
    assert res["report"] == json.loads((tmp_path / "cli" / "report.json").read_text())
    assert res["report"]["checks"]["ok"] and res["report"]["summary"]["ef_percent"] > 0


def test_reconstruct_one_frame_matches_vtk_reader(phantoms, tmp_path):
    vtk = pytest.importorskip("vtkmodules.vtkIOXML")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    ph = phantoms("left-heart")
    res = contour4d.reconstruct(ph / "contours.json", output=tmp_path / "f1", frame=1)
    assert res["positions"].shape[0] == 1
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(str(next((tmp_path / "f1" / "frames").glob("*.vtp"))))
    reader.Update()
    pts = vtk_to_numpy(reader.GetOutput().GetPoints().GetData())
    np.testing.assert_array_equal(pts, res["positions"][0])


def test_numpy_in_equals_the_same_contours_from_a_json_file(tmp_path):
    contours = ellipse_contours(frames=2)
    from_arrays = contour4d.reconstruct(contours, edge=1.5)
    frames = [{"time_ms": 40.0 * f, "contours": [{"label": c["label"], "slice": c["slice"], "points": c["points"].tolist()}
                                                 for c in contours if c["frame"] == f]} for f in range(2)]
    path = tmp_path / "ellipse.json"
    path.write_text(json.dumps({"format": "contour4d-contours", "version": 1, "units": "mm", "frames": frames}))
    from_file = contour4d.reconstruct(path, edge=1.5)
    np.testing.assert_array_equal(from_arrays["positions"], from_file["positions"])
    np.testing.assert_array_equal(from_arrays["triangles"], from_file["triangles"])
    assert from_arrays["report"]["frame_times"]["source"] == "data"
    np.testing.assert_array_equal(from_arrays["times_ms"], [0.0, 40.0])
    # read()'s dict goes back in unchanged
    again = contour4d.reconstruct(contour4d.read(contours), edge=1.5)
    np.testing.assert_array_equal(again["positions"], from_arrays["positions"])


@pytest.mark.parametrize("seed", [2, 3, 4])
def test_numpy_in_mesh_out_family(seed):
    """Random tilts and rigid motions of the ellipse stack: the mesh is valid and its volume follows the
    rigid motion (invariance), whatever the contours' start point and orientation."""
    rng = np.random.default_rng(seed)
    contours = ellipse_contours(frames=2, rng=rng)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    shift = rng.normal(size=3) * 30
    moved = []
    for c in contours:
        pts = np.roll(c["points"] @ q.T + shift, rng.integers(60), axis=0)
        if rng.random() < 0.5:
            pts = pts[::-1]
        moved.append({**c, "points": pts})
    a = contour4d.reconstruct(contours)
    b = contour4d.reconstruct(moved)
    va = [f["volume_mm3"] for f in a["report"]["frames"]]
    vb = [f["volume_mm3"] for f in b["report"]["frames"]]
    np.testing.assert_allclose(va, vb, rtol=0.01)
    assert a["report"]["checks"]["ok"] and b["report"]["checks"]["ok"]
    assert a["positions"].shape[0] == 2 and a["triangles"].max() < a["positions"].shape[1]


def test_pack_and_unpack_match_the_cli(phantoms, cli, tmp_path):
    ph = phantoms("left-heart")
    contour4d.reconstruct(ph / "contours.json", output=tmp_path / "out")
    stats = contour4d.pack(tmp_path / "out")
    assert stats["path"] == str(tmp_path / "out" / "model.c4d") and stats["max_error_mm"] <= 0.05
    cli("pack", tmp_path / "out", "-o", tmp_path / "cli.c4d")
    assert (tmp_path / "cli.c4d").read_bytes() == (tmp_path / "out" / "model.c4d").read_bytes() == stats["model"]
    decoded = contour4d.unpack(stats["model"], output=tmp_path / "py_unpacked")
    cli("unpack", tmp_path / "out" / "model.c4d", "-o", tmp_path / "cli_unpacked")  # OBJ comments name the file
    same_folder(tmp_path / "cli_unpacked" / "frames", tmp_path / "py_unpacked" / "frames")
    exact = contour4d.load(tmp_path / "out")
    assert decoded["positions"].shape == exact["positions"].shape  # the model may order vertices its own way
    from scipy.spatial import cKDTree
    for f in range(exact["positions"].shape[0]):
        d, _ = cKDTree(exact["positions"][f]).query(decoded["positions"][f])
        assert d.max() <= 0.05 + 1e-9
    # a mesh dict packs too, and decodes to the same
    again = contour4d.pack(exact, gltf=False)
    assert again["path"] is None and again["bytes"] == len(again["model"])


def test_evaluate_matches_the_cli(phantoms, cli, tmp_path):
    ph = phantoms("left-heart")
    contour4d.reconstruct(ph / "contours.json", output=tmp_path / "out")
    ev = contour4d.evaluate(tmp_path / "out", contours=ph / "contours.json", truth=ph / "truth", json=tmp_path / "py.json")
    cli("evaluate", tmp_path / "out", "--contours", ph / "contours.json", "--truth", ph / "truth", "--json", tmp_path / "cli.json")
    assert (tmp_path / "py.json").read_text() == (tmp_path / "cli.json").read_text()
    assert ev == json.loads((tmp_path / "cli.json").read_text())


@pytest.mark.parametrize("make_input,kwargs,cls,code", [
    (lambda d: d / "missing.json", {}, contour4d.IoError, 10),
    (lambda d: (d / "t.json").write_text('{"format": "contour4d-contours", "version": 1, "fra') and d / "t.json", {},
     contour4d.Error, 12),
    (lambda d: [{"frame": 0, "slice": 0, "points": [[0, 0, 0], [1, 0, 0]]}], {"strict": True}, contour4d.InvalidInput, 15),
    (lambda d: [{"frame": 0, "slice": 0, "points": [[0, 0, 0], [4, 4, 0], [4, 0, 0], [0, 2, 0]]}], {"strict": True},
     contour4d.InvalidInput, 16),
    (lambda d: ellipse_contours(frames=1), {"label": "rv"}, contour4d.InvalidInput, 21),
    (lambda d: ellipse_contours(frames=1), {"frame": 3}, contour4d.InvalidInput, 2),
    (lambda d: ellipse_contours(frames=1), {"no_such_option": 1}, contour4d.InvalidInput, 2),
    (lambda d: ellipse_contours(frames=2), {"volume_tolerance": 0.0}, contour4d.SolverError, 26),
])
def test_errors_carry_the_cli_exit_codes(tmp_path, make_input, kwargs, cls, code):
    with pytest.raises(cls) as info:
        contour4d.reconstruct(make_input(tmp_path), **kwargs)
    assert info.value.exit_code == code, str(info.value)
    assert str(info.value) == info.value.message and info.value.message


def test_a_failing_result_writes_nothing(tmp_path):
    with pytest.raises(contour4d.SolverError) as info:
        contour4d.reconstruct(ellipse_contours(frames=2), output=tmp_path / "out", volume_tolerance=0.0,
                              keep_failed=tmp_path / "failed")
    assert info.value.exit_code == 26
    assert not (tmp_path / "out").exists()
    assert (tmp_path / "failed" / "FAILED.txt").is_file()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no staging folder left behind


def test_mesh_and_model_errors(tmp_path):
    with pytest.raises(contour4d.InvalidInput) as info:
        contour4d.pack({"positions": np.zeros((1, 3, 3)), "triangles": np.array([[0, 1, 5]])})
    assert info.value.exit_code == 25
    with pytest.raises(contour4d.Error) as info:
        contour4d.unpack(b"not a model")
    assert info.value.exit_code in (11, 12, 13)
    with pytest.raises(contour4d.IoError) as info:
        contour4d.evaluate(tmp_path)  # no mesh.pvd, no frames/
    assert info.value.exit_code == 10


def test_work_runs_without_the_gil(phantoms):
    ph = phantoms("left-heart-cycle")
    ticks = 0
    done = threading.Event()

    def work():
        contour4d.reconstruct(ph / "contours.json", threads=1)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    t.join()
    assert ticks > 50  # the main thread kept running while the reconstruction ran


def test_real_data_sunnybrook(data_dir):
    res = contour4d.reconstruct(data_dir / "sunnybrook-SC-HF-I-1", threads=2)
    assert res["positions"].shape[0] == 2 and res["report"]["checks"]["ok"]
    assert res["report"]["frame_times"]["source"] == "data"
    assert 0 < res["report"]["summary"]["ef_percent"] < 100


def test_real_data_bivme_rv_and_slice_alignment(data_dir):
    gp = data_dir / "bivme-patient1" / "guidepoints"
    rv = contour4d.read(gp, label="rv-endo")
    assert {c["label"] for c in rv["contours"]} == {"rv-endo"}
    assert any("joined into" in n for n in rv["notes"])
    plain = contour4d.read(gp)
    aligned = contour4d.read(gp, align_slices=True)
    assert any("slices aligned in plane" in n for n in aligned["notes"])
    moved = [np.abs(a["points"] - p["points"]).max() for a, p in zip(aligned["contours"], plain["contours"])]
    assert 0 < max(moved) < 3  # each slice moved in its plane by at most a few mm
