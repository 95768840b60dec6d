#!/usr/bin/env bash
# A short run of a leaf OBJ with texture coordinates, released one leaf every 0.1 s, its
# animation.glb imported by Blender
# (headless, its own glTF importer): tests/render/blender_import.py checks the objects, UVs,
# keyframes, materials and attributes, and whether Blender imports the instanced file
# (EXT_mesh_gpu_instancing; Blender 3.4's importer refuses it, not knowing the extension).
#   blender_import_test.sh SOURCE_DIR LRIGID
set -euo pipefail
src=$1
lrigid=$2
command -v blender >/dev/null || { echo "FAIL: blender not found (scripts/install-deps)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/scene.json" <<JSON
{ "version": 1,
  "fluid": { "density": 1.2, "kinematic_viscosity": 1.5e-5,
             "uniform": { "U": [1, 0, 0], "k": 0.01, "epsilon": 0.01 } },
  "gravity": [0, 0, -9.81], "effects": ["gravity", "drag"],
  "integrator": { "scheme": "splitting", "dt": 0.01 }, "duration": 0.3, "seed": 1,
  "bodies": [ { "name": "leaf",
                "shape": { "type": "mesh", "file": "$src/tests/data/meshes/leaf_surface.obj",
                           "scale": 2, "thickness": 0.0008 },
                "density": 600, "count": 3, "position": [0, 0, 1],
                "release": { "rate": 10 } } ],
  "output": { "dir": "$work/out", "every": 0.05, "formats": ["csv", "glb", "glb_instanced"] } }
JSON
"$lrigid" run "$work/scene.json" --quiet >/dev/null
blender -b --factory-startup --python-exit-code 1 \
  --python "$src/tests/render/blender_import.py" -- \
  "$work/out/animation.glb" "$work/out/trajectories.csv" \
  "$src/tests/data/meshes/leaf_surface.obj" "$work/out/animation_instanced.glb" \
  > "$work/blender.log" 2>&1 ||
  { cat "$work/blender.log"; echo "FAIL: Blender's import of animation.glb"; exit 1; }
grep "blender_import:" "$work/blender.log"
echo "blender_import_test: ok"
