"""The Groom tab of the 3D view's sidebar: the scalp, each op's settings and its button."""

import bpy

from .operators import CM_LENGTHS


def _prop(layout, s, name):
    """A setting; under one of groom's centimetre lengths left untouched in a scene not in
    centimetres, what it runs as (the field shows the centimetres)."""
    layout.prop(s, name)
    if name in CM_LENGTHS and not s.is_property_set(name) and s.units_per_cm != 1.0:
        cm = getattr(s, name)
        layout.label(text=f"untouched: {cm:g} cm = {cm * s.units_per_cm:g} scene units")


class GROOM_PT_panel(bpy.types.Panel):
    bl_label = "Groom"
    bl_idname = "GROOM_PT_panel"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Groom"

    def draw(self, context):
        s = context.scene.groom
        col = self.layout.column()
        col.prop(s, "scalp")
        col.prop(s, "scalp_extras")
        col.prop(s, "scalp_fill_holes")
        col.prop(s, "scalp_voxel")
        col.prop(s, "units_per_cm")
        col.prop(s, "seed")
        col.prop(s, "threads")

        box = self.layout.box()
        box.label(text="Braid (selected guides)")
        for name in ("pattern", "strands", "knot_length", "orient", "fibers", "rest"):
            box.prop(s, name)
        box.operator("groom.braid")

        box = self.layout.box()
        box.label(text="Edge hairs (selected guides)")
        # Only the chosen mode's field: a count shown while the density ran had read as the count.
        box.prop(s, "partition_by")
        if s.partition_by != 'density':
            box.prop(s, s.partition_by)
        for name in ("samples", "width"):
            box.prop(s, name)
        box.operator("groom.partition")

        box = self.layout.box()
        box.label(text="Curl (selected curves)")
        box.prop(s, "type")
        box.prop(s, "uniformity")
        box.operator("groom.curl")

        box = self.layout.box()
        box.label(text="Generate (selected guides)")
        box.prop(s, "hairs")
        box.prop(s, "neighbours")
        box.operator("groom.generate")

        box = self.layout.box()
        box.label(text="Puff (its hair type also Gather's)")
        box.prop(s, "puff_place")
        if s.puff_place == 'custom':
            for name in ("center", "radius", "sphere_center", "sphere_radius"):
                box.prop(s, name)
        for name in ("puff_hairs", "puff_type", "puff_uniformity"):
            box.prop(s, name)
        box.operator("groom.puff")

        box = self.layout.box()
        box.label(text="Whole scalp")
        for name in ("up", "forward", "hairline", "parting", "parting_gap"):
            _prop(box, s, name)
        box.operator("groom.hairline")
        for name in ("cornrow_count", "cornrow_spread"):
            box.prop(s, name)
        box.operator("groom.cornrows")
        for name in ("edge_count", "edge_length", "edge_radius"):
            _prop(box, s, name)
        box.operator("groom.edges")
        for name in ("layout", "cols", "section_length"):
            _prop(box, s, name)
        box.operator("groom.sections")
        for name in ("gather_hairs", "lift"):
            _prop(box, s, name)
        box.operator("groom.gather", text="Groom Gather (selected puffs)")


class GROOM_MT_menu(bpy.types.Menu):
    """Object > Groom: every operator, with the settings of the Groom panel."""
    bl_label = "Groom"
    bl_idname = "GROOM_MT_menu"

    def draw(self, context):
        for op in ("braid", "partition", "curl", "generate", "puff", "hairline", "cornrows", "edges", "sections", "gather"):
            self.layout.operator("groom." + op)


def draw_object_menu(self, context):
    self.layout.separator()
    self.layout.menu(GROOM_MT_menu.bl_idname)


CLASSES = [GROOM_PT_panel, GROOM_MT_menu]
