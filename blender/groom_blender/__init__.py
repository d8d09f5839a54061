"""groom inside Blender: braid, partition, curl, puff, generate, hairline, edges, sections and gather
as operators (bpy.ops.groom.*) on the selected curves and a scalp mesh, each result a new hair
Curves object.

The add-on is a thin layer over the `groom` Python module (build/python, or installed with
`cmake --install`): Debian's Blender 3.4 runs on the system Python 3.11, the interpreter the module
is built for, so the same library and the same defaults run here as on the command line.
"""

bl_info = {
    "name": "groom",
    "author": "groom developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Groom, and Object > Groom",
    "description": "Braids, cornrows, edge hairs, curls and afro puffs from guide curves on a scalp mesh",
    "category": "Object",
}

import bpy

from . import convert, operators, panel

_classes = operators.CLASSES + panel.CLASSES


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.groom = bpy.props.PointerProperty(type=operators.GroomSettings)
    bpy.types.VIEW3D_MT_object.append(panel.draw_object_menu)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(panel.draw_object_menu)
    del bpy.types.Scene.groom
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
