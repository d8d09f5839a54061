"""The Groom tab of the 3D view's sidebar: the scalp, each op's settings and its button."""

import bpy


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
        col.prop(s, "scalp_voxel")
        col.prop(s, "seed")
        col.prop(s, "threads")

        box = self.layout.box()
        box.label(text="Braid (selected guides)")
        for name in ("pattern", "strands", "knot_length", "orient", "fibers", "rest"):
            box.prop(s, name)
        box.operator("groom.braid")

        box = self.layout.box()
        box.label(text="Edge hairs (selected guides)")
        for name in ("count", "samples", "width"):
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
        box.label(text="Puff")
        for name in ("center", "radius", "sphere_center", "sphere_radius", "puff_hairs"):
            box.prop(s, name)
        box.operator("groom.puff")


CLASSES = [GROOM_PT_panel]
