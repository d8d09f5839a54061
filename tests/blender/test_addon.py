"""The Blender add-on, headless: a sphere scalp and three guides made in Blender, every operator run
from bpy.ops.groom, and each new hair object checked against the groom module's own output for the
same inputs (curve count, point count, positions, radius = width / 2).

Run by tests/blender/run.sh: blender -b --factory-startup --python-exit-code 1 --python THIS."""
import math
import os
import sys

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

cases = [
    ("braid", lambda: groom.braid(guides, scalp=field, fibers=4, knot_length=0.6), dict(fibers=4, knot_length=0.6)),
    ("partition", lambda: groom.partition(guides, scalp=field, count=6), dict(count=6)),
    ("curl", lambda: groom.curl(guides, scalp=field, type="4a"), dict(type="4a")),
    ("generate", lambda: groom.generate(guides, scalp=field, count=40), dict(hairs=40)),
    ("puff", lambda: groom.puff(scalp=field, center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, hairs=20),
     dict(center=(0, 0, 1), radius=0.3, sphere_center=(0, 0, 1.6), sphere_radius=0.4, puff_hairs=20)),
]
for name, expected_fn, props in cases:
    for key in ("fibers", "knot_length", "count", "type", "hairs", "puff_hairs", "center", "radius", "sphere_center", "sphere_radius"):
        settings.property_unset(key)
    for key, value in props.items():
        setattr(settings, key, value)
    select_guides()
    result = getattr(bpy.ops.groom, name)()
    ob = bpy.context.view_layer.objects.active
    check(f"{name}: operator finished", result == {'FINISHED'}, str(result))
    if result != {'FINISHED'}:
        continue
    expected = expected_fn()
    check(f"{name}: makes hair", expected.num_curves > 0, str(expected))
    check(f"{name}: a new hair Curves object", ob.type == 'CURVES' and ob != guides_ob, ob.type)
    counts = (len(ob.data.curves), len(ob.data.points))
    check(f"{name}: curve and point counts", counts == (expected.num_curves, expected.num_points), f"{counts} vs {expected}")
    if counts == (expected.num_curves, expected.num_points):
        pos = np.empty(expected.num_points * 3, np.float32)
        ob.data.attributes['position'].data.foreach_get('vector', pos)
        err = np.abs(pos.reshape(-1, 3) - expected.points).max() if expected.num_points else 0.0
        check(f"{name}: positions", err == 0.0, f"max difference {err}")
        if "width" in expected.point_attributes:
            radius = np.empty(expected.num_points, np.float32)
            ob.data.attributes['radius'].data.foreach_get('value', radius)
            check(f"{name}: radius is half the width", np.array_equal(radius, 0.5 * expected.point_attributes["width"]))

# Errors reach the artist as a report, not a traceback: a partition with no scalp.
settings.scalp = None
select_guides()
try:
    r = bpy.ops.groom.partition()
    check("no scalp: cancelled", r == {'CANCELLED'}, str(r))
except RuntimeError as e:  # bpy raises the operator's ERROR report as RuntimeError in background mode
    check("no scalp: reported", "scalp" in str(e), str(e))

groom_blender.unregister()
check("unregister removes the operators", not hasattr(bpy.types, "GROOM_OT_braid"))

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
