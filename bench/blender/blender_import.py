"""Imports an lrigid animation.glb with Blender's own glTF importer and checks it against the
run's trajectories.csv and summary.json. Run inside Blender (bench/blender/check_import.sh):

    blender -b --factory-startup --python bench/blender/blender_import.py -- \
        RESULTS_DIR/animation.glb RESULTS_DIR [--sample 5] [--json out.json]

Checks (exit 1 on the first failed group, listing every failure):
  - one object per body, named body_<index>_<type>, children of the root lrigid_world_z_up;
  - mesh data shared: one Blender mesh per body type, used by every body of that type;
  - keyframes: every body's location and rotation F-curves hold one keyframe per output time,
    at frame = t * fps (the scene's frame rate);
  - transforms: for a few bodies at the first, middle and last output time (frame_set), the
    object's world position equals x of trajectories.csv, its world rotation equals
    q * Rx(-90 deg) (the importer turns the mesh data +90 deg about x when it converts glTF's
    Y-up to Blender's Z-up), and for box bodies the 8 world-space corners of the mesh's
    bounding box equal x + R(q) ((+-hx, +-hy, +-hz) - com) with the half extents and centre of
    mass of summary.json: the shape lands where the simulation put it, whatever the axes.
"""
import csv
import json
import math
import os
import sys
import time

import bpy
from mathutils import Quaternion, Vector

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(args) < 2:
    sys.exit("blender_import.py: usage: -- FILE.glb RESULTS_DIR [--sample N] [--json OUT]")
glb, results = args[0], args[1]
sample = int(args[args.index("--sample") + 1]) if "--sample" in args else 5
json_out = args[args.index("--json") + 1] if "--json" in args else None

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        if len(failures) <= 20:
            print("FAIL: " + what, flush=True)
    return ok


def end_group(name):
    if failures:
        print("blender_import: %s: %d failure(s)" % (name, len(failures)), flush=True)
        sys.exit(1)
    print("blender_import: %s: ok" % name, flush=True)


# the reference: trajectories.csv (frame by frame, bodies in order) and summary.json
with open(os.path.join(results, "summary.json")) as f:
    summary = json.load(f)
times, rows = [], {}
with open(os.path.join(results, "trajectories.csv")) as f:
    r = csv.DictReader(f)
    for row in r:
        t = float(row["t"])
        if not times or times[-1] != t:
            times.append(t)
        rows[(int(row["body"]), len(times) - 1)] = row
nbody = 1 + max(b for b, _ in rows)
body_type = {b: rows[(b, 0)]["type"] for b in range(nbody)}
print("blender_import: reference %d bodies x %d output times" % (nbody, len(times)), flush=True)

# the import itself, from an empty scene
bpy.ops.wm.read_factory_settings(use_empty=True)
t0, c0 = time.perf_counter(), time.process_time()
# import_shading FLAT: the default "NORMALS" of Debian 12's Blender 3.4.1 importer calls the
# removed np.bool and fails with numpy 1.24 (AttributeError); the file has no normals anyway
res = bpy.ops.import_scene.gltf(filepath=glb, import_shading="FLAT")
import_seconds, import_cpu = time.perf_counter() - t0, time.process_time() - c0
print("blender_import: imported %s in %.2f s (cpu %.2f s) (%s)" % (glb, import_seconds,
                                                                   import_cpu, res), flush=True)
scene = bpy.context.scene
fps = scene.render.fps / scene.render.fps_base

# 1. one object per body, under the root
bodies = {}
for ob in bpy.data.objects:
    if ob.name.startswith("body_"):
        parts = ob.name.split("_", 2)
        bodies[int(parts[1])] = ob
check(len(bodies) == nbody, "%d body objects, expected %d" % (len(bodies), nbody))
root = bpy.data.objects.get("lrigid_world_z_up")
check(root is not None, "no root object lrigid_world_z_up")
for b, ob in bodies.items():
    check(ob.name == "body_%d_%s" % (b, body_type.get(b)),
          "object %s: type %s expected" % (ob.name, body_type.get(b)))
    check(ob.parent == root, "object %s: parent %s" % (ob.name, ob.parent and ob.parent.name))
    check(ob.type == "MESH", "object %s: type %s" % (ob.name, ob.type))
end_group("one object per body")

# 2. mesh data stored once per body type
meshes_of = {}
for b, ob in bodies.items():
    meshes_of.setdefault(body_type[b], set()).add(ob.data.name)
ntypes = len(set(body_type.values()))
check(len(bpy.data.meshes) == ntypes, "%d meshes in the file's import, expected %d (one per type)"
      % (len(bpy.data.meshes), ntypes))
for t, names in meshes_of.items():
    check(len(names) == 1, "type %s uses %d meshes: %s" % (t, len(names), sorted(names)[:3]))
users = {m.name: m.users for m in bpy.data.meshes}
print("blender_import: meshes %s" % users, flush=True)
end_group("mesh data shared per body type")

# 3. keyframes at the output times
want = [t * fps for t in times]
for b, ob in bodies.items():
    ad = ob.animation_data
    if not check(ad is not None and ad.action is not None, "object %s: no action" % ob.name):
        continue
    curves = {(fc.data_path, fc.array_index): fc for fc in ad.action.fcurves}
    for path, n in (("location", 3), ("rotation_quaternion", 4)):
        for i in range(n):
            fc = curves.get((path, i))
            if not check(fc is not None, "object %s: no %s[%d] F-curve" % (ob.name, path, i)):
                continue
            kp = fc.keyframe_points
            if not check(len(kp) == len(times), "object %s %s[%d]: %d keyframes, expected %d" % (
                    ob.name, path, i, len(kp), len(times))):
                continue
            if b < sample:
                for k, want_f in zip(kp, want):
                    check(abs(k.co[0] - want_f) < 1e-3, "object %s %s[%d]: key at frame %.4f, "
                          "expected %.4f" % (ob.name, path, i, k.co[0], want_f))
end_group("keyframes at the output times (frame = t x %g fps)" % fps)

# 4. world transforms against trajectories.csv at the first, middle and last output time
half = {}  # box types: half extents and centre of mass in shape coordinates, m
for info in summary["body_types"]:
    if info["shape"]["type"] == "box":
        half[info["name"]] = (info["shape"]["half_extents"], Vector(info["com"]))
corr = Quaternion((1, 0, 0), math.radians(-90))  # the importer's turn of the mesh data, undone
picked = sorted(set([0, nbody // 2, nbody - 1] + list(range(min(sample, nbody)))))
worst_x = worst_q = worst_c = 0.0
for fi in sorted(set([0, len(times) // 2, len(times) - 1])):
    f = times[fi] * fps
    scene.frame_set(int(math.floor(f)), subframe=f - math.floor(f))
    for b in picked:
        ob, row = bodies[b], rows[(b, fi)]
        x = Vector((float(row["x"]), float(row["y"]), float(row["z"])))
        q = Quaternion((float(row["qw"]), float(row["qx"]), float(row["qy"]), float(row["qz"])))
        mw = ob.matrix_world
        dx = (mw.translation - x).length
        worst_x = max(worst_x, dx)
        check(dx < 1e-5 + 1e-6 * x.length, "body %d t=%g: position %s, csv %s" % (
            b, times[fi], tuple(mw.translation), tuple(x)))
        want_q = q @ corr
        got_q = mw.to_quaternion()
        dq = 1 - abs(got_q.dot(want_q))
        worst_q = max(worst_q, dq)
        check(dq < 1e-6, "body %d t=%g: rotation %s, expected %s" % (b, times[fi], tuple(got_q),
                                                                     tuple(want_q)))
        if body_type[b] in half:
            h, com = half[body_type[b]]
            want_c = [x + q @ (Vector((sx * h[0], sy * h[1], sz * h[2])) - com)
                      for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
            got = [mw @ Vector(c) for c in ob.bound_box]
            for w in want_c:
                d = min((g - w).length for g in got)
                worst_c = max(worst_c, d)
                check(d < 1e-5, "body %d t=%g: no world corner near %s (%.2e m)" % (
                    b, times[fi], w, d))
end_group("world transforms of %d bodies at 3 times (worst: position %.1e m, rotation "
          "1-|dot| %.1e, box corners %.1e m)" % (len(picked), worst_x, worst_q, worst_c))
if not half:
    print("blender_import: note: no box body type; corner check skipped", flush=True)

out = dict(glb=glb, glb_bytes=os.path.getsize(glb), bodies=nbody, times=len(times),
           import_seconds=import_seconds, import_cpu_seconds=import_cpu, fps=fps, meshes=len(bpy.data.meshes),
           objects=len(bpy.data.objects), actions=len(bpy.data.actions))
print("blender_import: " + json.dumps(out), flush=True)
if json_out:
    with open(json_out, "w") as f:
        json.dump(out, f, indent=1)
print("blender_import: PASS", flush=True)
