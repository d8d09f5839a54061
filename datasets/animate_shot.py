#!/usr/bin/env python3
"""The animation of datasets/animate.sh: Alisha turning her head over FRAMES frames.

  animate_shot.py OUT_DIR FRAMES HEAD.obj TAILS.obj

writes OUT_DIR/poses.txt (the head's rigid pose per frame, for --scalp-xform: frame, then a 3x4
matrix [R|t] row by row), OUT_DIR/head.####.obj (the head mesh posed, only for the pictures: groom
itself never rebuilds the field) and OUT_DIR/tails.####.obj (her loose curly ends' guides, swayed and
posed: per-frame world space, as a simulation would hand them over). Standard library only.

The turn: about the vertical axis through the neck, from -35 to +35 degrees with an ease in and
out, and a nod of up to 4 degrees. The sway: the ends lag the turn, each tail bent about the vertical
through its root by an angle proportional to the head's angular velocity (opposite to it), growing
with the square of the distance along the tail; so the ends swing out as the head speeds up and
settle as it stops.
"""
import math
import sys


def read_obj(path):
    verts, lines, faces = [], [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                verts.append(tuple(float(x) for x in w[1:4]))
            elif w[0] == "l":
                lines.append([int(x.split("/")[0]) - 1 for x in w[1:]])
            elif w[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in w[1:]])
    return verts, lines, faces


def write_obj(path, verts, lines=(), faces=()):
    out = ["v %.7g %.7g %.7g\n" % v for v in verts]
    out += ["l " + " ".join(str(i + 1) for i in l) + "\n" for l in lines]
    out += ["f " + " ".join(str(i + 1) for i in f) + "\n" for f in faces]
    with open(path, "w") as f:
        f.writelines(out)


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(r, t, p):
    return tuple(r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + t[i] for i in range(3))


def main():
    out, frames, head_path, tails_path = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
    hv, _, hf = read_obj(head_path)
    tv, tl, _ = read_obj(tails_path)
    lo = [min(v[i] for v in hv) for i in range(3)]
    hi = [max(v[i] for v in hv) for i in range(3)]
    pivot = ((lo[0] + hi[0]) / 2, lo[1] + 0.35 * (hi[1] - lo[1]), (lo[2] + hi[2]) / 2)  # the top of the neck

    def turn(f):  # degrees
        return -35.0 + 70.0 * (0.5 - 0.5 * math.cos(math.pi * f / (frames - 1)))

    poses = []
    with open(f"{out}/poses.txt", "w") as pf:
        pf.write("# frame, then [R|t] row by row: a turn about the neck (datasets/animate_shot.py)\n")
        for f in range(frames):
            r = mul(rot_y(math.radians(turn(f))), rot_x(math.radians(4.0 * math.sin(math.pi * f / (frames - 1)))))
            rp = apply(r, (0, 0, 0), pivot)
            t = [pivot[i] - rp[i] for i in range(3)]
            poses.append((r, t))
            pf.write("%d " % f + " ".join("%.17g %.17g %.17g %.17g" % (r[i][0], r[i][1], r[i][2], t[i]) for i in range(3)) + "\n")
    for f, (r, t) in enumerate(poses):
        write_obj(f"{out}/head.{f:04d}.obj", [apply(r, t, v) for v in hv], faces=hf)
        # Angular velocity, degrees per frame (central difference); the ends lag by 6 frames of it.
        vel = (turn(min(f + 1, frames - 1)) - turn(max(f - 1, 0))) / (min(f + 1, frames - 1) - max(f - 1, 0))
        sway = math.radians(-6.0 * vel)
        verts = list(tv)
        for line in tl:
            root = tv[line[0]]
            total = sum(math.dist(tv[a], tv[b]) for a, b in zip(line, line[1:])) or 1.0
            s = 0.0
            for k, i in enumerate(line):
                if k:
                    s += math.dist(tv[line[k - 1]], tv[i])
                a = sway * (s / total) ** 2
                d = [tv[i][j] - root[j] for j in range(3)]
                c, sn = math.cos(a), math.sin(a)
                verts[i] = (root[0] + c * d[0] + sn * d[2], root[1] + d[1], root[2] - sn * d[0] + c * d[2])
        write_obj(f"{out}/tails.{f:04d}.obj", [apply(r, t, v) for v in verts], lines=tl)


if __name__ == "__main__":
    main()
