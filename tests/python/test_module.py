"""The groom Python module: numpy views of the container's memory, the CLI's options as keywords
with the CLI's bytes, the scalp's queries against an analytic sphere, and errors that name the
parameter. Run by CTest (tests/python, see CMakeLists.txt) with PYTHONPATH at the built module."""
import math
import os
import subprocess
import threading
import time

import numpy as np
import pytest

import groom

GROOM = os.environ.get("GROOM_BINARY", "groom")


def straight_guides(n=3, points=8, length=4.0, spacing=1.5):
    """n vertical guides along +Y, root at y = 0, x = i * spacing."""
    pts = np.zeros((n * points, 3), np.float32)
    for i in range(n):
        pts[i * points:(i + 1) * points, 0] = i * spacing
        pts[i * points:(i + 1) * points, 1] = np.linspace(0.0, length, points)
    return groom.CurveSet(pts, np.full(n, points, np.int64))


def uv_sphere(radius=1.0, rings=48, segments=96):
    """A closed UV sphere mesh: vertices (n, 3) and triangles (m, 3)."""
    verts = [(0.0, radius, 0.0)]
    for r in range(1, rings):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            verts.append((radius * math.sin(theta) * math.cos(phi), radius * math.cos(theta), radius * math.sin(theta) * math.sin(phi)))
    verts.append((0.0, -radius, 0.0))
    tris = []
    ring = lambda r, s: 1 + (r - 1) * segments + (s % segments)
    for s in range(segments):
        tris.append((0, ring(1, s + 1), ring(1, s)))
        tris.append((len(verts) - 1, ring(rings - 1, s), ring(rings - 1, s + 1)))
    for r in range(1, rings - 1):
        for s in range(segments):
            a, b, c, d = ring(r, s), ring(r, s + 1), ring(r + 1, s), ring(r + 1, s + 1)
            tris += [(a, b, d), (a, d, c)]
    return np.array(verts, np.float32), np.array(tris, np.int32)


@pytest.fixture(scope="module")
def sphere():
    v, f = uv_sphere()
    return groom.Scalp.from_mesh(v, f, voxel=0.02)


def test_points_share_the_containers_memory(tmp_path):
    cs = straight_guides()
    assert (cs.num_curves, cs.num_points) == (3, 24)
    assert cs.points.dtype == np.float32 and cs.points.shape == (24, 3)
    view = cs.points
    view[0] = (7.0, 8.0, 9.0)  # writes through to the container: the file written has it
    groom.write(cs, str(tmp_path / "a.usda"))
    back = groom.read(str(tmp_path / "a.usda"))
    assert tuple(back.points[0]) == (7.0, 8.0, 9.0)
    assert list(back.counts) == [8, 8, 8] and list(back.offsets) == [0, 8, 16, 24]
    # The view keeps the set alive after the last other reference goes.
    del cs, back
    assert view[0, 2] == 9.0


def test_attributes_are_numpy_columns_on_three_domains(tmp_path):
    cs = straight_guides()
    cs.point_attributes["width"] = np.linspace(0.1, 0.2, cs.num_points)
    cs.curve_attributes["id"] = np.array([10, 11, 12], np.int64)
    cs.curve_attributes["Cd"] = np.ones((3, 3))
    cs.detail_attributes["hair_type"] = "4a"
    groom.write(cs, str(tmp_path / "a.usda"))
    back = groom.read(str(tmp_path / "a.usda"))
    assert set(back.point_attributes.keys()) == {"P", "width"}
    assert back.point_attributes["width"].dtype == np.float32
    np.testing.assert_allclose(back.point_attributes["width"], np.linspace(0.1, 0.2, 24), rtol=1e-6)
    assert list(back.curve_attributes["id"]) == [10, 11, 12]
    assert back.curve_attributes["Cd"].shape == (3, 3)
    assert back.detail_attributes["hair_type"] == "4a"
    assert "width" in back.point_attributes and "nope" not in back.point_attributes
    del back.point_attributes["width"]
    assert "width" not in back.point_attributes
    with pytest.raises(KeyError):
        back.curve_attributes["nope"]
    with pytest.raises(groom.ParamError, match="expected 3 values"):
        back.curve_attributes["bad"] = np.zeros(5)


def test_bad_arrays_name_what_is_wrong():
    with pytest.raises(ValueError, match=r"counts add up to 5 points but points has 4 rows"):
        groom.CurveSet(np.zeros((4, 3)), np.array([2, 3]))
    with pytest.raises(groom.ParamError, match=r"shape \(n, 3\)"):
        groom.CurveSet(np.zeros((4, 2)), np.array([4]))
    with pytest.raises(groom.Error, match="nan"):
        groom.CurveSet(np.full((2, 3), np.nan), np.array([2]))
    # A mesh with a NaN vertex was refused as "no extent (all vertices at one point)" (a trial); a
    # face naming a vertex past the end is named by its array row (the repair counted faces from 1).
    tri = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [np.nan, 0, 0]], np.float32)
    with pytest.raises(groom.ParamError, match=r"vertices: row 3 is not finite \(nan,0,0\)"):
        groom.Scalp.from_mesh(tri, np.array([[0, 1, 2]]), voxel=0.1)
    with pytest.raises(groom.ParamError, match=r"faces: row 1 names vertex 7; expected 0 to 2"):
        groom.Scalp.from_mesh(tri[:3], np.array([[0, 1, 2], [0, 2, 7]]), voxel=0.1)
    # Numbers that are not whole, or that no int64 holds, were cast without a word (a trial: counts
    # [2.5, 2.5] made two curves of 2, a face index 2.7 named vertex 2, a uint64 2^64 - 1 read back -1).
    with pytest.raises(groom.ParamError, match=r"counts: expected whole numbers, found 2.5"):
        groom.CurveSet(np.zeros((5, 3)), [2.5, 2.5])
    with pytest.raises(groom.ParamError, match=r"faces: expected whole numbers, found 2.7"):
        groom.Scalp.from_mesh(tri[:3], np.array([[0, 1, 2.7]]), voxel=0.1)
    curves = groom.CurveSet(np.zeros((5, 3)), [2.0, 3.0])  # whole floats are counts
    assert list(curves.counts) == [2, 3]
    with pytest.raises(groom.ParamError, match=r"curve attribute 'big': values 1 to 18446744073709551615 are outside"):
        curves.curve_attributes["big"] = np.array([2**64 - 1, 1], np.uint64)
    with pytest.raises(groom.ParamError, match=r"values 1 to 9223372036854775808 are outside"):  # compared exactly, not in float64
        curves.curve_attributes["big"] = np.array([2**63, 1], np.uint64)
    curves.curve_attributes["top"] = np.array([2**63 - 1, 1], np.uint64)
    assert int(curves.curve_attributes["top"][0]) == 2**63 - 1
    curves.curve_attributes["u32"] = np.array([2**32 - 1, 1], np.uint32)  # into int64: it wrapped to -1 in int32
    assert list(curves.curve_attributes["u32"]) == [2**32 - 1, 1]


@pytest.mark.parametrize("op,kwargs,options", [
    ("braid", dict(strands=3, knot_length=1.3, initial_normal=(0, 0, 1)), ["--strands", "3", "--knot-length", "1.3", "--initial-normal", "0,0,1"]),
    ("braid", dict(pattern="fishtail", fibers=6, seed=4), ["--pattern", "fishtail", "--fibers", "6", "--seed", "4"]),
    ("curl", dict(type="4a", seed=2), ["--type", "4a", "--seed", "2"]),
    ("resample", dict(count=12), ["--count", "12"]),
    ("select", dict(ids="0-1", invert=True), ["--ids", "0-1", "--invert"]),
    ("transform", dict(rotate=(0, 0, 90), scale=2, up_axis="z"), ["--rotate", "0,0,90", "--scale", "2", "--up-axis", "z"]),
])
def test_an_op_gives_the_clis_bytes(tmp_path, op, kwargs, options):
    guides = tmp_path / "guides.usda"
    groom.write(straight_guides(), str(guides))
    cli_out, py_out = tmp_path / "cli.usda", tmp_path / "py.usda"
    subprocess.run([GROOM, op, str(guides), "-o", str(cli_out), "--quiet"] + options, check=True)
    groom.write(getattr(groom, op)(groom.read(str(guides)), **kwargs), str(py_out))
    assert py_out.read_bytes() == cli_out.read_bytes()


def test_select_and_transform_cut_and_place_curves():
    cs = straight_guides(n=4)
    # A list of comparisons: all must hold (curve ids are the indices here).
    kept = groom.select(cs, where=["id>=1", "id<=2"])
    assert kept.num_curves == 2
    np.testing.assert_array_equal(kept.points[:, 0], np.repeat([1.5, 3.0], 8).astype(np.float32))
    moved = groom.transform(cs, translate=(1, 2, 3), scale=0.5)
    np.testing.assert_allclose(moved.points, cs.points * 0.5 + np.array([1, 2, 3], np.float32), atol=1e-6)
    with pytest.raises(groom.ParamError, match="where"):
        groom.select(cs, where="id=>1")


def test_scalp_ops_take_a_scalp_object_or_a_path(tmp_path, sphere):
    v, f = uv_sphere()
    mesh = tmp_path / "sphere.obj"
    with open(mesh, "w") as out:
        out.writelines(f"v {x} {y} {z}\n" for x, y, z in v)
        out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f)
    guides = straight_guides(n=2, spacing=0.3)
    guides.points[:, 1] += 1.0  # roots on the sphere's north pole region, growing up
    by_path = groom.generate(guides, scalp=str(mesh), count=50, scalp_voxel=0.02, seed=3)
    by_object = groom.generate(guides, scalp=sphere, count=50, seed=3)
    assert by_path.num_curves == by_object.num_curves == 50
    np.testing.assert_array_equal(by_path.points, by_object.points)
    # No hair point inside the scalp (the op's promise, checked on the output).
    assert (np.linalg.norm(by_object.points, axis=1) >= 1.0 - 0.02).all()


def test_scalp_queries_match_the_analytic_sphere(sphere):
    rng = np.random.default_rng(1)
    dirs = rng.normal(size=(2000, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    radii = rng.uniform(0.9, 1.1, size=(2000, 1))
    pts = (dirs * radii).astype(np.float32)
    # The mesh is a 48 x 96 UV sphere: it lies within R (1 - cos(pi / 48)) = 0.0021 of the sphere;
    # trilinear distances in a 0.02 band add a few thousandths more.
    np.testing.assert_allclose(sphere.distance(pts), radii[:, 0] - 1.0, atol=0.006)
    cosines = np.sum(sphere.normal(pts) * dirs, axis=1)
    assert np.degrees(np.arccos(np.clip(cosines, -1, 1))).max() < 3.0
    np.testing.assert_allclose(np.linalg.norm(sphere.closest(pts), axis=1), 1.0, atol=0.006)
    inside = sphere.inside(np.array([[0, 0, 0], [0.5, 0, 0], [1.5, 0, 0], [0, -3, 0]], np.float32))
    assert inside.dtype == bool and list(inside) == [True, True, False, False]


def test_scalp_queries_are_probes_numbers(tmp_path):
    """Scalp.distance/normal/closest answer as `groom probe` does, bit for bit, for points that
    crowd (a thin shell: per-cell candidates) and points spread through a box (bigger cells, or the
    tree), and far out they are the analytic sphere's."""
    v, f = uv_sphere()
    with open(tmp_path / "sphere.obj", "w") as out:
        out.writelines(f"v {x} {y} {z}\n" for x, y, z in v)
        out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f)
    vdb = str(tmp_path / "sphere.vdb")
    subprocess.run([GROOM, "scalp", str(tmp_path / "sphere.obj"), "-o", vdb, "--voxel", "0.02", "-q"], check=True)
    scalp = groom.Scalp.load(vdb)
    rng = np.random.default_rng(4)
    dirs = rng.normal(size=(20000, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    for pts in ((dirs * rng.uniform(1.07, 1.12, size=(20000, 1))).astype(np.float32),
                rng.uniform(-2.0, 2.0, size=(20000, 3)).astype(np.float32)):
        np.save(tmp_path / "p.npy", pts)
        subprocess.run([GROOM, "probe", str(tmp_path / "p.npy"), "--scalp", vdb, "-o", str(tmp_path / "q.npy"), "-q", "--force"],
                       check=True)
        probe = np.load(tmp_path / "q.npy")
        d, n, c = scalp.distance(pts), scalp.normal(pts), scalp.closest(pts)
        assert np.array_equal(d, probe[:, 3]) and np.array_equal(n, probe[:, 4:7]) and np.array_equal(c, probe[:, 7:10])
        r = np.linalg.norm(pts, axis=1)
        far = r > 1.1  # beyond the band: the mesh's exact distance, within 0.0021 of the sphere's
        np.testing.assert_allclose(d[far], r[far] - 1.0, atol=0.003)


def test_scalp_load_picks_a_grid_or_a_group_by_keyword(tmp_path):
    """Scalp.load(grid=) and (group=) as the commands' --scalp-grid and --scalp-group (a trial found
    no way to pick another program's grid from Python), refused by their Python names where they do
    not apply."""
    v, f = uv_sphere(rings=16, segments=32)
    with open(tmp_path / "two.obj", "w") as out:
        out.write("o head\n")
        out.writelines(f"v {x} {y} {z}\n" for x, y, z in v)
        out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f)
        out.write("o eye\n")  # a small ball 3 units off to the side
        out.writelines(f"v {0.2 * x + 3.0} {0.2 * y} {0.2 * z}\n" for x, y, z in v)
        out.writelines(f"f {a + 1 + len(v)} {b + 1 + len(v)} {c + 1 + len(v)}\n" for a, b, c in f)
    both = groom.Scalp.load(tmp_path / "two.obj", voxel=0.05)
    head = groom.Scalp.load(tmp_path / "two.obj", voxel=0.05, group="head")
    eye_centre = np.array([[3.0, 0.0, 0.0]], dtype=np.float32)
    assert both.distance(eye_centre)[0] < 0.0  # inside the eye
    assert abs(head.distance(eye_centre)[0] - 2.0) < 0.01  # the head's unit sphere alone
    vdb = str(tmp_path / "head.vdb")
    subprocess.run([GROOM, "scalp", str(tmp_path / "two.obj"), "--group", "head", "-o", vdb, "--voxel", "0.05", "-q"], check=True)
    named = groom.Scalp.load(vdb, grid="scalp")
    assert named.voxel_size == pytest.approx(0.05)
    with pytest.raises(groom.ParamError) as e:
        groom.Scalp.load(vdb, grid="surface")
    assert "grid=surface" in str(e.value) and "found: 'scalp'" in str(e.value) and "--" not in str(e.value)
    with pytest.raises(groom.ParamError, match=r"grid=scalp: .*two\.obj is a mesh"):
        groom.Scalp.load(tmp_path / "two.obj", grid="scalp")
    with pytest.raises(groom.ParamError, match=r"group=head: .*head\.vdb is a level set"):
        groom.Scalp.load(vdb, group="head")


def test_errors_name_the_parameter_and_the_value():
    cs = straight_guides()
    with pytest.raises(ValueError) as e:
        groom.braid(cs, knot_length=-1)
    assert isinstance(e.value, groom.ParamError) and isinstance(e.value, groom.Error)
    assert "knot_length" in str(e.value) and "-1" in str(e.value) and "--" not in str(e.value)
    with pytest.raises(groom.ParamError, match="did you mean 'knot_length'"):
        groom.braid(cs, knot_lenght=1.0)
    with pytest.raises(groom.Error, match="scalp"):
        groom.generate(cs, count=5)
    with pytest.raises(groom.Error, match="no such file|cannot open"):
        groom.read("/nonexistent/guides.usda")


def test_none_for_the_curves_is_a_type_error_not_a_crash(sphere):
    # pybind11 let None through as a null pointer and the interpreter died (segfault) in a trial.
    for call in (lambda: groom.generate(None, scalp=sphere, count=10), lambda: groom.curl(None), lambda: groom.braid(None),
                 lambda: groom.cull(None, scalp=sphere), lambda: groom.select(None, ids="0")):
        with pytest.raises(TypeError):
            call()
    with pytest.raises(TypeError, match=r"puffs\[0\] is None"):
        groom.gather([None], scalp=sphere)


def test_objects_made_without_init_are_refused_not_a_crash(sphere, tmp_path):
    # CurveSet.__new__(CurveSet) without __init__ read unmade memory: .points, repr(), len() and
    # groom.write segfaulted the interpreter (as did Scalp's and AttributeView's methods).
    empty = groom.CurveSet.__new__(groom.CurveSet)
    for call in (lambda: empty.points, lambda: repr(empty), lambda: len(empty), lambda: empty.counts, lambda: empty.copy(),
                 lambda: empty.point_attributes, lambda: groom.write(empty, str(tmp_path / "x.usda")), lambda: groom.curl(empty)):
        with pytest.raises(TypeError, match=r"__new__ without __init__.*groom.CurveSet\(points, counts\)"):
            call()
    assert not (tmp_path / "x.usda").exists()
    no_scalp = groom.Scalp.__new__(groom.Scalp)
    for call in (lambda: no_scalp.distance([[0, 0, 0]]), lambda: no_scalp.voxel_size,
                 lambda: groom.curl(straight_guides(points=8, length=1.5), scalp=no_scalp)):
        with pytest.raises(TypeError, match="groom.Scalp.load"):
            call()
    with pytest.raises(TypeError, match="__new__ without __init__"):
        groom.AttributeView.__new__(groom.AttributeView).keys()


def test_warnings_reach_python_as_groom_warnings(sphere):
    """The CLI's unit warnings were dropped (every command ran --quiet): a head in metres got straight
    'curls' with no word why. The sphere is 2 units across, outside a head's 10-300 cm."""
    import warnings
    guides = straight_guides(points=8, length=1.5)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        groom.curl(guides)  # the default radius 1 is more than half of the 1.5 long hairs
    texts = [str(w.message) for w in caught if issubclass(w.category, groom.GroomWarning)]
    assert len(texts) == 1 and "curl radius" in texts[0] and "units_per_cm" in texts[0] and "--" not in texts[0]
    assert issubclass(groom.GroomWarning, UserWarning)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        groom.curl(guides, units_per_cm=0.1)  # a 0.1 radius on 1.5 long hairs shows: nothing to say
    assert not [w for w in caught if issubclass(w.category, groom.GroomWarning)]
    with warnings.catch_warnings():
        warnings.simplefilter("error", groom.GroomWarning)  # a pipeline that wants warnings to stop it
        with pytest.raises(groom.GroomWarning):
            groom.curl(guides)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        groom.generate(guides, scalp=sphere, count=5, scalp_voxel=0.05)  # the Scalp object is built already
    assert any("scalp_voxel" in str(w.message) for w in caught)


def test_input_problems_are_blamed_on_the_input():
    with pytest.raises(groom.ParamError, match="curve 1 has 0 points"):
        groom.CurveSet(np.zeros((5, 3), np.float32), np.array([3, 0, 2]))
    cs = straight_guides()
    cs.points[0] = np.nan  # through the live view, after the constructor checked
    with pytest.raises(groom.ParamError, match=r"^curves: point 0 \(curve 0\) has a non-finite position"):
        groom.curl(cs)
    with pytest.raises(ValueError, match="read-only"):
        cs.counts[0] = 5  # a copy: writing to it would silently change nothing
    with pytest.raises(ValueError, match="read-only"):
        cs.offsets[1] = 5


def test_messages_name_what_python_passed(sphere, tmp_path):
    """A trial's list: messages named the in-memory files a call makes (mem:out1, mem:scalp10),
    printed DBL_MAX in 309 digits, or blamed the wrong thing."""
    cs = straight_guides()
    with pytest.raises(groom.ParamError) as e:
        groom.generate(cs, scalp=sphere, count=10, prim="/x")
    assert "mem:" not in str(e.value) and "the curves given are not a USD file" in str(e.value)
    with pytest.raises(groom.ParamError, match=r"threads: expected 0 \(all cores\) or a number of threads, got -1$"):
        groom.curl(cs, threads=-1)
    with pytest.raises(groom.ParamError, match=r"^points: row 1 is not finite \(nan, 0, 0\)"):
        sphere.distance(np.array([[0, 0, 2], [np.nan, 0, 0]], np.float32))
    with pytest.raises(groom.ParamError, match="the result is returned"):
        groom.curl(cs, output=str(tmp_path / "x.usda"))
    with pytest.raises(groom.ParamError, match="help"):
        groom.curl(cs, help=True)
    with pytest.raises(TypeError, match="scalp: expected a groom.Scalp or a path, got int"):
        groom.generate(cs, scalp=123, count=10)
    with pytest.raises(groom.Error, match="is a directory"):
        groom.read(str(tmp_path))
    with pytest.raises(groom.ParamError, match=r"^resample: count takes a value \(int\), not True/False"):
        groom.resample(cs, count=True)  # it said "count: 1 required INT missing"
    # numpy's bool is a flag like Python's (it was sent as the text "True").
    np.testing.assert_array_equal(groom.braid(cs, rest=np.True_, scalp=sphere).points, groom.braid(cs, rest=True, scalp=sphere).points)


def test_curves_pickle_and_copy_with_every_column():
    """pickle, copy.copy/deepcopy and so multiprocessing said "cannot pickle 'groom.CurveSet'"."""
    import copy
    import pickle
    cs = straight_guides()
    cs.point_attributes["width"] = np.linspace(0.1, 0.2, cs.num_points).astype(np.float32)
    cs.point_attributes["rest"] = (cs.points * 2.0).astype(np.float32)
    cs.curve_attributes["id"] = np.array([7, 8, 2**40], np.int64)
    cs.curve_attributes["kind"] = np.array([1, 2, 3], np.int32)
    cs.detail_attributes["hair_type"] = "4a"
    for twin in (pickle.loads(pickle.dumps(cs)), copy.copy(cs), copy.deepcopy(cs)):
        assert (twin.num_curves, twin.num_points) == (cs.num_curves, cs.num_points)
        np.testing.assert_array_equal(twin.points, cs.points)
        for view, other in ((twin.point_attributes, cs.point_attributes), (twin.curve_attributes, cs.curve_attributes)):
            assert sorted(view.keys()) == sorted(other.keys())
            for k in other.keys():
                np.testing.assert_array_equal(view[k], other[k])
                assert np.asarray(view[k]).dtype == np.asarray(other[k]).dtype
        assert twin.detail_attributes["hair_type"] == "4a"
        twin.points[0] = (9, 9, 9)  # its own memory
        assert tuple(cs.points[0]) != (9.0, 9.0, 9.0)


def test_paths_may_be_pathlib_paths(tmp_path):
    import pathlib
    cs = straight_guides()
    path = pathlib.Path(tmp_path) / "a.usda"
    groom.write(cs, path)
    np.testing.assert_array_equal(groom.read(path).points, cs.points)


def test_threads_do_not_change_the_result():
    cs = straight_guides()
    one = groom.braid(cs, fibers=12, flyaways=0.2, threads=1)
    two = groom.braid(cs, fibers=12, flyaways=0.2, threads=2)
    np.testing.assert_array_equal(one.points, two.points)


def test_the_gil_is_released_while_an_op_runs():
    cs = straight_guides(n=120, points=64, length=40.0)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.01)
    start = time.perf_counter()
    groom.braid(cs, fibers=100)
    end = time.perf_counter()
    done.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    # With the GIL held for the whole op the other thread could not tick at all meanwhile.
    assert end - start > 0.05, "the op was too quick to tell"
    assert len(during) >= 5


def test_gather_takes_puffs_hairline_and_parting_as_curves(sphere):
    """The whole-scalp chain from Python: hairline, parting and puffs go in as CurveSets."""
    hairline = groom.hairline(scalp=sphere)
    assert hairline.num_curves == 1
    parting = groom.parting(scalp=sphere, through="0,0,2/0,2,0/0,0,-2", step=0.05)
    np.testing.assert_allclose(parting.points[:, 0], 0.0, atol=0.01)  # the x = 0 great circle
    puffs = [
        groom.puff(scalp=sphere, center=(s * 0.6, 0.8, 0), radius=0.25, sphere_center=(s * 1.0, 1.3, 0),
                   sphere_radius=0.4, rows=4, cols=4, hairs=50, amplitude=(0.01, 0.02), seed=1)
        for s in (-1, 1)
    ]
    out = groom.gather(puffs, scalp=sphere, hairline=hairline, parting=parting, hairs=300, lift=0.01, step=0.03,
                       band_width=0.08, band_thickness=0.01, amplitude=(0.01, 0.02), parting_gap=0.03, seed=2)
    kind = out.curve_attributes["kind"]
    assert (kind == 1).sum() == 300 and (kind == 2).sum() == 24
    roots = out.points[out.offsets[:-1]]
    hairs = kind == 1
    # Each hair stays on its side of the parting, and nothing is inside the sphere.
    for c in np.nonzero(hairs)[0]:
        xs = out.points[out.offsets[c]:out.offsets[c + 1], 0]
        assert (np.sign(xs) == np.sign(roots[c, 0])).all()
    assert (np.linalg.norm(out.points, axis=1) >= 1.0 - 0.01).all()
    with pytest.raises(groom.ParamError, match="lift"):
        groom.gather(puffs, scalp=sphere, lift=-1)


def test_edges_lie_flat_along_a_hairline_given_as_curves(sphere):
    """Edges from Python on the unit sphere: the hairline goes in as a CurveSet; every point stays
    within the hairs' height of the sphere (plus the mesh's chordal error) and none inside."""
    hairline = groom.hairline(scalp=sphere)
    out = groom.edges(scalp=sphere, hairline=hairline, count=60, length=0.2, radius=0.015, swoop=0.1, depth=0.02,
                      height=0.005, width=0.001, seed=3)
    assert out.num_curves == 60
    assert (out.curve_attributes["kind"] == 3).all()
    r = np.linalg.norm(out.points, axis=1)
    assert (r >= 1.0 - 0.01).all() and (r <= 1.0 + 0.005 + 0.01).all()
    with pytest.raises(groom.ParamError, match="bends"):
        groom.edges(scalp=sphere, bends=0)


def test_sections_part_the_scalp_inside_the_hairline(sphere, tmp_path):
    """Grid sections on the unit sphere: one hanging guide per section, rooted on the sphere inside
    the hairline, the partings to a file; a count that does not fit the layout names the keyword."""
    hairline = groom.hairline(scalp=sphere)
    partings = tmp_path / "partings.usda"
    kw = dict(hairline=hairline, length=1.5, points=12, bend=0.1, clearance=0.02, layer=0.01, parting_gap=0.03, step=0.03)
    guides = groom.sections(scalp=sphere, cols=4, partings_out=str(partings), **kw)
    section = guides.curve_attributes["section"]
    np.testing.assert_array_equal(section, np.arange(guides.num_curves))
    assert guides.num_curves >= 8
    roots = guides.points[guides.offsets[:-1]]
    np.testing.assert_allclose(np.linalg.norm(roots, axis=1), 1.0, atol=0.01)
    assert (np.linalg.norm(guides.points, axis=1) >= 1.0 - 0.01).all()
    assert groom.read(str(partings)).num_curves >= 3
    with pytest.raises(groom.ParamError, match="cols"):
        groom.sections(scalp=sphere, layout="rows", cols=4, **kw)


def test_ops_that_make_hairs_take_root_and_tip_widths(sphere):
    """root_width= and tip_width= are the CLI's --root-width and --tip-width: the root point gets the
    one, the tip point the other, widths fall monotonically between; without them curl writes the
    human-hair defaults (0.008 to 0.004), and edges' width= is still one diameter."""
    def check(cs, root, tip):
        w = cs.point_attributes["width"]
        assert w.dtype == np.float32 and len(w) == cs.num_points
        starts, ends = cs.offsets[:-1], cs.offsets[1:] - 1
        np.testing.assert_array_equal(w[starts], np.float32(root))
        np.testing.assert_array_equal(w[ends], np.float32(tip))
        for c in range(cs.num_curves):
            assert (np.diff(w[cs.offsets[c]:cs.offsets[c + 1]]) <= 0).all()

    guides = straight_guides()
    check(groom.curl(guides, amplitude=(0.1, 0.2)), 0.008, 0.004)
    check(groom.curl(guides, amplitude=(0.1, 0.2), root_width=0.01, tip_width=0.002), 0.01, 0.002)
    hairline = groom.hairline(scalp=sphere)
    check(groom.edges(scalp=sphere, hairline=hairline, count=20, root_width=0.003, tip_width=0.001), 0.003, 0.001)
    check(groom.edges(scalp=sphere, hairline=hairline, count=20, width=0.002), 0.002, 0.002)
    with pytest.raises(groom.ParamError, match="root_width must be a finite number > 0"):
        groom.curl(guides, root_width=-1)


def test_scalp_fill_holes_and_joined_meshes():
    # A sphere missing its top fan (a hole whose rim is the first ring, at y = cos(pi / rings)):
    # fill_holes= closes it, so above it the distance is to the rim's plane, as `groom scalp
    # --fill-holes`. And two meshes' arrays concatenated are one scalp, their union: inside the
    # sphere beside a second sphere's buried back reads inside.
    rings = 16
    v, f = uv_sphere(rings=rings)
    open_f = f[~np.any(f == 0, axis=1)]
    plane = math.cos(math.pi / rings)
    above = np.array([[0, 1.5, 0]], np.float32)
    filled = groom.Scalp.from_mesh(v, open_f, voxel=0.02, fill_holes=10.0)
    assert abs(filled.distance(above)[0] - (1.5 - plane)) < 1e-4
    unfilled = groom.Scalp.from_mesh(v, open_f, voxel=0.02)
    assert unfilled.distance(above)[0] > 1.5 - plane + 0.01  # to the rim, farther than the plane
    with pytest.raises(groom.ParamError, match="fill_holes"):
        groom.Scalp.from_mesh(v, open_f, voxel=0.02, fill_holes=-1.0)
    eye_v = v * 0.3 + np.array([0.9, 0, 0], np.float32)
    both = groom.Scalp.from_mesh(np.concatenate([v, eye_v]), np.concatenate([f, f + len(v)]), voxel=0.02)
    d = both.distance(np.array([[0.5, 0, 0], [1.1, 0, 0]], np.float32))
    assert d[0] < -0.45 and -0.12 < d[1] < -0.08, d


def test_write_warns_of_the_columns_the_format_cannot_hold(tmp_path):
    """groom.write to .obj dropped width and ids without a word (a trial); now a GroomWarning names them."""
    import warnings
    guides = straight_guides(points=4, length=1.0)
    guides.point_attributes["width"] = np.full(guides.num_points, 0.01, np.float32)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        groom.write(guides, tmp_path / "g.obj")
        groom.write(guides, tmp_path / "g.usda")
    texts = [str(w.message) for w in caught if issubclass(w.category, groom.GroomWarning)]
    assert len(texts) == 1 and "g.obj: .obj cannot hold these attributes, dropped: point width" in texts[0], texts


def test_flags_given_numbers_and_frames_are_named():
    """keep_extent=0 said "unexpected argument: 0"; frames= said every frame "would write over this
    file", a file the call does not have (a trial)."""
    guides = straight_guides(points=8, length=1.5)
    with pytest.raises(groom.ParamError, match=r"curl: keep_extent is a flag: pass True or False \(got 0\)"):
        groom.curl(guides, keep_extent=0, units_per_cm=0.1)
    with pytest.raises(groom.ParamError, match="frames: a call returns one result, for one frame"):
        groom.curl(guides, frames="1:3", units_per_cm=0.1)
