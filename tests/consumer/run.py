#!/usr/bin/env python3
"""The installed library, used as a user would: `cmake --install` of the build into a fresh prefix,
then two programs outside the project built against it with find_package(curvemesh):

  1. tests/consumer (CMakeLists.txt and main.cpp beside this script), run on a drawing: its .msh
     must be byte-identical to the installed `curvemesh mesh` of the same drawing;
  2. the example of README.md, the ```cmake and ```cpp blocks right after the marker
     <!-- cpp-example -->, built and run as they stand.

It also checks what the prefix holds and that the library exports the public API and nothing of
the engine. Everything happens in a temporary folder, removed at the end.

    run.py --build BUILD_DIR --source SOURCE_DIR --cmake CMAKE [--generator G] [--cxx CXX]
           [--example DRAWING.svg]
exit 0 when every step passes, 1 otherwise.
"""
import argparse
import filecmp
import os
import re
import shutil
import subprocess
import sys
import tempfile

MARKER = "<!-- cpp-example -->"


class Failure(Exception):
    pass


def run(cmd, **kw):
    print("+", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600, **kw)
    if r.stdout.strip():
        print(r.stdout.rstrip())
    if r.returncode != 0:
        print(r.stderr.rstrip())
        raise Failure(f"exit code {r.returncode}: {' '.join(cmd)}")
    return r


def readme_example(readme):
    """The first ```cmake and ```cpp blocks after the marker, before the next heading."""
    with open(readme, encoding="utf-8") as f:
        lines = f.read().splitlines(keepends=True)
    starts = [i for i, line in enumerate(lines) if line.strip() == MARKER]
    if len(starts) != 1:
        raise Failure(f"{readme}: {len(starts)} lines {MARKER}, not one")
    blocks, fence, body = {}, None, []
    for line in lines[starts[0] + 1:]:
        if fence is None:
            if line.startswith("#"):
                break  # the next heading: the example's section ends
            if line.startswith("```"):
                fence, body = line[3:].strip(), []
        elif line.startswith("```"):
            blocks.setdefault(fence, "".join(body))
            fence = None
        else:
            body.append(line)
    for lang in ("cmake", "cpp"):
        if lang not in blocks:
            raise Failure(f"{readme}: no ```{lang} block between {MARKER} and the next heading")
    return blocks["cmake"], blocks["cpp"]


def configure_build(args, source, build, prefix):
    cmd = [args.cmake, "-S", source, "-B", build, f"-DCMAKE_PREFIX_PATH={prefix}",
           "-DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON", "-DCMAKE_FIND_PACKAGE_NO_SYSTEM_PACKAGE_REGISTRY=ON"]
    if args.generator:
        cmd += ["-G", args.generator]
    if args.cxx:
        cmd += [f"-DCMAKE_CXX_COMPILER={args.cxx}"]
    run(cmd)
    # The package found is the one just installed, not another on the machine.
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        found = re.search(r"^curvemesh_DIR:PATH=(.*)$", f.read(), re.M)
    if not found or not os.path.realpath(found.group(1)).startswith(os.path.realpath(prefix) + os.sep):
        raise Failure(f"find_package(curvemesh) found {found.group(1) if found else 'nothing'}, not {prefix}")
    run([args.cmake, "--build", build])


def check_prefix(prefix):
    libdirs = [d for d in ("lib", "lib64") if os.path.isdir(os.path.join(prefix, d))]
    libs = [os.path.join(prefix, d, n) for d in libdirs for n in os.listdir(os.path.join(prefix, d))
            if n.startswith("libcurvemesh.so")]
    expected = ["include/curvemesh/curvemesh.hpp", "include/curvemesh/parameters.hpp", "bin/curvemesh"]
    missing = [e for e in expected if not os.path.exists(os.path.join(prefix, e))]
    configs = [os.path.join(r, "curvemeshConfig.cmake") for r, _, files in os.walk(prefix)
               if "curvemeshConfig.cmake" in files]
    if missing or not libs or not configs:
        raise Failure(f"the prefix lacks {missing + ([] if libs else ['libcurvemesh.so']) + ([] if configs else ['curvemeshConfig.cmake'])}")
    # Only the public headers: nothing of src/ is installed.
    headers = sorted(os.listdir(os.path.join(prefix, "include")))
    if headers != ["curvemesh"]:
        raise Failure(f"include/ holds {headers}, not curvemesh/ alone")
    print(f"prefix: {', '.join(os.path.relpath(p, prefix) for p in libs + configs)}")
    return [p for p in libs if not os.path.islink(p)][0]


def check_exports(lib):
    """The library exports the API; no symbol of the engine's namespaces or of its dependencies."""
    nm = shutil.which("nm")
    if not nm:
        print("nm not found: exports not checked")
        return
    r = subprocess.run([nm, "-D", "--defined-only", "-C", lib], capture_output=True, text=True, check=True)
    # "ADDRESS TYPE NAME": a name of the engine, or the type information of one of its classes
    # (std:: templates instantiated on them are the standard library's, exported by its headers).
    symbols = [line.split(" ", 2)[-1] for line in r.stdout.splitlines()]
    internal = re.compile(r"^(?:(?:typeinfo name|typeinfo|vtable|VTT|guard variable) for )?"
                          r"(?:curvemesh::(?:pipeline|io|svg|features|triangulate|optimize|curve|mesh|geometry|api)::"
                          r"|CGAL::|Eigen::|nlohmann::|pugi::|__gmp)")
    leaked = [s for s in symbols if internal.search(s)]
    if leaked:
        raise Failure(f"{lib} exports {len(leaked)} internal symbols, e.g. {leaked[:3]}")
    api = [s for s in symbols if "curvemesh::mesh_file" in s or "curvemesh::Mesh::write" in s]
    if len(api) != 2:
        raise Failure(f"{lib} does not export curvemesh::mesh_file and curvemesh::Mesh::write")
    print(f"exports: {len(symbols)} symbols, none of the engine")


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True, help="the configured and built project to install")
    ap.add_argument("--source", required=True, help="the project's source folder (README.md, examples/)")
    ap.add_argument("--cmake", default="cmake")
    ap.add_argument("--generator")
    ap.add_argument("--cxx")
    ap.add_argument("--example", help="the drawing to mesh (default examples/overlapping-shapes.svg)")
    args = ap.parse_args(argv)
    drawing = args.example or os.path.join(args.source, "examples", "overlapping-shapes.svg")
    here = os.path.dirname(os.path.abspath(__file__))

    tmp = tempfile.mkdtemp(prefix="curvemesh-consumer-")
    try:
        prefix = os.path.join(tmp, "prefix")
        run([args.cmake, "--install", args.build, "--prefix", prefix])
        lib = check_prefix(prefix)
        check_exports(lib)
        # The programs run with the library found through the RPATH CMake gave them, not the environment.
        env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}

        # (1) The consumer: the .msh it writes through the API is the command line's, byte for byte.
        configure_build(args, here, os.path.join(tmp, "consumer"), prefix)
        app = os.path.join(tmp, "consumer", "app")
        ldd = shutil.which("ldd")
        if ldd:
            linked = subprocess.run([ldd, app], capture_output=True, text=True, env=env).stdout
            line = next((l for l in linked.splitlines() if "libcurvemesh.so" in l), "")
            if os.path.realpath(prefix) not in line and prefix not in line:
                raise Failure(f"app does not load the installed library: {line.strip() or linked}")
        api_msh, cli_msh = os.path.join(tmp, "api.msh"), os.path.join(tmp, "cli.msh")
        run([app, drawing, api_msh], env=env)
        run([os.path.join(prefix, "bin", "curvemesh"), "mesh", drawing, "-o", cli_msh, "-q"], env=env)
        if not filecmp.cmp(api_msh, cli_msh, shallow=False):
            raise Failure(f"the consumer's .msh differs from `curvemesh mesh {drawing}`")
        print("consumer: .msh byte-identical to `curvemesh mesh`")

        # (2) README.md's example, as it stands.
        cmake_text, cpp_text = readme_example(os.path.join(args.source, "README.md"))
        example = os.path.join(tmp, "readme-example")
        os.makedirs(example)
        with open(os.path.join(example, "CMakeLists.txt"), "w") as f:
            f.write(cmake_text)
        with open(os.path.join(example, "main.cpp"), "w") as f:
            f.write(cpp_text)
        configure_build(args, example, os.path.join(example, "build"), prefix)
        run([os.path.join(example, "build", "app"), drawing, os.path.join(tmp, "readme.msh")], env=env)
        run([os.path.join(prefix, "bin", "curvemesh"), "check", os.path.join(tmp, "readme.msh")], env=env)
        print("README example: built and ran")
    except (Failure, subprocess.TimeoutExpired, OSError) as e:
        print(f"FAILED: {e}")
        return 1
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
