#!/usr/bin/env python3
"""The layers of curvemesh, checked: a file may include its own layer and the layers below it, never
one above. The order is the data flow (svg -> features -> triangulate -> optimize -> curve -> io) with
base (files and text from outside), geometry and mesh below it, then the one pipeline that drives the stages, then what calls the
pipeline: the finite elements, the public API, the command line and the Python module. The finite
elements take a finished mesh: they include no stage.

    layering.py SRC_DIR [INCLUDE_DIR ...]   exit 0 when every include keeps to the order, 1 otherwise
    layering.py --self-test                 shows that a file including a layer above its own fails
"""
import os
import re
import sys
import tempfile

ORDER = ["base", "geometry", "mesh", "svg", "features", "triangulate", "optimize", "curve", "io", "regions",
         "pipeline", "fem", "api", "app", "python"]
RANK = {layer: i for i, layer in enumerate(ORDER)}
# Below its own rank, a layer may still not reach these (it must go through the pipeline). The
# command line calls the pipeline and never a stage, nor cuts a mesh (regions) or touches one (mesh):
# it reads and writes files through io.
FORBIDDEN = {
    "fem": {"svg", "features", "triangulate", "optimize", "curve"},
    "app": {"mesh", "svg", "features", "triangulate", "optimize", "curve", "regions"},
    "api": {"svg", "features", "triangulate", "optimize", "curve", "regions", "fem"},
    "python": {"base", "geometry", "mesh", "svg", "features", "triangulate", "optimize", "curve", "io", "regions",
               "pipeline", "fem"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)
# A layer's namespace named in code (comments and strings left out), e.g. `regions::submesh`: what a
# forbidden layer's header reached through an allowed one would still let a file call.
QUALIFIED = re.compile(r'\b([a-z]+)::')
COMMENT_OR_STRING = re.compile(r'//[^\n]*|"(?:\\.|[^"\\\n])*"')


def layer_of(path, root):
    rel = os.path.relpath(path, root).replace(os.sep, "/")
    first = rel.split("/")[0]
    return first if first in RANK else None


def violations(roots):
    found = []
    for root in roots:
        for folder, _, files in os.walk(root):
            for name in sorted(files):
                if not name.endswith((".hpp", ".cpp", ".h")):
                    continue
                path = os.path.join(folder, name)
                own = layer_of(path, root)
                if own is None:
                    continue
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for included in INCLUDE.findall(text):
                    target = included.split("/")[0]
                    if target not in RANK:
                        continue  # the public header (curvemesh/...), or a file beside this one
                    if RANK[target] > RANK[own]:
                        found.append(f"{path}: {own} includes \"{included}\", a layer above it")
                    elif target in FORBIDDEN.get(own, ()):
                        found.append(f"{path}: {own} includes \"{included}\"; it must go through the pipeline")
                code = COMMENT_OR_STRING.sub("", text)
                for named in sorted(set(QUALIFIED.findall(code)) & FORBIDDEN.get(own, set())):
                    found.append(f"{path}: {own} calls {named}::; it must go through the pipeline")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, "curve"))
        os.makedirs(os.path.join(tmp, "fem"))
        os.makedirs(os.path.join(tmp, "app"))
        with open(os.path.join(tmp, "curve", "ok.cpp"), "w") as f:
            f.write('#include "mesh/tri_mesh.hpp"\n#include "curve/curve.hpp"\n')
        if violations([tmp]):
            print("self-test: a file including only lower layers was refused")
            return 1
        with open(os.path.join(tmp, "curve", "up.cpp"), "w") as f:
            f.write('#include "pipeline/pipeline.hpp"\n')
        with open(os.path.join(tmp, "fem", "stage.cpp"), "w") as f:
            f.write('#include "triangulate/triangulate.hpp"\n')
        with open(os.path.join(tmp, "app", "cut.cpp"), "w") as f:
            f.write('#include "pipeline/pipeline.hpp"\n#include "regions/faces.hpp"\n')
        with open(os.path.join(tmp, "app", "reach.cpp"), "w") as f:
            f.write('#include "pipeline/pipeline.hpp"\n// regions::x in a comment\nint f() { return regions::count(); }\n')
        found = violations([tmp])
        if len(found) != 4:
            print("self-test: expected 4 violations, found", found)
            return 1
    print("self-test: ok (an upward include, a stage included by fem, a cut in the command line, included or reached: all refused)")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) < 2:
        print(__doc__)
        return 2
    found = violations(argv[1:])
    for v in found:
        print(v)
    print(f"layering: {len(found)} includes out of order")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
