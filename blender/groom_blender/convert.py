"""Blender objects <-> groom arrays: guides from curve objects, the scalp from a mesh object, and
groom's curves back as a hair Curves object. World space throughout: groom works on positions as the
artist sees them, so an object's transform is applied on the way in and the result is made in world
space."""

import bpy
import numpy as np

try:
    import groom
except ModuleNotFoundError as e:  # a bare "No module named 'groom'" told the artist nothing
    raise ModuleNotFoundError("the groom add-on needs the groom Python module on Blender's path: start Blender with "
                              "PYTHONPATH=<groom>/build/python, or run `cmake --install build` (README, Blender)") from e


def _world(points, matrix):
    """(n, 3) points through a 4x4 object matrix."""
    m = np.array(matrix, dtype=np.float64)
    return (points @ m[:3, :3].T + m[:3, 3]).astype(np.float32)


def _evaluated_splines(ob):
    """A legacy curve object's splines as Blender draws them, in object space: a list of (points
    (n, 3), cyclic). Bezier and NURBS splines are evaluated at their resolution (a 3-point Bezier
    arc is 25 points along the arc, not its 3 control points off it; Blender's default Bezier is a
    curve, not a 2-point line); POLY splines are their points as they are. The object's modifiers
    are not applied."""
    data = ob.data.copy()
    # Blender's own evaluation, on a copy without what would make a surface of the centre line
    # (a bevel, an extrusion, a 2D curve's fill): then the mesh is each spline's points in order,
    # joined by edges, a cyclic spline's last point joined back to its first.
    data.bevel_mode = 'ROUND'
    data.bevel_depth = 0.0
    data.bevel_object = None
    data.extrude = 0.0
    if data.dimensions == '2D':
        data.fill_mode = 'NONE'
    temp = bpy.data.objects.new("groom_evaluate", data)
    try:
        mesh = temp.to_mesh()
        verts = np.empty(len(mesh.vertices) * 3, np.float32)
        mesh.vertices.foreach_get('co', verts)
        edges = np.empty(len(mesh.edges) * 2, np.int32)
        mesh.edges.foreach_get('vertices', edges)
    finally:
        temp.to_mesh_clear()
        bpy.data.objects.remove(temp)
        bpy.data.curves.remove(data)
    verts, edges = verts.reshape(-1, 3), np.sort(edges.reshape(-1, 2), axis=1)
    n = len(verts)
    if n == 0:
        return []
    # A spline ends where no edge joins a point to the next; an edge between the first and last
    # points of one run closes it.
    step = edges[:, 1] - edges[:, 0] == 1
    joined = np.zeros(n, bool)
    joined[edges[step, 0]] = True
    starts = np.r_[0, np.flatnonzero(~joined[:-1]) + 1]
    ends = np.r_[starts[1:], n]
    closing = {(int(a), int(b)) for a, b in edges[~step]}
    return [(verts[a:b], (int(a), int(b) - 1) in closing) for a, b in zip(starts, ends)]


def _closing_points(counts, cyclic):
    """For np.insert(array, at, array[first], axis=0): each cyclic curve of 3 or more points gets its
    first point repeated at its end, as groom's readers give a closed curve (detail `closed`)."""
    counts = np.asarray(counts, np.int64)
    ends = np.cumsum(counts)
    loop = np.asarray(cyclic, bool) & (counts >= 3)
    return ends[loop], (ends - counts)[loop], loop


def _curves_cyclic(data):
    """Per curve of a hair Curves datablock: whether it is cyclic (its `cyclic` attribute)."""
    attribute = data.attributes.get('cyclic')
    cyclic = np.zeros(len(data.curves), bool)
    if attribute is not None and attribute.domain == 'CURVE' and attribute.data_type == 'BOOLEAN':
        attribute.data.foreach_get('value', cyclic)
    return cyclic


def guides_from_objects(objects):
    """A groom.CurveSet from hair Curves objects and legacy curve objects, root first, in world
    space. Legacy curves are read as Blender evaluates them (_evaluated_splines). A cyclic curve
    comes with its first point repeated at its end, and where every curve is one the set is marked
    closed (detail `closed` = 1), as groom reads a closed curve from a file: a Bezier circle drawn
    as the hairline is the whole loop. Raises ValueError naming the objects when they hold no curves."""
    chunks, counts, loops = [], [], []
    for ob in objects:
        if ob.type == 'CURVES':
            data = ob.data
            n = len(data.points)
            pos = np.empty(n * 3, np.float32)
            data.attributes['position'].data.foreach_get('vector', pos)
            offsets = np.empty(len(data.curves) + 1, np.int32)
            data.curve_offset_data.foreach_get('value', offsets)
            curve_counts = np.diff(offsets)
            at, first, loop = _closing_points(curve_counts, _curves_cyclic(data))
            pos = np.insert(pos.reshape(-1, 3), at, pos.reshape(-1, 3)[first], axis=0)
            chunks.append(_world(pos, ob.matrix_world))
            counts.extend((curve_counts + loop).tolist())
            loops.extend(loop.tolist())
        elif ob.type == 'CURVE':
            for co, cyclic in _evaluated_splines(ob):
                loop = cyclic and len(co) >= 3
                if loop:
                    co = np.vstack([co, co[:1]])
                chunks.append(_world(co, ob.matrix_world))
                counts.append(len(co))
                loops.append(loop)
    if not counts:
        names = ", ".join(f"{ob.name} ({ob.type})" for ob in objects) or "nothing"
        raise ValueError(f"guides: expected curves to read; {names} hold none (a curve object with no splines, "
                         "or a hair object with no curves)")
    curves = groom.CurveSet(np.concatenate(chunks), np.array(counts, np.int64))
    if all(loops):
        curves.detail_attributes["closed"] = np.array([1], np.int32)
    return curves


_BLENDER_NAMES = {"position", "radius", "curve_type", "resolution", "cyclic", "tilt", "handle_left", "handle_right"}
_DETAIL = "groom_"  # prefix of the object properties that hold groom's detail attributes
# Set on a hair object whose curves had no width: its radius only draws them thin (curves_object),
# so it is not written back as a width. Not groom_*: that would read back as a detail attribute.
_NO_WIDTH = "_groom_no_width"


def _width_from_radius(ob):
    """A hair Curves object's point `radius` as groom's `width`, in world space: curves_object sets
    radius = width / 2 on an object at the origin, unscaled, so width = 2 radius there; an object
    scaled since draws its hair scaled, by the cube root of its axes' scales (as Cycles scales a
    curve's radius), and its points are written in world space, so its widths are scaled alike.
    None where the object has no radius, or only the thin one drawn for curves without a width."""
    radius = ob.data.attributes.get('radius')
    if radius is None or radius.domain != 'POINT' or radius.data_type != 'FLOAT' or ob.get(_NO_WIDTH):
        return None
    width = np.empty(len(ob.data.points), np.float32)
    radius.data.foreach_get('value', width)
    width *= 2
    axes = np.linalg.norm(np.array(ob.matrix_world, np.float64)[:3, :3], axis=0)
    scale = float(np.cbrt(np.prod(axes)))
    if scale != 1.0:
        width *= np.float32(scale)
    return width


def curveset_from_object(ob):
    """A groom.CurveSet from one object, with what curves_object kept of groom's attributes: the
    point width (from the radius, _width_from_radius), 32-bit integer, float and vector curve
    attributes (Blender attributes on the CURVE domain) and the detail attributes (object
    properties named groom_NAME), so a puff made here can be gathered and a file written from a
    hair object renders at its widths. A legacy curve object's radius is a bevel's scale, not a
    width, and is not read."""
    curves = guides_from_objects([ob])
    if ob.type != 'CURVES':
        return curves
    width = _width_from_radius(ob)
    if width is not None:
        offsets = np.empty(len(ob.data.curves) + 1, np.int32)
        ob.data.curve_offset_data.foreach_get('value', offsets)
        at, first, _ = _closing_points(np.diff(offsets), _curves_cyclic(ob.data))
        curves.point_attributes["width"] = np.insert(width, at, width[first])
    for attribute in ob.data.attributes:
        if attribute.domain != 'CURVE' or attribute.name in _BLENDER_NAMES or attribute.name.startswith("."):
            continue
        n = len(ob.data.curves)
        if attribute.data_type == 'INT':
            values = np.empty(n, np.int32)
            attribute.data.foreach_get('value', values)
        elif attribute.data_type == 'FLOAT':
            values = np.empty(n, np.float32)
            attribute.data.foreach_get('value', values)
        elif attribute.data_type == 'FLOAT_VECTOR':
            values = np.empty(n * 3, np.float32)
            attribute.data.foreach_get('vector', values)
            values = values.reshape(-1, 3)
        else:
            continue
        curves.curve_attributes[attribute.name] = values
    for key in ob.keys():
        if key.startswith(_DETAIL):
            value = ob[key]
            name = key[len(_DETAIL):]
            if isinstance(value, str):
                curves.detail_attributes[name] = value
            elif isinstance(value, (int, float)):
                curves.detail_attributes[name] = np.array([value], np.float32 if isinstance(value, float) else np.int32)
            else:
                curves.detail_attributes[name] = np.array(list(value), np.float32).reshape(1, -1)
    return curves


def _world_triangles(ob, depsgraph):
    """A mesh object's evaluated triangles: (n, 3) world positions and (m, 3) vertex indices."""
    mesh = ob.evaluated_get(depsgraph).to_mesh()
    try:
        mesh.calc_loop_triangles()
        verts = np.empty(len(mesh.vertices) * 3, np.float32)
        mesh.vertices.foreach_get('co', verts)
        tris = np.empty(len(mesh.loop_triangles) * 3, np.int32)
        mesh.loop_triangles.foreach_get('vertices', tris)
    finally:
        ob.evaluated_get(depsgraph).to_mesh_clear()
    return _world(verts.reshape(-1, 3), ob.matrix_world), tris.reshape(-1, 3)


def scalp_from_object(ob, voxel=0.0, extras=(), fill_holes=0.0):
    """groom.Scalp from a mesh object's evaluated triangles, in world space, joined with those of the
    mesh objects in `extras` (eyeballs in open sockets, teeth): the scalp is the solid they make
    together, as `groom scalp head.obj eyes.obj` makes it (the head's size sets the automatic voxel;
    unlike the command, a joined mesh far from the head or of another scale is not refused).
    `fill_holes` closes open rims up to that length, as `groom scalp --fill-holes`."""
    if ob is None or ob.type != 'MESH':
        raise ValueError(f"scalp: expected a mesh object, got {ob.name + ' (' + ob.type + ')' if ob else 'none'}")
    depsgraph = bpy.context.evaluated_depsgraph_get()
    points, triangles = [], []
    base = 0
    for part in [ob] + [e for e in extras if e.type == 'MESH' and e != ob]:
        verts, tris = _world_triangles(part, depsgraph)
        points.append(verts)
        triangles.append(tris + base)
        base += len(verts)
    if voxel <= 0.0 and len(points) > 1:
        # As `groom scalp head.obj eyes.obj`: the head sets the automatic voxel (its diagonal / 256),
        # so a body joined to it does not make it coarser.
        voxel = float(np.linalg.norm(points[0].max(axis=0) - points[0].min(axis=0))) / 256.0
    return groom.Scalp.from_mesh(np.concatenate(points), np.concatenate(triangles), voxel=voxel, fill_holes=fill_holes)


def curves_object(curves, name, collection):
    """A new hair Curves object holding `curves` (groom.CurveSet), its `radius` half of groom's
    `width` where the curves have one. Blender 3.4's Python cannot size a Curves datablock, so the
    curves go in as a poly curve and are converted (the conversion keeps curve and point order)."""
    counts = np.asarray(curves.counts)
    points = np.asarray(curves.points, np.float32)
    cu = bpy.data.curves.new(name, 'CURVE')
    cu.dimensions = '3D'
    start = 0
    for n in counts.tolist():
        spline = cu.splines.new('POLY')
        spline.points.add(n - 1)
        co = np.ones((n, 4), np.float32)
        co[:, :3] = points[start:start + n]
        spline.points.foreach_set('co', co.ravel())
        start += n
    ob = bpy.data.objects.new(name, cu)
    collection.objects.link(ob)
    view_layer = bpy.context.view_layer
    for other in view_layer.objects.selected:
        other.select_set(False)
    view_layer.objects.active = ob
    ob.select_set(True)
    bpy.ops.object.convert(target='CURVES')
    ob = view_layer.objects.active
    radius = ob.data.attributes.get('radius') or ob.data.attributes.new('radius', 'FLOAT', 'POINT')
    if 'width' in curves.point_attributes:
        radius.data.foreach_set('value', 0.5 * np.asarray(curves.point_attributes['width'], np.float32))
    elif len(points):
        # Guides without widths (a hairline, section guides) got Blender's default radius of 1: tubes
        # 2 cm thick on a head in centimetres, 2 m in metres. A thousandth of their extent draws them thin.
        extent = float(np.max(points.max(axis=0) - points.min(axis=0)))
        radius.data.foreach_set('value', np.full(len(points), max(1e-3 * extent, 1e-6), np.float32))
        ob[_NO_WIDTH] = True
    _keep_attributes(curves, ob)
    return ob


def _keep_attributes(curves, ob):
    """groom's curve attributes that Blender can hold (32-bit int, float, float3; not the 64-bit ids)
    as CURVE-domain attributes, and its detail attributes as object properties (groom_NAME), for
    curveset_from_object and for the artist's own node trees."""
    for name in curves.curve_attributes.keys():
        if name in _BLENDER_NAMES:
            continue
        values = np.asarray(curves.curve_attributes[name])
        if values.dtype == np.int32:
            a = ob.data.attributes.new(name, 'INT', 'CURVE')
            a.data.foreach_set('value', values)
        elif values.dtype == np.float32 and values.ndim == 1:
            a = ob.data.attributes.new(name, 'FLOAT', 'CURVE')
            a.data.foreach_set('value', values)
        elif values.dtype == np.float32 and values.ndim == 2 and values.shape[1] == 3:
            a = ob.data.attributes.new(name, 'FLOAT_VECTOR', 'CURVE')
            a.data.foreach_set('vector', values.ravel())
    for name in curves.detail_attributes.keys():
        value = curves.detail_attributes[name]
        if isinstance(value, str):
            ob[_DETAIL + name] = value
        else:
            flat = np.asarray(value).ravel()
            if flat.size == 1:
                ob[_DETAIL + name] = flat[0].item()
            elif flat.dtype.kind == 'f':
                ob[_DETAIL + name] = [float(x) for x in flat]
