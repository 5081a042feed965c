"""The harness the command-line tests share: named checks that record failures instead of
stopping at the first, and one summary line and exit status at the end; the PNG reader of
scripts/region-agreement for the tests that measure a rendering."""
import importlib.machinery
import importlib.util
import os
import sys

failures = []
passed = 0


def check(name, condition, detail=""):
    global passed
    if condition:
        passed += 1
    else:
        failures.append(f"{name}: {detail}")
        print(f"FAIL {name}: {detail}")


def finish():
    print(f"{passed} checks passed, {len(failures)} failed")
    sys.exit(1 if failures else 0)


def read_png(path):
    """An (H, W, 4) uint8 array of a PNG file: scripts/region-agreement's reader (numpy and zlib)."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "region-agreement")
    loader = importlib.machinery.SourceFileLoader("region_agreement", script)
    spec = importlib.util.spec_from_loader("region_agreement", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module.read_png(path)
