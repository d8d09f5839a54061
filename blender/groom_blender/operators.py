"""The operators (bpy.ops.groom.braid, .partition, .curl, .puff, .generate) and their settings.

Each setting is named like the command-line option it feeds (knot_length -> --knot-length) and only
settings the artist changed are passed on, so an untouched panel runs with groom's own defaults; the
defaults shown here are the CLI's (`groom COMMAND --help`)."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty, IntProperty, PointerProperty

import groom

from . import convert

HAIR_TYPES = [(t, t, f"Hair type {t}") for t in ("2a", "2b", "2c", "3a", "3b", "3c", "4a", "4b", "4c")]
PATTERNS = [
    ("plait", "Plait", "Woven: every strand over, then under"),
    ("fishtail", "Fishtail", "Two sections, an outer piece crossing each time"),
    ("twist", "Twist", "Two plies twisted"),
    ("rope", "Rope", "Three or more plies twisted"),
    ("round", "Round", "Tubular, maypole over/under"),
    ("lissajous", "Lissajous", "The talk's formula as written"),
]


def _mesh_poll(self, ob):
    return ob.type == 'MESH'


class GroomSettings(bpy.types.PropertyGroup):
    scalp: PointerProperty(name="Scalp", type=bpy.types.Object, poll=_mesh_poll, description="Mesh the hair grows on")
    scalp_voxel: FloatProperty(name="Scalp voxel", default=0.0, min=0.0, description="Voxel size of the scalp's field (0 = automatic)")
    threads: IntProperty(name="Threads", default=0, min=0, description="Worker threads (0 = all cores); results are identical for any count")
    seed: IntProperty(name="Seed", default=0, min=0)
    # braid
    pattern: EnumProperty(name="Pattern", items=PATTERNS, default="plait")
    strands: IntProperty(name="Strands", default=0, min=0, description="Strands per braid (0 = the pattern's own)")
    knot_length: FloatProperty(name="Knot length", default=0.0, min=0.0, description="Length of one knot (0 = groom's default frequency)")
    orient: EnumProperty(name="Orient", items=[("frame", "Frame", "Rotation-minimising frames"),
                                               ("scalp", "Scalp", "Cornrows: the normal is the scalp's")], default="frame")
    fibers: IntProperty(name="Fibers", default=0, min=0, description="Hair fibers per strand (0 = strand centrelines)")
    rest: BoolProperty(name="Rest on scalp", default=False)
    # partition
    count: IntProperty(name="Segments per side", default=24, min=1)
    samples: IntProperty(name="Points per segment", default=8, min=2)
    width: FloatProperty(name="Hair width", default=0.01, min=0.0)
    # curl
    type: EnumProperty(name="Hair type", items=HAIR_TYPES, default="3a")
    uniformity: FloatProperty(name="Uniformity", default=0.7, min=0.0, max=1.0)
    # generate
    hairs: IntProperty(name="Hairs", default=1000, min=1)
    neighbours: IntProperty(name="Neighbours", default=4, min=1)
    # puff
    center: FloatVectorProperty(name="Region centre", default=(0.0, 1.0, 0.0), subtype='XYZ')
    radius: FloatProperty(name="Region radius", default=0.3, min=0.0)
    sphere_center: FloatVectorProperty(name="Puff centre", default=(0.0, 1.5, 0.0), subtype='XYZ')
    sphere_radius: FloatProperty(name="Puff radius", default=0.5, min=0.0)
    puff_hairs: IntProperty(name="Puff hairs", default=0, min=0)


def _given(settings, names):
    """The settings among `names` the artist set (so groom's defaults apply to the rest)."""
    out = {}
    for name in names:
        if settings.is_property_set(name):
            value = getattr(settings, name)
            out[name] = tuple(value) if hasattr(value, "__len__") and not isinstance(value, str) else value
    return out


class _GroomOperator:
    bl_options = {'REGISTER', 'UNDO'}
    needs_guides = True
    needs_scalp = True
    keywords = ()

    def run(self, settings, guides, scalp, kw):
        """The groom call: a CurveSet from the guides (None for puff), the scalp and keywords."""
        raise NotImplementedError

    def execute(self, context):
        settings = context.scene.groom
        try:
            guides = None
            if self.needs_guides:
                chosen = [ob for ob in context.selected_objects if ob.type in {'CURVES', 'CURVE'} and ob != settings.scalp]
                guides = convert.guides_from_objects(chosen)
            scalp = None
            if settings.scalp is not None:
                scalp = convert.scalp_from_object(settings.scalp, settings.scalp_voxel)
            elif self.needs_scalp:
                raise ValueError("scalp: choose a scalp mesh in the Groom panel")
            kw = _given(settings, ("threads",))
            result = self.run(settings, guides, scalp, kw)
        except (groom.Error, ValueError) as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        ob = convert.curves_object(result, self.bl_label.split()[-1].lower(), context.collection)
        self.report({'INFO'}, f"groom: {result.num_curves} curves, {result.num_points} points -> {ob.name}")
        return {'FINISHED'}


class GROOM_OT_braid(_GroomOperator, bpy.types.Operator):
    """Braid the selected guide curves (cornrows with Orient = Scalp)"""
    bl_idname = "groom.braid"
    bl_label = "Groom Braid"
    needs_scalp = False

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("pattern", "strands", "knot_length", "orient", "fibers", "rest", "seed")))
        return groom.braid(guides, scalp=scalp, **kw)


class GROOM_OT_partition(_GroomOperator, bpy.types.Operator):
    """Edge hairs between the selected (braided) guides"""
    bl_idname = "groom.partition"
    bl_label = "Groom Partition"

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("count", "samples", "width", "seed")))
        return groom.partition(guides, scalp=scalp, **kw)


class GROOM_OT_curl(_GroomOperator, bpy.types.Operator):
    """Curl the selected curves (scalp optional: keeps curls outside it)"""
    bl_idname = "groom.curl"
    bl_label = "Groom Curl"
    needs_scalp = False

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("type", "uniformity", "seed")))
        return groom.curl(guides, scalp=scalp, **kw)


class GROOM_OT_generate(_GroomOperator, bpy.types.Operator):
    """Grow hairs over the scalp from the selected guides"""
    bl_idname = "groom.generate"
    bl_label = "Groom Generate"

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("neighbours", "seed")))
        return groom.generate(guides, scalp=scalp, count=s.hairs, **kw)


class GROOM_OT_puff(_GroomOperator, bpy.types.Operator):
    """An afro puff: guides from a region of the scalp into a sphere, curled hairs optional"""
    bl_idname = "groom.puff"
    bl_label = "Groom Puff"
    needs_guides = False

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("type", "seed")))
        return groom.puff(scalp=scalp, center=tuple(s.center), radius=s.radius, sphere_center=tuple(s.sphere_center),
                          sphere_radius=s.sphere_radius, hairs=s.puff_hairs, **kw)


CLASSES = [GroomSettings, GROOM_OT_braid, GROOM_OT_partition, GROOM_OT_curl, GROOM_OT_generate, GROOM_OT_puff]
