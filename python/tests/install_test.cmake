# ctest python_install: `cmake --install` puts a working package under a fresh prefix.
#   cmake -DBUILD=build -DWORK=dir -DPYTHON=/usr/bin/python3 -DSITE=lib/python3.11/dist-packages -P install_test.cmake
# The installed module (not the build tree's) renders, path-traces and compares.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --component python --prefix ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${out}${err}")
endif()
foreach(file _bounce __init__.py __init__.pyi py.typed)
  file(GLOB found ${WORK}/${SITE}/bounce/${file}*)
  if(NOT found)
    message(FATAL_ERROR "cmake --install did not install bounce/${file}* under ${WORK}/${SITE}")
  endif()
endforeach()
set(script [=[
import os, sys
import bounce
where = os.path.realpath(bounce.__file__)
assert where.startswith(os.path.realpath(sys.argv[1])), f"imported {where}, not the installed copy"
ref = bounce.reference("cornell-box", 16, spp=4)
try:
    image, record = bounce.Renderer("cornell-box", "direct", 16).frame(0)
except bounce.Error as e:
    if os.environ.get("CI") == "true":
        raise
    print(f"no GL context ({e}); rendering not checked")
    image = ref.image
result = bounce.compare(image, ref)
assert image.shape == (16, 16, 3) and result["relMse"] >= 0 and "floor" in result
print(f"installed bounce at {where}: relMse {result['relMse']:.4f}")
]=])
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK}/${SITE} ${PYTHON} -c "${script}" ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed module failed (${rc})")
endif()
