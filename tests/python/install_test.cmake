# `cmake --install` of the build into a scratch prefix, then the installed Python package imported
# from there alone: it must load the installed libcurvemesh.so (through its RPATH), not the build
# tree's, and mesh a drawing.
#   cmake -DBUILD_DIR=build -DPREFIX=/tmp/p -DPYTHON=/usr/bin/python3 -DPYTHON_DIR=lib/python3/dist-packages
#         -DEXAMPLE=examples/square-with-hole.svg -P install_test.cmake
foreach(var BUILD_DIR PREFIX PYTHON PYTHON_DIR EXAMPLE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_test.cmake: -D${var}=... is missing")
  endif()
endforeach()

file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
                OUTPUT_QUIET RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${err}")
endif()

set(script [=[
import pathlib, sys
prefix = pathlib.Path(sys.argv[1]).resolve()
import curvemesh
where = pathlib.Path(curvemesh.__file__).resolve()
assert prefix in where.parents, f"curvemesh imported from {where}, not from {prefix}"
loaded = {line.split()[-1] for line in open("/proc/self/maps") if "libcurvemesh" in line}
assert loaded, "no libcurvemesh loaded"
for path in loaded:
    assert prefix in pathlib.Path(path).resolve().parents, f"{path} loaded, not the installed library"
m = curvemesh.mesh(sys.argv[2], linear=True)
assert len(m.triangles) > 0
print(f"curvemesh {curvemesh.__version__} from {where.parent}, library {sorted(loaded)}: "
      f"{len(m.triangles)} triangles")
]=])
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH PYTHONPATH=${PREFIX}/${PYTHON_DIR}
                        ${PYTHON} -c "${script}" ${PREFIX} ${EXAMPLE}
                WORKING_DIRECTORY ${PREFIX} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed module failed: ${err}")
endif()
