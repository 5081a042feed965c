#!/usr/bin/python3
"""Every public name of include/curvemesh/*.hpp is documented: Doxygen (docs/Doxyfile, through
docs/doxygen-filter.py) runs over the headers with every warning an error, into a scratch folder.

First it shows that the check bites: a made-up header with one documented and one undocumented
function must fail, naming the undocumented one, and the same header with a comment added must
pass. Then the real headers must pass with no warning at all.

usage: doxygen_check.py SOURCE_DIR [--doxygen doxygen]
exit 0 when the headers are documented, 1 when not (or the check does not bite), 2 when Doxygen
cannot run.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("source", help="the repository (docs/Doxyfile, include/curvemesh)")
parser.add_argument("--doxygen", default="doxygen")
args = parser.parse_args()

doxygen = shutil.which(args.doxygen)
if not doxygen:
    print(f"doxygen_check: {args.doxygen} not found; scripts/install-deps.sh installs Debian's doxygen")
    sys.exit(2)

HEADER = """#pragma once
// A made-up public header.
#include <string>

namespace curvemesh {{

// Says hello.
int documented();
{comment}int undocumented(const std::string& name);

// What was kept and dropped.
struct Counts {{
  int kept = 0;  // what stayed
  int dropped = 0;  // what went
}};

}}  // namespace curvemesh
"""


def run(headers, output):
    env = dict(os.environ, CURVEMESH_SOURCE_DIR=os.path.abspath(args.source),
               CURVEMESH_DOXYGEN_INPUT=headers, CURVEMESH_DOXYGEN_OUTPUT=output)
    r = subprocess.run([doxygen, os.path.join(args.source, "docs", "Doxyfile")], env=env, capture_output=True,
                       text=True, timeout=300)
    return r.returncode, (r.stdout + r.stderr).strip()


failures = []
with tempfile.TemporaryDirectory() as tmp:
    made_up = os.path.join(tmp, "made-up")
    os.makedirs(made_up)
    header = os.path.join(made_up, "made_up.hpp")

    with open(header, "w") as f:
        f.write(HEADER.format(comment=""))
    code, text = run(made_up, os.path.join(tmp, "out1"))
    bites = code != 0 and "undocumented" in text and "documented()" not in text.replace("undocumented", "")
    print(f"{'ok' if bites else 'FAIL'}: an undocumented function fails the check (exit {code})")
    if not bites:
        failures.append("an undocumented function does not fail the check:\n" + text)

    with open(header, "w") as f:
        f.write(HEADER.format(comment="// Says hello to `name`; <use> and --options are text.\n"))
    code, text = run(made_up, os.path.join(tmp, "out2"))
    print(f"{'ok' if code == 0 else 'FAIL'}: the same header with a comment passes (exit {code})")
    if code != 0:
        failures.append("a documented header fails the check:\n" + text)

    headers = os.path.join(os.path.abspath(args.source), "include", "curvemesh")
    code, text = run(headers, os.path.join(tmp, "out3"))
    print(f"{'ok' if code == 0 and not text else 'FAIL'}: every public name of include/curvemesh/*.hpp is documented")
    if code != 0 or text:
        failures.append("include/curvemesh/*.hpp:\n" + text + "\n(document each name with a // comment above it "
                        "or after it on its line; docs/Doxyfile says how the comments are read)")

for failure in failures:
    print(failure)
print(f"{3 - len(failures)} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
