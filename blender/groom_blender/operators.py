"""The operators (bpy.ops.groom.braid, .partition, .curl, .puff, .generate, .hairline, .cornrows, .edges,
.sections, .gather) and their settings.

Each setting is named like the command-line option it feeds (knot_length -> --knot-length) and only
settings the artist changed are passed on, so an untouched panel runs with groom's own defaults; the
defaults shown here are the CLI's (`groom COMMAND --help`). Two settings are always passed: the head's up
and forward directions, because Blender is Z-up with the face toward -Y where groom's own defaults
(+Y up, face +Z) are those of the DCCs that export Y-up.

Where the panel offers a choice the CLI makes by which options are given (Partition's density, count
or spacing; the Puff's place), it is a mode setting, and the fields of the other modes are hidden:
the panel shows what will run. Setting a mode's field from Python picks that mode."""

import warnings

import numpy as np

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


LAYOUTS = [
    ("grid", "Grid", "Box braids, twists, bantu knots"),
    ("rows", "Rows", "Fulani: front to back, a centre row"),
    ("radial", "Radial", "Wedges around the crown"),
]


PARTITION_BY = [
    ("density", "Density", "groom's default: a segment every 1/200 of the typical gap between guides, on each side of "
                           "every guide (many: Sintel's 228 guides made 1.5 M hairs)"),
    ("count", "Count", "Segments per side: this many on each side of every guide"),
    ("spacing", "Spacing", "Arc length between segments along the guide, scene units"),
]
PUFF_PLACES = [
    ("top", "Top of the head", "The region centred where Up leaves the scalp, sized from the head's width near its top: "
                               "region radius 0.15 of it, the puff's sphere radius 0.25 of it, its centre 0.4 of it above"),
    ("custom", "Custom", "The region and sphere given below, scene units"),
]


def _picks(mode, value):
    """An update callback: setting this field picks the mode it belongs to, so a script that sets
    `count` (as before the mode existed) gets that count, not the density."""
    def update(self, context):
        if getattr(self, mode) != value:
            setattr(self, mode, value)
    return update


def _mesh_poll(self, ob):
    return ob.type == 'MESH'


def _curves_poll(self, ob):
    return ob.type in {'CURVES', 'CURVE'}


# The lengths whose defaults are groom's centimetres (the panel says what an untouched one runs as).
_CM = "; untouched, groom's default in centimetres x Units per cm; a value typed is scene units"
CM_LENGTHS = ("parting_gap", "edge_length", "edge_radius", "section_length", "lift")


class GroomSettings(bpy.types.PropertyGroup):
    scalp: PointerProperty(name="Scalp", type=bpy.types.Object, poll=_mesh_poll, description="Mesh the hair grows on")
    scalp_extras: PointerProperty(name="Joined", type=bpy.types.Collection,
                                  description="Meshes joined to the scalp (eyeballs in open eye sockets, teeth): hair keeps "
                                              "outside the solid they make together, and roots may grow on them too")
    scalp_fill_holes: FloatProperty(name="Fill holes", default=0.0, min=0.0,
                                    description="Close the scalp's open rims up to this length (eye sockets, a mouth; not "
                                                "the neck), so hair lies over them: 0 = none")
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
    # partition: how many segments is one choice (the CLI's --count, --spacing or neither), shown as one
    partition_by: EnumProperty(name="Segments", items=PARTITION_BY, default="density",
                               description="How many edge hairs: groom's density, a count per side, or a spacing")
    count: IntProperty(name="Segments per side", default=24, min=1, update=_picks("partition_by", "count"),
                       description="Segments on each side of every guide (Segments: Count)")
    spacing: FloatProperty(name="Spacing", default=0.1, min=1e-6, update=_picks("partition_by", "spacing"),
                           description="Arc length between segments along the guide, scene units (Segments: Spacing)")
    samples: IntProperty(name="Points per segment", default=8, min=2)
    width: FloatProperty(name="Hair width", default=0.0, min=0.0,
                         description="One hair diameter root to tip, scene units; 0 = groom's: 0.008 cm at the root "
                                     "tapering to 0.004 cm at the tip, x Units per cm")
    # curl
    type: EnumProperty(name="Hair type", items=HAIR_TYPES, default="3a", description="Curl's hair type")
    uniformity: FloatProperty(name="Uniformity", default=0.7, min=0.0, max=1.0,
                              description="Curl: probability a cycle takes the type's dominant shape")
    # generate
    hairs: IntProperty(name="Hairs", default=1000, min=1)
    neighbours: IntProperty(name="Neighbours", default=4, min=1)
    # puff: where is one choice (the top of the head, or the values given), shown as one
    puff_place: EnumProperty(name="Place", items=PUFF_PLACES, default="top", description="Where the puff grows")
    center: FloatVectorProperty(name="Region centre", default=(0.0, 0.0, 1.0), subtype='XYZ', update=_picks("puff_place", "custom"),
                                description="The region's centre, projected onto the scalp (Place: Custom)")
    radius: FloatProperty(name="Region radius", default=0.3, min=0.0, update=_picks("puff_place", "custom"),
                          description="Region radius around the projected centre, scene units (Place: Custom)")
    sphere_center: FloatVectorProperty(name="Puff centre", default=(0.0, 0.0, 1.6), subtype='XYZ', update=_picks("puff_place", "custom"),
                                       description="Centre of the puff's sphere (Place: Custom)")
    sphere_radius: FloatProperty(name="Puff radius", default=0.5, min=0.0, update=_picks("puff_place", "custom"),
                                 description="Radius of the puff's sphere, scene units (Place: Custom)")
    puff_hairs: IntProperty(name="Puff hairs", default=0, min=0, description="Curled hairs grown in the region (0 = the guides only)")
    puff_type: EnumProperty(name="Puff hair type", items=HAIR_TYPES, default="3a",
                            description="The curls of the Puff's hairs and of the hair Gather pulls into the puffs")
    puff_uniformity: FloatProperty(name="Puff uniformity", default=0.7, min=0.0, max=1.0,
                                   description="Puff and Gather: probability a cycle takes the type's dominant shape")
    # the head, for hairline, edges, sections and gather
    up: FloatVectorProperty(name="Up", default=(0.0, 0.0, 1.0), subtype='XYZ', description="The head's up direction")
    forward: FloatVectorProperty(name="Forward", default=(0.0, -1.0, 0.0), subtype='XYZ', description="The direction the face looks")
    hairline: PointerProperty(name="Hairline", type=bpy.types.Object, poll=_curves_poll,
                              description="One closed curve around the head (Groom Hairline makes one); none = groom's default")
    parting: PointerProperty(name="Parting", type=bpy.types.Object, poll=_curves_poll,
                             description="Parting curves on the scalp: bare lines no hair crosses")
    parting_gap: FloatProperty(name="Parting gap", default=0.3, min=0.0, description="Bare width along each parting" + _CM)
    # cornrows
    cornrow_count: IntProperty(name="Rows", default=8, min=1, max=256, description="Cornrow rows, hairline to nape")
    cornrow_spread: FloatProperty(name="Spread", default=24.0, min=0.0, max=89.0,
                                  description="How far the outermost rows lean from vertical, degrees (smaller keeps them off the ears)")
    # edges
    edge_count: IntProperty(name="Edge hairs", default=0, min=0, description="Exact number of baby hairs (0 = from the density)")
    edge_length: FloatProperty(name="Edge length", default=2.4, min=0.0, description="Arc length of one baby hair" + _CM)
    edge_radius: FloatProperty(name="Swirl radius", default=0.15, min=0.0,
                               description="Tightest radius of curvature of a baby hair" + _CM)
    units_per_cm: FloatProperty(name="Units per cm", default=1.0, min=0.0,
                                description="Scene units per centimetre, for groom's centimetre defaults: the widths, curl radii "
                                            "and default lengths of Partition, Curl, Generate, Puff, Edges, Sections and Gather; "
                                            "values typed are scene units (0.01 for a scene in metres, Blender's default)")
    # sections
    layout: EnumProperty(name="Layout", items=LAYOUTS, default="grid")
    cols: IntProperty(name="Columns", default=8, min=1, max=256, description="grid: bands across the head; rows: rows")
    section_length: FloatProperty(name="Guide length", default=30.0, min=0.0, description="Length of each section guide's free part" + _CM)
    # gather
    gather_hairs: IntProperty(name="Gathered hairs", default=20000, min=1, description="Hairs over the scalp outside the puffs' bases")
    lift: FloatProperty(name="Lift", default=0.08, min=0.0, description="Greatest height of the gathered hair above the scalp" + _CM)


def _given(settings, names, rename=None):
    """The settings among `names` the artist set (so groom's defaults apply to the rest), keyed by
    groom's keyword (`rename` maps a setting to it where two ops share a keyword)."""
    out = {}
    for name in names:
        if settings.is_property_set(name):
            value = getattr(settings, name)
            key = (rename or {}).get(name, name)
            out[key] = tuple(value) if hasattr(value, "__len__") and not isinstance(value, str) else value
    return out


def _head(settings, forward=True):
    """up= (and forward=), always: Blender's axes are not groom's defaults."""
    kw = {"up": tuple(settings.up)}
    if forward:
        kw["forward"] = tuple(settings.forward)
    return kw


def _region(settings):
    """hairline= and parting= from the chosen curve objects, and the parting gap if set."""
    kw = _given(settings, ("parting_gap",))
    for name in ("hairline", "parting"):
        ob = getattr(settings, name)
        if ob is not None:
            kw[name] = convert.curveset_from_object(ob)
    return kw


def _selected_guides(op, context, scalp):
    """The selected hair Curves and curve objects (not the scalp). Raises ValueError naming what is
    selected when none is: "no curves in the selection (nothing)" had not said a mesh was selected
    and curves were needed."""
    chosen = [ob for ob in context.selected_objects if ob.type in {'CURVES', 'CURVE'} and ob != scalp]
    if not chosen:
        found = ", ".join(f"{ob.name} ({'the scalp' if ob == scalp else ob.type.lower()})" for ob in context.selected_objects)
        raise ValueError(f"{op.bl_label.split()[-1].lower()}: expected guide curves selected (hair Curves or curve objects); "
                         f"selected: {found or 'nothing'}")
    return chosen


def _puff_place(settings, context):
    """center, radius, sphere_center, sphere_radius for the Puff: the panel's with Place = Custom;
    with Top of the head, from the scalp mesh: the region centred where Up leaves it (groom projects
    the centre onto the scalp), sized from the head's width across Up over the top 15% of its
    height (a head there, not the shoulders of a bust or body), the sphere above it. Fixed
    defaults had put a Z-up head's puff at (0, 1, 0), the back of a unit head and nowhere on a real one."""
    if settings.puff_place == 'custom':
        return tuple(settings.center), settings.radius, tuple(settings.sphere_center), settings.sphere_radius
    up = np.array(settings.up, np.float64)
    if not np.linalg.norm(up) > 0:
        raise ValueError(f"puff: Up must be a direction to find the top of the head; found {tuple(settings.up)}")
    up /= np.linalg.norm(up)
    verts, _ = convert._world_triangles(settings.scalp, context.evaluated_depsgraph_get())
    height = verts @ up
    top, depth = float(height.max()), 0.15 * float(height.max() - height.min())
    across = verts[height >= top - depth] - np.outer(height[height >= top - depth], up)
    middle = across.mean(axis=0)
    width = 2.0 * float(np.linalg.norm(across - middle, axis=1).max())
    center = middle + top * up
    return tuple(center), 0.15 * width, tuple(center + 0.4 * width * up), 0.25 * width


def _in_blender_words(message):
    """groom's warning as the artist sets it here: the Units per cm setting, not the keyword."""
    return message.replace("pass units_per_cm", "set Units per cm (Groom panel)").replace("units_per_cm", "Units per cm")


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
                guides = convert.guides_from_objects(_selected_guides(self, context, settings.scalp))
            scalp = None
            if settings.scalp is not None:
                extras = settings.scalp_extras.all_objects if settings.scalp_extras else ()
                scalp = convert.scalp_from_object(settings.scalp, settings.scalp_voxel, extras, settings.scalp_fill_holes)
            elif self.needs_scalp:
                raise ValueError("scalp: choose a scalp mesh in the Groom panel")
            kw = _given(settings, ("threads",))
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", groom.GroomWarning)
                result = self.run(settings, guides, scalp, kw)
        except (groom.Error, ValueError) as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        if result.num_curves == 0:  # an empty object reported as FINISHED told the artist nothing
            self.report({'ERROR'}, f"groom: {self.bl_label} made no curves (guides with fewer than 2 points or no length "
                                   "are skipped; see the warnings above)")
            return {'CANCELLED'}
        # groom's warnings (a scene in metres with centimetre defaults: hairs 2 cm wide, curls that
        # do not show) in the status bar and the Info editor, where an artist looks.
        for w in caught:
            if issubclass(w.category, groom.GroomWarning):
                self.report({'WARNING'}, _in_blender_words(str(w.message)))
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
        if kw.get("knot_length") == 0:  # the panel's "0 = groom's default frequency", typed back: groom refuses 0
            del kw["knot_length"]
        return groom.braid(guides, scalp=scalp, **kw)


class GROOM_OT_partition(_GroomOperator, bpy.types.Operator):
    """Edge hairs between the selected (braided) guides"""
    bl_idname = "groom.partition"
    bl_label = "Groom Partition"

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("samples", "units_per_cm", "seed")))
        if s.partition_by != 'density':
            kw[s.partition_by] = getattr(s, s.partition_by)
        if s.width > 0:  # 0: groom's tapered default widths
            kw["width"] = s.width
        return groom.partition(guides, scalp=scalp, **kw)


class GROOM_OT_curl(_GroomOperator, bpy.types.Operator):
    """Curl the selected curves (scalp optional: keeps curls outside it)"""
    bl_idname = "groom.curl"
    bl_label = "Groom Curl"
    needs_scalp = False

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("type", "uniformity", "units_per_cm", "seed")))
        return groom.curl(guides, scalp=scalp, **kw)


class GROOM_OT_generate(_GroomOperator, bpy.types.Operator):
    """Grow hairs over the scalp from the selected guides"""
    bl_idname = "groom.generate"
    bl_label = "Groom Generate"

    def run(self, s, guides, scalp, kw):
        kw.update(_given(s, ("neighbours", "units_per_cm", "seed")))
        return groom.generate(guides, scalp=scalp, count=s.hairs, **kw)


class GROOM_OT_puff(_GroomOperator, bpy.types.Operator):
    """An afro puff: guides from a region of the scalp into a sphere, curled hairs optional"""
    bl_idname = "groom.puff"
    bl_label = "Groom Puff"
    needs_guides = False

    def run(self, s, guides, scalp, kw):
        # Its own hair type and uniformity: it had taken Curl's type and no uniformity at all.
        kw.update(_given(s, ("puff_type", "puff_uniformity", "units_per_cm", "seed"),
                         {"puff_type": "type", "puff_uniformity": "uniformity"}))
        center, radius, sphere_center, sphere_radius = _puff_place(s, bpy.context)
        if s.puff_place != 'custom':
            self.report({'INFO'}, "groom: puff on the top of the head: region centre ({:.4g}, {:.4g}, {:.4g}) radius {:.4g}, "
                                  "sphere centre ({:.4g}, {:.4g}, {:.4g}) radius {:.4g} (Place: Custom to change them)"
                        .format(*center, radius, *sphere_center, sphere_radius))
        return groom.puff(scalp=scalp, center=center, radius=radius, sphere_center=sphere_center,
                          sphere_radius=sphere_radius, hairs=s.puff_hairs, **kw)


class GROOM_OT_hairline(_GroomOperator, bpy.types.Operator):
    """A default hairline around the scalp (forehead, temples, sideburns, ears, nape)"""
    bl_idname = "groom.hairline"
    bl_label = "Groom Hairline"
    needs_guides = False

    def run(self, s, guides, scalp, kw):
        kw.update(_head(s))
        return groom.hairline(scalp=scalp, **kw)


class GROOM_OT_cornrows(_GroomOperator, bpy.types.Operator):
    """Cornrow guide rows over the scalp from the hairline to the nape (braid them with Orient = Scalp)"""
    bl_idname = "groom.cornrows"
    bl_label = "Groom Cornrows"
    needs_guides = False

    def run(self, s, guides, scalp, kw):
        kw.update(_head(s))
        # No Hairline object: the head's default one, as Gather does; the rows run between its ends
        # and the cranium is fitted inside it, so no sphere need be measured in the scene.
        hairline = _region(s).get("hairline")
        if hairline is None:
            hairline = groom.hairline(scalp=scalp, **_head(s))
        kw.update(_given(s, ("cornrow_count", "cornrow_spread"), {"cornrow_count": "count", "cornrow_spread": "spread"}))
        return groom.cornrow_guides(scalp=scalp, hairline=hairline, fit_cranium=True, **kw)


class GROOM_OT_edges(_GroomOperator, bpy.types.Operator):
    """Edges (baby hairs) laid flat in swirls along the hairline"""
    bl_idname = "groom.edges"
    bl_label = "Groom Edges"
    needs_guides = False

    def run(self, s, guides, scalp, kw):
        kw.update(_head(s))
        kw.update(_region(s))
        kw.update(_given(s, ("edge_count", "edge_length", "edge_radius", "units_per_cm", "seed"),
                         {"edge_count": "count", "edge_length": "length", "edge_radius": "radius"}))
        return groom.edges(scalp=scalp, **kw)


class GROOM_OT_sections(_GroomOperator, bpy.types.Operator):
    """Part the scalp into sections, one guide each (feed them to Braid or Curl)"""
    bl_idname = "groom.sections"
    bl_label = "Groom Sections"
    needs_guides = False

    def run(self, s, guides, scalp, kw):
        kw.update(_head(s))
        kw.update(_region(s))
        kw.pop("parting", None)  # sections make their own partings
        kw.update(_given(s, ("layout", "cols", "section_length", "units_per_cm", "seed"), {"section_length": "length"}))
        return groom.sections(scalp=scalp, **kw)


class GROOM_OT_gather(_GroomOperator, bpy.types.Operator):
    """Gather the rest of the scalp's hair into the selected puffs (made by Groom Puff)"""
    bl_idname = "groom.gather"
    bl_label = "Groom Gather"
    needs_guides = False

    def run(self, s, guides, scalp, kw):
        chosen = [ob for ob in bpy.context.selected_objects if ob.type == 'CURVES' and "groom_puff_base" in ob]
        if not chosen:
            raise ValueError("gather: select the puffs (hair objects made by Groom Puff) to gather the hair into")
        kw.update(_head(s))  # forward too: with no Hairline object, gather makes the head's default one
        kw.update(_region(s))
        # The Puff's hair type: the hair gathered into a puff curls as the puff's own.
        kw.update(_given(s, ("gather_hairs", "lift", "puff_type", "puff_uniformity", "units_per_cm", "seed"),
                         {"gather_hairs": "hairs", "puff_type": "type", "puff_uniformity": "uniformity"}))
        return groom.gather([convert.curveset_from_object(ob) for ob in chosen], scalp=scalp, **kw)


CLASSES = [GroomSettings, GROOM_OT_braid, GROOM_OT_partition, GROOM_OT_curl, GROOM_OT_generate, GROOM_OT_puff,
           GROOM_OT_hairline, GROOM_OT_cornrows, GROOM_OT_edges, GROOM_OT_sections, GROOM_OT_gather]
