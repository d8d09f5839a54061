"""The Blender add-on, headless: a sphere scalp and three guides made in Blender, every operator run
from bpy.ops.groom, and each new hair object checked against the groom module's own output for the
same inputs (curve count, point count, positions, radius = width / 2). Then what the panel shows
against what runs, legacy curves as Blender draws them, widths written back from a hair object, and
the reports an artist gets for a wrong selection.

Run by tests/blender/run.sh: blender -b --factory-startup --python-exit-code 1 --python THIS."""
import math
import os
import sys
import tempfile
import traceback
import types

import bpy
import numpy as np

sys.path.insert(0, os.environ["GROOM_BLENDER_ADDON_DIR"])
import groom  # noqa: E402
import groom_blender  # noqa: E402
from groom_blender import convert  # noqa: E402

groom_blender.register()
failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def part(what):
    """Runs a block of checks at once; an exception in it fails the block by name instead of ending
    the run, so every later block still reports."""
    def run(fn):
        try:
            fn()
        except Exception as e:
            traceback.print_exc()
            check(f"{what}: ran to the end", False, f"{type(e).__name__}: {e}")
        return fn
    return run


def unset(settings, *names):
    """Back to the panel's defaults (names this add-on does not have are skipped)."""
    for name in names:
        if name in settings.bl_rna.properties:
            settings.property_unset(name)


def select_only(*obs):
    for ob in bpy.context.view_layer.objects:
        ob.select_set(ob in obs)
    bpy.context.view_layer.objects.active = obs[0] if obs else None


def point_positions(ob):
    pos = np.empty(len(ob.data.points) * 3, np.float32)
    ob.data.attributes['position'].data.foreach_get('vector', pos)
    return pos.reshape(-1, 3)


def run_report(opname):
    """bpy.ops.groom.OPNAME(): (result, error text); background Blender raises an ERROR report."""
    try:
        return getattr(bpy.ops.groom, opname)(), ""
    except RuntimeError as e:
        return {'CANCELLED'}, str(e)


class PanelRecorder:
    """A stand-in for the panel's layout: which settings and labels it draws."""
    def __init__(self):
        self.props, self.labels = [], []

    def column(self, *args, **kw):
        return self

    box = row = column

    def prop(self, data, name, **kw):
        self.props.append(name)

    def label(self, text="", **kw):
        self.labels.append(text)

    def operator(self, *args, **kw):
        pass

    def separator(self, *args, **kw):
        pass


def panel_draws():
    from groom_blender import panel
    rec = PanelRecorder()
    panel.GROOM_PT_panel.draw(types.SimpleNamespace(layout=rec), types.SimpleNamespace(scene=bpy.context.scene))
    return rec


# The scene: a unit sphere (the scalp) and three cornrow-like guides lying 0.02 above it, arcs from
# front to back over the top, 0.25 apart.
for ob in list(bpy.data.objects):
    bpy.data.objects.remove(ob)
bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=64, ring_count=32, location=(0, 0, 0))
scalp = bpy.context.active_object
scalp.name = "scalp"
cu = bpy.data.curves.new("guides", 'CURVE')
cu.dimensions = '3D'
for k in (-1, 0, 1):
    spline = cu.splines.new('POLY')
    spline.points.add(15)
    x = 0.25 * k
    ring = math.sqrt(1 - x * x) * 1.02
    co = [(x * 1.02, ring * math.cos(a), ring * math.sin(a), 1.0) for a in np.linspace(0.3, math.pi - 0.3, 16)]
    spline.points.foreach_set('co', np.array(co, np.float32).ravel())
guides_ob = bpy.data.objects.new("guides", cu)
bpy.context.scene.collection.objects.link(guides_ob)
settings = bpy.context.scene.groom
settings.scalp = scalp
settings.scalp_voxel = 0.02


def select_guides():
    for ob in bpy.context.view_layer.objects:
        ob.select_set(ob == guides_ob)
    bpy.context.view_layer.objects.active = guides_ob


menu = [f.__name__ for f in bpy.types.VIEW3D_MT_object._dyn_ui_initialize()]
check("Object menu has the Groom submenu", "draw_object_menu" in menu, str(menu[-3:]))

guides = convert.guides_from_objects([guides_ob])
check("guides read from the legacy curve", (guides.num_curves, guides.num_points) == (3, 48))
field = convert.scalp_from_object(scalp, 0.02)
d = field.distance(np.array([[0, 0, 0], [0, 0, 2]], np.float32))
check("scalp from the sphere mesh", abs(d[0] + 1) < 0.01 and abs(d[1] - 1) < 0.01, str(d))

def generate_matches(label, field):
    """Runs the Generate operator (40 hairs) on the selected guides and checks its object's points
    equal the module's generate on `field`; returns the new object."""
    select_guides()
    result = bpy.ops.groom.generate()
    ob = bpy.context.view_layer.objects.active
    expected = groom.generate(guides, scalp=field, count=40)
    pos = np.empty(len(ob.data.points) * 3, np.float32)
    ob.data.attributes['position'].data.foreach_get('vector', pos)
    check(label, result == {'FINISHED'} and pos.size == expected.points.size and np.array_equal(pos.reshape(-1, 3), expected.points),
          str(result))
    return ob


# Meshes joined to the scalp (the panel's "Joined" collection): an eyeball half through the sphere.
# The scalp is their union: inside the sphere beside the eyeball's back reads inside (the eyeball's
# back, buried in the sphere, is not part of the surface), inside the eyeball outside the sphere too.
bpy.ops.mesh.primitive_uv_sphere_add(radius=0.3, segments=32, ring_count=16, location=(0.9, 0, 0))
eye = bpy.context.active_object
eye.name = "eye"
joined = bpy.data.collections.new("joined")
bpy.context.scene.collection.children.link(joined)
joined.objects.link(eye)
with_eye = convert.scalp_from_object(scalp, 0.02, joined.all_objects)
d = with_eye.distance(np.array([[0.5, 0, 0], [1.1, 0, 0], [1.3, 0, 0]], np.float32))
check("joined: inside the sphere beside the eyeball", d[0] < -0.3, str(d))
check("joined: inside the eyeball out of the sphere", -0.15 < d[1] < -0.05, str(d))
check("joined: outside both", abs(d[2] - 0.1) < 0.01, str(d))
settings.scalp_extras = joined
settings.property_unset("hairs")
settings.hairs = 40
ob = generate_matches("joined: the operator grows on the joined scalp", with_eye)
settings.scalp_extras = None
bpy.data.objects.remove(ob)
bpy.data.objects.remove(eye)
bpy.data.collections.remove(joined)

# Fill holes: a sphere missing its top fan (the rim is its first ring, at z = cos(pi / 16)); filled,
# above it the distance is to the rim's plane, and the Generate operator grows on the filled scalp.
rings, segs = 16, 32
verts = [(0.0, 0.0, 1.0)] + [(math.sin(math.pi * r / rings) * math.cos(2 * math.pi * s / segs),
                              math.sin(math.pi * r / rings) * math.sin(2 * math.pi * s / segs),
                              math.cos(math.pi * r / rings)) for r in range(1, rings) for s in range(segs)] + [(0.0, 0.0, -1.0)]
ring_at = lambda r, s: 1 + (r - 1) * segs + s % segs
faces = [(len(verts) - 1, ring_at(rings - 1, s + 1), ring_at(rings - 1, s)) for s in range(segs)]
faces += [q for r in range(1, rings - 1) for s in range(segs)
          for q in [(ring_at(r, s), ring_at(r + 1, s), ring_at(r + 1, s + 1), ring_at(r, s + 1))]]
open_mesh = bpy.data.meshes.new("open")
open_mesh.from_pydata(verts, [], faces)
open_ob = bpy.data.objects.new("open", open_mesh)
bpy.context.scene.collection.objects.link(open_ob)
plane = math.cos(math.pi / rings)
above = np.array([[0, 0, 1.5]], np.float32)
filled = convert.scalp_from_object(open_ob, 0.02, (), 10.0)
unfilled = convert.scalp_from_object(open_ob, 0.02)
check("fill holes: above the filled hole, the rim's plane", abs(filled.distance(above)[0] - (1.5 - plane)) < 1e-4,
      str(filled.distance(above)))
check("fill holes: unfilled, farther (the rim)", unfilled.distance(above)[0] > 1.5 - plane + 0.01, str(unfilled.distance(above)))
settings.scalp = open_ob
settings.scalp_fill_holes = 10.0
ob = generate_matches("fill holes: the operator grows on the filled scalp", filled)
settings.property_unset("scalp_fill_holes")
settings.scalp = scalp
bpy.data.objects.remove(ob)
bpy.data.objects.remove(open_ob)

cases = [
    ("braid", lambda: groom.braid(guides, scalp=field, fibers=4, knot_length=0.6), dict(fibers=4, knot_length=0.6)),
    ("partition", lambda: groom.partition(guides, scalp=field, count=6), dict(count=6)),
    ("curl", lambda: groom.curl(guides, scalp=field, type="4a"), dict(type="4a")),
    ("generate", lambda: groom.generate(guides, scalp=field, count=40), dict(hairs=40)),
    # Units per cm reaches Generate (its widths) and Curl (its radius), not only Edges: a scene in
    # metres got 2 cm hairs and curls that did not show.
    ("generate", lambda: groom.generate(guides, scalp=field, count=40, units_per_cm=0.01), dict(hairs=40, units_per_cm=0.01)),
    ("curl", lambda: groom.curl(guides, scalp=field, type="4a", units_per_cm=0.1), dict(type="4a", units_per_cm=0.1)),
    ("puff", lambda: groom.puff(scalp=field, center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, hairs=20),
     dict(center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, puff_hairs=20)),
    # ... and Partition and Puff too (a trial in metres: Partition's and Puff's hairs 4-8 mm thick).
    ("partition", lambda: groom.partition(guides, scalp=field, count=6, units_per_cm=0.1), dict(count=6, units_per_cm=0.1)),
    ("puff", lambda: groom.puff(scalp=field, center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, hairs=20,
                                units_per_cm=0.1),
     dict(center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, puff_hairs=20, units_per_cm=0.1)),
    # The Puff's own hair type and uniformity, not Curl's type (it had ignored uniformity).
    ("puff", lambda: groom.puff(scalp=field, center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, hairs=20,
                                type="2a", uniformity=0.2),
     dict(center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, puff_hairs=20, type="4c", puff_type="2a",
          puff_uniformity=0.2)),
]
SETTINGS_USED = ("fibers", "knot_length", "count", "partition_by", "spacing", "width", "type", "hairs", "puff_hairs", "puff_place",
                 "center", "radius", "sphere_center", "sphere_radius", "puff_type", "puff_uniformity", "units_per_cm")
made = {}  # label -> the object the case made


def run_case(name, expected_fn, props):
    label = f"{name} ({', '.join(f'{k}={v}' for k, v in props.items())})"
    unset(settings, *SETTINGS_USED)
    for key, value in props.items():
        setattr(settings, key, value)
    select_guides()
    result, error = run_report(name)
    ob = bpy.context.view_layer.objects.active
    check(f"{label}: operator finished", result == {'FINISHED'}, str(result) + error)
    if result != {'FINISHED'}:
        return
    made[label] = ob
    expected = expected_fn()
    check(f"{label}: makes hair", expected.num_curves > 0, str(expected))
    check(f"{label}: a new hair Curves object", ob.type == 'CURVES' and ob != guides_ob, ob.type)
    counts = (len(ob.data.curves), len(ob.data.points))
    check(f"{label}: curve and point counts", counts == (expected.num_curves, expected.num_points), f"{counts} vs {expected}")
    if counts == (expected.num_curves, expected.num_points):
        pos = np.empty(expected.num_points * 3, np.float32)
        ob.data.attributes['position'].data.foreach_get('vector', pos)
        err = np.abs(pos.reshape(-1, 3) - expected.points).max() if expected.num_points else 0.0
        check(f"{label}: positions", err == 0.0, f"max difference {err}")
        if "width" in expected.point_attributes:
            radius = np.empty(expected.num_points, np.float32)
            ob.data.attributes['radius'].data.foreach_get('value', radius)
            check(f"{label}: radius is half the width", np.array_equal(radius, 0.5 * expected.point_attributes["width"]))


for name, expected_fn, props in cases:
    part(name)(lambda: run_case(name, expected_fn, props))

# The whole scalp, Z-up as Blender is: a head-sized sphere (radius 10, centimetres like groom's
# defaults), its hairline, edges along it, grid sections, and two puffs gathered. Each object must
# equal the module's output for the same inputs with up = +Z and the face toward -Y.
unset(settings, *SETTINGS_USED)
bpy.ops.mesh.primitive_uv_sphere_add(radius=10.0, segments=96, ring_count=48, location=(0, 0, 0))
head = bpy.context.active_object
head.name = "head"
settings.scalp = head
settings.scalp_voxel = 0.1
head_field = convert.scalp_from_object(head, 0.1)
up, forward = (0.0, 0.0, 1.0), (0.0, -1.0, 0.0)


def same_as(name, ob, expected):
    """The new object holds exactly `expected` (counts and positions)."""
    counts = (len(ob.data.curves), len(ob.data.points))
    check(f"{name}: curve and point counts", counts == (expected.num_curves, expected.num_points), f"{counts} vs {expected}")
    if counts == (expected.num_curves, expected.num_points) and expected.num_points:
        pos = np.empty(expected.num_points * 3, np.float32)
        ob.data.attributes['position'].data.foreach_get('vector', pos)
        err = np.abs(pos.reshape(-1, 3) - expected.points).max()
        check(f"{name}: positions", err == 0.0, f"max difference {err}")


def run_op(name):
    result = getattr(bpy.ops.groom, name)()
    check(f"{name}: operator finished", result == {'FINISHED'}, str(result))
    return bpy.context.view_layer.objects.active if result == {'FINISHED'} else None


hairline_ob = run_op("hairline")
if hairline_ob is not None:
    expected = groom.hairline(scalp=head_field, up=up, forward=forward)
    same_as("hairline", hairline_ob, expected)
    # No width: drawn thin (a thousandth of its extent), not with Blender's default radius of 1.
    radius = np.empty(expected.num_points, np.float32)
    hairline_ob.data.attributes['radius'].data.foreach_get('value', radius)
    extent = float(np.max(expected.points.max(axis=0) - expected.points.min(axis=0)))
    check("hairline: drawn thin", np.allclose(radius, 1e-3 * extent), f"radius {radius[:2]} extent {extent}")
    # Z-up read right: the hairline is higher at the forehead (-Y) than at the nape (+Y).
    p = expected.points
    check("hairline: forehead above the nape", p[np.argmin(p[:, 1]), 2] > p[np.argmax(p[:, 1]), 2] + 2.0)
    settings.hairline = hairline_ob
    hairline = convert.curveset_from_object(hairline_ob)
    settings.edge_count = 40
    edges_ob = run_op("edges")
    if edges_ob is not None:
        same_as("edges", edges_ob, groom.edges(scalp=head_field, up=up, forward=forward, hairline=hairline, count=40))
    settings.cols = 4
    sections_ob = run_op("sections")
    if sections_ob is not None:
        same_as("sections", sections_ob, groom.sections(scalp=head_field, up=up, forward=forward, hairline=hairline, cols=4))
    puffs = []
    for side in (-1, 1):
        settings.center, settings.radius = (6.0 * side, 0.0, 8.0), 2.5
        settings.sphere_center, settings.sphere_radius = (10.0 * side, 0.0, 13.0), 4.0
        ob = run_op("puff")
        if ob is not None:
            puffs.append(ob)
    check("puff: keeps its base and sphere for gather", all("groom_puff_base" in ob for ob in puffs) and len(puffs) == 2)
    if len(puffs) == 2:
        puff_sets = [convert.curveset_from_object(ob) for ob in puffs]
        check("puff: kind kept as a curve attribute", all((np.asarray(c.curve_attributes["kind"]) == 0).all() for c in puff_sets))
        for ob in bpy.context.view_layer.objects:
            ob.select_set(ob in puffs)
        settings.gather_hairs = 200
        gathered = run_op("gather")
        if gathered is not None:
            expected = groom.gather(puff_sets, scalp=head_field, up=up, hairline=hairline, hairs=200)
            same_as("gather", gathered, expected)
            kind = np.asarray(expected.curve_attributes["kind"])
            check("gather: hairs and bands", (kind == 1).sum() == 200 and (kind == 2).sum() > 0)
            # No Hairline object: the head's default hairline, oriented by Up and Forward (before,
            # the whole bust was gathered, face included; a trial).
            settings.hairline = None
            for ob in bpy.context.view_layer.objects:
                ob.select_set(ob in puffs)
            unbounded = run_op("gather")
            if unbounded is not None:
                same_as("gather without a hairline", unbounded, groom.gather(puff_sets, scalp=head_field, up=up, forward=forward, hairs=200))
            settings.hairline = hairline_ob
    for ob in bpy.context.view_layer.objects:
        ob.select_set(False)
    r = None
    try:
        r = bpy.ops.groom.gather()
        check("gather with no puff selected: cancelled", r == {'CANCELLED'}, str(r))
    except RuntimeError as e:
        check("gather with no puff selected: reported", "select the puffs" in str(e), str(e))

# Errors reach the artist as a report, not a traceback: a partition with no scalp.
settings.scalp = None
select_guides()
try:
    r = bpy.ops.groom.partition()
    check("no scalp: cancelled", r == {'CANCELLED'}, str(r))
except RuntimeError as e:  # bpy raises the operator's ERROR report as RuntimeError in background mode
    check("no scalp: reported", "scalp" in str(e), str(e))

# Guides that make nothing (a single point): an error report and no empty object, not FINISHED.
cu = bpy.data.curves.new("dot", 'CURVE')
cu.dimensions = '3D'
cu.splines.new('POLY')  # one point
dot = bpy.data.objects.new("dot", cu)
bpy.context.scene.collection.objects.link(dot)
for ob in bpy.context.view_layer.objects:
    ob.select_set(ob == dot)
bpy.context.view_layer.objects.active = dot
before = len(bpy.data.objects)
try:
    r = bpy.ops.groom.braid()
    check("braid of nothing: cancelled", r == {'CANCELLED'}, str(r))
except RuntimeError as e:
    check("braid of nothing: reported", "made no curves" in str(e), str(e))
check("braid of nothing: no empty object", len(bpy.data.objects) == before, f"{before} -> {len(bpy.data.objects)}")

groom_blender.unregister()
check("unregister removes the operators", not hasattr(bpy.types, "GROOM_OT_braid"))

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
