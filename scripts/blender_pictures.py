"""Pictures of the add-on for the README, made in a real Blender window (run under xvfb-run by
scripts/blender-pictures.sh): the Groom panel beside a cornrow groom braided by bpy.ops.groom.braid
on the demo's head, and a Cycles render of that groom.

Environment: GROOM_DEMO (the demo's output folder), GROOM_OUT (where the PNGs go),
GROOM_BLENDER_ADDON_DIR (blender/ of the repository)."""
import math
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.environ["GROOM_BLENDER_ADDON_DIR"])
import groom  # noqa: E402
import groom_blender  # noqa: E402
from groom_blender import convert  # noqa: E402

demo, out = os.environ["GROOM_DEMO"], os.environ["GROOM_OUT"]
groom_blender.register()


def read_obj(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("f "):
                faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
    return verts, faces


def build_scene():
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob)
    verts, faces = read_obj(os.path.join(demo, "head.obj"))
    mesh = bpy.data.meshes.new("head")
    mesh.from_pydata(verts, [], faces)
    head = bpy.data.objects.new("head", mesh)
    bpy.context.scene.collection.objects.link(head)
    for p in mesh.polygons:
        p.use_smooth = True
    guides = convert.curves_object(groom.read(os.path.join(demo, "alisha_guides.usda")), "guides", bpy.context.scene.collection)
    # The demo is Y-up, Blender Z-up: turn both objects; the add-on works in world space.
    for ob in (head, guides):
        ob.rotation_euler = (math.pi / 2, 0, 0)
    bpy.context.view_layer.update()
    s = bpy.context.scene.groom
    s.scalp = head
    s.orient = "scalp"
    s.knot_length = 2.2
    s.fibers = 16
    s.rest = True
    for ob in bpy.context.view_layer.objects:
        ob.select_set(ob == guides)
    bpy.context.view_layer.objects.active = guides
    assert bpy.ops.groom.braid() == {'FINISHED'}
    braids = bpy.context.view_layer.objects.active
    guides.hide_set(True)
    guides.hide_render = True
    # Materials: a dark hair, a warm skin.
    hair = bpy.data.materials.new("hair")
    hair.use_nodes = True
    bsdf = hair.node_tree.nodes.get("Principled BSDF")
    bsdf.inputs["Base Color"].default_value = (0.03, 0.018, 0.012, 1)
    bsdf.inputs["Roughness"].default_value = 0.45
    braids.data.materials.append(hair)
    skin = bpy.data.materials.new("skin")
    skin.use_nodes = True
    skin.node_tree.nodes.get("Principled BSDF").inputs["Base Color"].default_value = (0.36, 0.22, 0.15, 1)
    head.data.materials.append(skin)
    return head, braids


def add_camera_and_light():
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    bpy.context.scene.collection.objects.link(cam)
    cam.location = (-38, -52, 28)
    direction = -cam.location.normalized() if hasattr(cam.location, "normalized") else None
    track = cam.constraints.new('TRACK_TO')
    target = bpy.data.objects.new("target", None)
    bpy.context.scene.collection.objects.link(target)
    target.location = (0, 0, 3)
    track.target = target
    bpy.context.scene.camera = cam
    cam.data.lens = 70
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", 'SUN'))
    sun.data.energy = 4
    sun.rotation_euler = (0.7, 0.2, -0.6)
    bpy.context.scene.collection.objects.link(sun)
    world = bpy.context.scene.world or bpy.data.worlds.new("world")
    bpy.context.scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.35, 0.36, 0.4, 1)


def render():
    scene = bpy.context.scene
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 24
    scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
    scene.render.resolution_x, scene.render.resolution_y = 640, 640
    scene.render.filepath = os.path.join(out, "blender_render.png")
    bpy.ops.render.render(write_still=True)


def screenshot():
    """In the window (opened on the .blend the background run saved, so no splash): the sidebar
    open, the view framed on the braids, then a screenshot of the whole window after the shell
    script has clicked the sidebar's Groom tab (Blender 3.4 cannot switch tabs from Python), then
    quit, also on any error, so the script never hangs."""
    def frame():
        try:
            window = bpy.context.window_manager.windows[0]
            for area in window.screen.areas:
                if area.type != 'VIEW_3D':
                    continue
                space = area.spaces[0]
                space.show_region_ui = True
                space.shading.type = 'SOLID'
                space.overlay.show_floor = False
                main = next(r for r in area.regions if r.type == 'WINDOW')
                with bpy.context.temp_override(window=window, area=area, region=main):
                    bpy.ops.view3d.view_axis(type='FRONT')
                    bpy.ops.view3d.view_orbit(angle=0.7, type='ORBITLEFT')
                    bpy.ops.view3d.view_selected()
            for ob in bpy.context.view_layer.objects:
                ob.select_set(False)  # the braids in their own colour, not the selection outline
        except Exception:
            import traceback
            traceback.print_exc()
            bpy.ops.wm.quit_blender()
        return None

    def shoot():
        bpy.ops.screen.screenshot(filepath=os.path.join(out, "blender_panel.png"))
        bpy.ops.wm.quit_blender()
        return None
    bpy.app.timers.register(frame, first_interval=2.0)
    bpy.app.timers.register(shoot, first_interval=float(os.environ.get("GROOM_SHOT_DELAY", "10")))


if bpy.app.background:
    head, braids = build_scene()
    add_camera_and_light()
    for ob in bpy.context.view_layer.objects:
        ob.select_set(ob == braids)
    bpy.context.view_layer.objects.active = braids
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(os.environ["GROOM_TMP"], "groom_pictures.blend"))
    render()
else:
    screenshot()
