# Run by tests/render/blender_import_test.sh inside Blender:
#   blender -b --factory-startup --python-exit-code 1 --python blender_import.py -- \
#       animation.glb trajectories.csv leaf.obj animation_instanced.glb
# Imports the glTF with Blender's own importer and checks what a user relies on: one object per
# body, the mesh's UV layer holding the OBJ's texture coordinates, keyframes at the output
# times, one material per body entry, the body's attributes as custom properties, the bodies
# sharing their type's mesh, a body released later hidden (scale 0) until its release. Then says
# whether this Blender imports the instanced file (EXT_mesh_gpu_instancing).
import csv
import sys

import bpy
import numpy

glb, trajectories, obj, instanced = sys.argv[sys.argv.index("--") + 1:]

# Debian 12's Blender 3.4.1 importer uses numpy.bool, which Debian's numpy 1.24 no longer has:
# its default shading (the file's normals) fails without this alias (docs/outputs.md)
if not hasattr(numpy, "bool"):
    numpy.bool = bool

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)

# the run's bodies and output times
times, bodies, entries, rows = set(), set(), set(), []
with open(trajectories) as f:
    for row in csv.DictReader(f):
        times.add(float(row["t"]))
        bodies.add(int(row["body"]))
        entries.add(row["type"])
        rows.append((row["t"], int(row["body"])))
times = sorted(times)

# the OBJ's texture coordinates
obj_uv = set()
with open(obj) as f:
    for line in f:
        p = line.split()
        if p and p[0] == "vt":
            obj_uv.add((round(float(p[1]), 4), round(float(p[2]), 4)))
check(obj_uv, "the OBJ has vt lines")

objects = [o for o in bpy.data.objects if o.name.startswith("body_")]
check(len(objects) == len(bodies), f"{len(objects)} body objects for {len(bodies)} bodies")

fps = bpy.context.scene.render.fps / bpy.context.scene.render.fps_base
for o in objects:
    check(o.type == "MESH", f"{o.name} is a mesh")
    mesh = o.data
    check(len(mesh.uv_layers) >= 1, f"{o.name}: a UV layer")
    if mesh.uv_layers:
        uv = {(round(d.uv[0], 4), round(d.uv[1], 4)) for d in mesh.uv_layers[0].data}
        check(uv <= obj_uv, f"{o.name}: UVs not among the OBJ's: {sorted(uv - obj_uv)[:3]}")
        # the leaf's both sides carry the texture: every one of the OBJ's coordinates is used
        check(len(uv) == len(obj_uv), f"{o.name}: {len(uv)} of the OBJ's {len(obj_uv)} UVs")
    check(len(mesh.polygons) > 0, f"{o.name}: faces")
    # the body's attributes (the node's extras)
    check(o.get("id") is not None and int(o["id"]) in bodies, f"{o.name}: id property")
    check(o.get("entry") in entries, f"{o.name}: entry property {o.get('entry')}")
    check(o.get("variant") is not None, f"{o.name}: variant property")
    # keyframes at the output times
    ad = o.animation_data
    check(ad is not None and ad.action is not None, f"{o.name}: animated")
    if ad and ad.action:
        frames = set()
        for fc in ad.action.fcurves:
            if fc.data_path == "location":
                frames |= {round(k.co[0], 3) for k in fc.keyframe_points}
        want = {round(t * fps + 1, 3) for t in times}
        want0 = {round(t * fps, 3) for t in times}
        check(frames == want or frames == want0,
              f"{o.name}: keyframes at frames {sorted(frames)}, output times give {sorted(want)}")
    # its material is its entry's
    mats = [s.material.name for s in o.material_slots if s.material]
    check(any(m.split(".")[0] == o.get("entry") for m in mats), f"{o.name}: materials {mats}")

for e in entries:
    check(e in bpy.data.materials, f"material {e}")

# instanced the way Blender instances: the leaves are linked duplicates of one mesh
meshes = {o.data.name for o in objects}
check(len(meshes) == len(entries), f"{len(objects)} leaves use meshes {sorted(meshes)}")

# a leaf released later (the scene's release rate) is hidden until its release: scale 0 at the
# first output time, its own size at the last
for o in objects:
    first_row = min(float(t) for t, b in rows if b == int(o["id"]))
    ad = o.animation_data
    scale = [fc for fc in ad.action.fcurves if fc.data_path == "scale"] if ad and ad.action else []
    if first_row > times[0]:
        check(scale, f"{o.name}: released at {first_row} s but no scale channel")
        if scale:
            ks = scale[0].keyframe_points
            check(ks[0].co[1] == 0 and ks[-1].co[1] == 1,
                  f"{o.name}: scale {ks[0].co[1]} at the start, {ks[-1].co[1]} at the end")
released_late = sum(1 for o in objects
                    if min(float(t) for t, b in rows if b == int(o["id"])) > times[0])
check(released_late >= 1, "a leaf released after the first output time")

# the instanced file: imported, or refused for its required extension
bpy.ops.wm.read_factory_settings(use_empty=True)
try:
    bpy.ops.import_scene.gltf(filepath=instanced)
    print("blender_import: instanced file imported")
except Exception as e:  # the importer reports its refusal as an operator error
    check("EXT_mesh_gpu_instancing" in str(e), f"instanced file refused for another reason: {e}")
    print("blender_import: instanced file refused:", str(e).strip().splitlines()[-1])

if failures:
    for f in failures[:20]:
        print("FAIL:", f)
    sys.exit(1)
print(f"blender_import: {len(objects)} bodies, {len(times)} times, UVs and materials as written")
