#!/usr/bin/python3
"""The runtime's folders are layers: a file may include only from its own folder and the layers
below it. Scans every #include "..." in runtime/src/** and runtime/app/**, prints each include
that goes up a layer (or across to another folder of the same layer) as
    file:line: 'a' includes 'b' (layer X above Y)
and exits non-zero when there is one.

The layers, lowest first (a folder may include its own and every lower layer's headers):
    util <- body, fluid <- model <- effects <- contact <- compile, integrate <- io <- app
body and fluid are one layer, and so are compile (the model built from a scene) and integrate
(the steps): neither of a pair includes the other.

Usage: layers_test.py [source root]   (default: the repository this script is in)
"""
import os
import re
import sys

LAYERS = [
    ["util"],
    ["body", "fluid"],
    ["model"],
    ["effects"],
    ["contact"],
    ["compile", "integrate"],
    ["io"],
    ["app"],
]
LEVEL = {folder: level for level, folders in enumerate(LAYERS) for folder in folders}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def folder_of(path, root):
    """The layer folder of a file under runtime/src/<folder>/ or runtime/app/."""
    rel = os.path.relpath(path, root).split(os.sep)
    if rel[:2] == ["runtime", "app"]:
        return "app"
    if rel[:2] == ["runtime", "src"] and len(rel) > 3:
        return rel[2]
    return None


def target_of(include, folder):
    """The layer folder an include names: its first path component when that is a layer,
    the including file's own folder for a bare name ("cmd_run.h"), None for anything else
    (a third-party header included with quotes)."""
    parts = include.split("/")
    if len(parts) == 1:
        return folder
    return parts[0] if parts[0] in LEVEL else None


def violations(root):
    found = []
    for top in (os.path.join(root, "runtime", "src"), os.path.join(root, "runtime", "app")):
        for dirpath, dirnames, filenames in os.walk(top):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith((".h", ".hpp", ".cpp", ".cc", ".inl")):
                    continue
                path = os.path.join(dirpath, name)
                folder = folder_of(path, root)
                if folder is None:
                    continue
                if folder not in LEVEL:
                    found.append("%s:1: folder '%s' is in no layer (add it to LAYERS in %s)"
                                 % (os.path.relpath(path, root), folder, sys.argv[0]))
                    continue
                with open(path, encoding="utf-8", errors="replace") as f:
                    for line_no, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        target = target_of(m.group(1), folder)
                        if target is None or target == folder:
                            continue
                        if LEVEL[target] > LEVEL[folder]:
                            relation = "above"
                        elif LEVEL[target] == LEVEL[folder]:
                            relation = "beside"
                        else:
                            continue
                        rel = os.path.relpath(path, root)
                        me = rel[len("runtime/src/"):] if rel.startswith("runtime/src/") else rel
                        found.append("%s:%d: '%s' includes '%s' (layer %s %s %s)"
                                     % (rel, line_no, me, m.group(1), target, relation, folder))
    return found


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(
        os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    if not os.path.isdir(os.path.join(root, "runtime", "src")):
        print("layers_test: no runtime/src under %s" % root, file=sys.stderr)
        return 2
    found = violations(root)
    for v in found:
        print(v)
    if found:
        print("layers_test: %d include(s) go up a layer (layers, lowest first: %s)"
              % (len(found), " <- ".join(", ".join(f) for f in LAYERS)), file=sys.stderr)
        return 1
    print("layers_test: every include of runtime/src and runtime/app stays within its layers")
    return 0


if __name__ == "__main__":
    sys.exit(main())
