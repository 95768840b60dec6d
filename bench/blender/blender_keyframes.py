"""`import lrigid` inside Blender: runs a scene with the Python module in Blender's own Python
(Debian's Blender uses the system Python 3.11, the interpreter the module is built for) and keys
every body's location and rotation on the timeline, with a gust pushed mid-run. Run inside
Blender (bench/blender/python_keyframes.sh):

    blender -b --factory-startup --python-exit-code 1 \
        --python bench/blender/blender_keyframes.py -- BUILD_DIR SCENE.json OUT.blend \
        [--bodies N] [--seconds S] [--fps F]

Checks (exit 1 on failure): one object per body, one keyframe per frame on each location and
quaternion channel, and at the first, middle and last frame (frame_set) every object's world
position and rotation equal the module's state at that time (to float32, Blender's storage);
the pushed bodies rise faster than they would have.
"""
import json
import math
import os
import sys
import time

import bmesh
import bpy
from mathutils import Quaternion, Vector

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(args) < 3:
    sys.exit("blender_keyframes.py: usage: -- BUILD_DIR SCENE.json OUT.blend [--bodies N] "
             "[--seconds S] [--fps F]")
build, scene_path, blend = args[:3]
opt = dict(zip(args[3::2], args[4::2]))
nbodies = int(opt.get("--bodies", 40))
seconds = float(opt.get("--seconds", 1.0))
fps = int(opt.get("--fps", 24))

# Blender ignores PYTHONPATH unless started with --python-use-system-env: add the build's
# module folder here
sys.path.insert(0, os.path.join(os.path.abspath(build), "python"))
import lrigid  # noqa: E402

print("blender_keyframes: Blender %s, Python %s, lrigid %s from %s" % (
    bpy.app.version_string, sys.version.split()[0], lrigid.__version__, lrigid.__file__),
    flush=True)
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what, flush=True)


with open(scene_path) as f:
    d = json.load(f)
for b in d["bodies"]:
    b["count"] = max(1, nbodies // len(d["bodies"]))
d["duration"] = seconds
sim = lrigid.Simulation(lrigid.Scene.from_dict(d, name=scene_path), threads=1)
n = len(sim)


def shape_mesh(name, shape):
    """the body type's surface in its body frame (boxes and spheres: centred)"""
    bm = bmesh.new()
    if shape["type"] == "sphere":
        bmesh.ops.create_uvsphere(bm, u_segments=16, v_segments=8, radius=shape["radius"])
    elif shape["type"] == "box":
        bmesh.ops.create_cube(bm, size=1.0)
        for v in bm.verts:
            v.co = Vector([c * s for c, s in zip(v.co, shape["size"])])
    else:
        sys.exit("blender_keyframes.py: this demo draws boxes and spheres, not " + shape["type"])
    me = bpy.data.meshes.new(name)
    bm.to_mesh(me)
    bm.free()
    return me


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = fps
frames = int(round(seconds * fps))
scene.frame_start, scene.frame_end = 0, frames
meshes = [shape_mesh(b["name"], b["shape"]) for b in d["bodies"]]
objs = []
for i in range(n):
    o = bpy.data.objects.new("body_%d_%s" % (i, sim.type_names[sim.types[i]]),
                             meshes[sim.types[i]])
    o.rotation_mode = "QUATERNION"
    scene.collection.objects.link(o)
    objs.append(o)

# step and key: the state at frame k is the state at t = k / fps
t_run = t_key = 0.0
ref = {}
pushed = list(range(0, n, 4))
v_before = None
for k in range(frames + 1):
    t0 = time.perf_counter()
    sim.run(until=k / fps)
    if k == frames // 2:  # a gust: every 4th body pushed upwards (0.5 m/s for its bare mass)
        v_before = sim.velocities[pushed, 2].copy()
        for i in pushed:
            m = sim.type_info(int(sim.types[i]))["mass"]
            sim.push(i, [0.0, 0.0, 0.5 * m])
        v_after = sim.velocities[pushed, 2]
    t1 = time.perf_counter()
    x, q = sim.positions.copy(), sim.orientations  # positions is a view that follows the run
    for i, o in enumerate(objs):
        o.location = x[i]
        o.rotation_quaternion = q[i]
        o.keyframe_insert("location", frame=k)
        o.keyframe_insert("rotation_quaternion", frame=k)
    ref[k] = (x, q)
    t_run += t1 - t0
    t_key += time.perf_counter() - t1
print("blender_keyframes: %d bodies x %d frames: stepping %.2f s, keyframing %.2f s" % (
    n, frames + 1, t_run, t_key), flush=True)

for o in objs:
    fc = o.animation_data.action.fcurves
    check(len(fc) == 7, "%s: %d F-curves, expected 7" % (o.name, len(fc)))
    check(all(len(c.keyframe_points) == frames + 1 for c in fc),
          "%s: not one key per frame" % o.name)
for k in (0, frames // 2, frames):
    scene.frame_set(k)
    x, q = ref[k]
    for i, o in enumerate(objs):
        mw = o.matrix_world
        dx = (mw.translation - Vector(x[i])).length
        dq = mw.to_quaternion().rotation_difference(Quaternion(q[i])).angle
        dq = min(dq, 2 * math.pi - dq)  # q and -q are the same rotation
        check(dx <= 1e-6 * max(1.0, Vector(x[i]).length), "frame %d %s: position off by %g m"
              % (k, o.name, dx))
        check(dq <= 1e-5, "frame %d %s: rotation off by %g rad" % (k, o.name, dq))
check(v_before is not None and all(a > b + 0.1 for a, b in zip(v_after, v_before)),
      "the push did not speed the bodies upwards: %s -> %s" % (v_before, v_after))
bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(blend))
print("blender_keyframes: saved %s" % blend, flush=True)
if failures:
    print("blender_keyframes: FAIL (%d)" % len(failures), flush=True)
    sys.exit(1)
print("blender_keyframes: PASS (%d bodies, %d keyed frames, pushed %d bodies at frame %d)" % (
    n, frames + 1, len(pushed), frames // 2), flush=True)
