# End-to-end bad-input cases of the `bounce` CLI: each must exit non-zero with exactly one line on
# stderr naming what is wrong, and leave no output file behind. Run by ctest (cli_bad_input).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(failures 0)

function(expect_failure name expected_text output)
  execute_process(COMMAND ${BOUNCE} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err_stripped)
  string(REGEX MATCHALL "\n" newlines "${err_stripped}")
  list(LENGTH newlines extra_lines)
  set(ok TRUE)
  if(rc EQUAL 0)
    message(SEND_ERROR "${name}: expected a non-zero exit, got 0")
    set(ok FALSE)
  endif()
  if(NOT extra_lines EQUAL 0)
    message(SEND_ERROR "${name}: expected a one-line error, got:\n${err}")
    set(ok FALSE)
  endif()
  string(FIND "${err}" "${expected_text}" pos)
  if(pos EQUAL -1)
    message(SEND_ERROR "${name}: error does not mention '${expected_text}':\n${err}")
    set(ok FALSE)
  endif()
  if(NOT "${output}" STREQUAL "" AND EXISTS "${output}")
    message(SEND_ERROR "${name}: left an output file ${output}")
    set(ok FALSE)
  endif()
  if(ok)
    message(STATUS "ok: ${name}: ${err_stripped}")
  endif()
endfunction()

set(png ${WORK}/out.png)
expect_failure("unknown command" "frobnicate" "" frobnicate)
expect_failure("unknown technique" "unknown technique 'nope'" ${png}
               render --scene cornell-box --technique nope --size 8x8 --out ${png})
expect_failure("unknown scene" "no-such-scene" ${png} render --scene no-such-scene --size 8x8 --out ${png})
expect_failure("unknown setting" "unknown setting 'bogus'" ${png}
               render --scene cornell-box --technique ambient --set bogus=1 --size 8x8 --out ${png})
expect_failure("setting out of range" "out of range" ${png}
               render --scene cornell-box --set renderer.shadowMapSize=3 --size 8x8 --out ${png})
expect_failure("setting not a number" "expected a finite number" ${png}
               render --scene cornell-box --technique ambient --set radiance=abc --size 8x8 --out ${png})
expect_failure("setting without =" "name=value" ${png} render --scene cornell-box --set radiance --size 8x8 --out ${png})
expect_failure("other technique's setting" "another technique" ${png}
               render --scene cornell-box --technique direct --set ambient.radiance=1 --size 8x8 --out ${png})
expect_failure("vct resolution not a power of two" "power of two" ${png}
               render --scene cornell-box --technique vct --set resolution=48 --size 8x8 --out ${png})
expect_failure("vct storage unknown" "storage" ${png}
               render --scene cornell-box --technique vct --set storage=octree --size 8x8 --out ${png})
expect_failure("vct volumes over the memory budget" "memoryBudgetMiB" ${png}
               render --scene cornell-box --technique vct --set resolution=512 --set memoryBudgetMiB=64 --size 8x8 --out ${png})
expect_failure("zero size" "--size '0x8'" ${png} render --scene cornell-box --size 0x8 --out ${png})
expect_failure("malformed size" "--size 'big'" ${png} render --scene cornell-box --size big --out ${png})
expect_failure("zero frames" "--frames 0" ${png} render --scene cornell-box --frames 0 --size 8x8 --out ${png})
expect_failure("negative start frame" "--start-frame -1 must not be negative" ${png} render --scene cornell-box --start-frame -1 --size 8x8 --out ${png})
expect_failure("radiosity with a textured area light" "area light 'screen' is textured" ${png} render --scene area-screen --technique radiosity-pr --size 8x8 --out ${png})
expect_failure("bad component" "unknown component" ${png}
               render --scene cornell-box --component both --size 8x8 --out ${png})
expect_failure("bad output extension" "unsupported image extension" ${WORK}/out.bmp
               render --scene cornell-box --size 8x8 --out ${WORK}/out.bmp)
expect_failure("output folder missing" "does not exist" ${WORK}/missing/out.png
               render --scene cornell-box --size 8x8 --out ${WORK}/missing/out.png)
expect_failure("stats folder missing" "does not exist" ${png}
               render --scene cornell-box --size 8x8 --out ${png} --stats ${WORK}/missing/run.json)
expect_failure("missing scene file" "not found" ${png} render --scene ${WORK}/absent.json --size 8x8 --out ${png})
file(WRITE ${WORK}/malformed.json "{ \"objects\": [ 1, 2,\n")
expect_failure("malformed scene file" "malformed.json" ${png} render --scene ${WORK}/malformed.json --size 8x8 --out ${png})
file(WRITE ${WORK}/garbage.obj "v 0 0 0\nv nan 1 0\nv 1 0 0\nf 1 2 3\n")
expect_failure("NaN in a model" "garbage.obj" ${png} render --scene ${WORK}/garbage.obj --size 8x8 --out ${png})
file(WRITE ${WORK}/degenerate.obj "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n")
expect_failure("degenerate geometry" "degenerate" ${png} render --scene ${WORK}/degenerate.obj --size 8x8 --out ${png})
file(WRITE ${WORK}/tri.obj "v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n")
file(WRITE ${WORK}/screen.json "{\"objects\": [{\"model\": \"tri.obj\"}],\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]},\n\"lights\": [{\"type\": \"area\", \"position\": [0, 1, 0], \"edgeU\": [1, 0, 0], \"edgeV\": [0, 0, 1], \"radiance\": 1,\n  \"texture\": \"absent.png\"}]}\n")
expect_failure("area light texture missing" "screen.json:4: light 'light-0': texture" ${png}
               render --scene ${WORK}/screen.json --size 8x8 --out ${png})
file(WRITE ${WORK}/square.json "{\"objects\": [{\"model\": \"tri.obj\"}],\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]},\n\"lights\": [{\"type\": \"area\", \"position\": [0, 1, 0], \"edgeU\": [1, 0, 0], \"edgeV\": [0, 0, 1], \"radiance\": 1,\n  \"texture\": {\"pattern\": \"bouncing-square\", \"size\": 0}}]}\n")
expect_failure("bouncing square of size 0" "square.json:4: light 'light-0': square size" ${png}
               reference --scene ${WORK}/square.json --size 8x8 --spp 1 --out ${png})
expect_failure("unknown scene parameter" "triangles" ${png}
               render --scene cornell-box --scene-param triangles=5 --size 8x8 --out ${png})
expect_failure("compare missing file" "not found" "" compare ${WORK}/a.exr ${WORK}/b.exr)

# A good run writes the image and the run record.
execute_process(COMMAND ${BOUNCE} render --scene cornell-box --size 16x16 --out ${png} --stats ${WORK}/run.json
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${png} OR NOT EXISTS ${WORK}/run.json)
  message(SEND_ERROR "good render failed (${rc}): ${err}")
endif()
file(WRITE ${WORK}/small.exr "")
execute_process(COMMAND ${BOUNCE} render --scene cornell-box --size 8x8 --out ${WORK}/small.exr RESULT_VARIABLE rc)
expect_failure("compare different sizes" "size" "" compare ${png} ${WORK}/small.exr)

# bounce photon-map: flags checked before any work, one line, no output left.
expect_failure("photon-map k 1" "--k" ${WORK}/pm.exr photon-map --scene cornell-box --size 8x8 --k 1 --out ${WORK}/pm.exr)
expect_failure("photon-map no photons" "--photons" ${WORK}/pm.exr photon-map --scene cornell-box --photons 0 --out ${WORK}/pm.exr)
expect_failure("photon-map bad stats" "JSON" ${WORK}/pm.exr photon-map --scene cornell-box --size 8x8 --out ${WORK}/pm.exr --stats ${WORK}/pm.txt)
expect_failure("photon-map missing folder" "does not exist" "" photon-map --scene cornell-box --out ${WORK}/none/pm.exr)

# What a new user tripped over (issue "Reliability"): errors name the key and what was found; the spot
# cutoff's range is (0, 180] as documented; scene-file settings are checked whatever runs.
file(WRITE ${WORK}/keys.json "{\"objects\": [{\"model\": \"tri.obj\", \"material\": \"m\"}],\n\"materials\": {\"m\": {\"roughness\": \"rough\"}},\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]}}\n")
expect_failure("string for a number" "materials/m/roughness: expected a number, got the string \"rough\"" ${WORK}/nu.png
               render --scene ${WORK}/keys.json --size 8x8 --out ${WORK}/nu.png)
file(WRITE ${WORK}/albedo.json "{\"objects\": [{\"model\": \"tri.obj\", \"material\": \"m\"}],\n\"materials\": {\"m\": {\"baseColor\": -0.4}},\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]}}\n")
expect_failure("albedo out of range" "albedo.json:2: materials/m/baseColor: value -0.4 is outside [0, 1]" ${WORK}/nu.png
               render --scene ${WORK}/albedo.json --size 8x8 --out ${WORK}/nu.png)
file(WRITE ${WORK}/cutoff.json "{\"objects\": [{\"model\": \"tri.obj\"}],\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]},\n\"lights\": [{\"type\": \"spot\", \"position\": [0, 1, 0], \"direction\": [0, -1, 0], \"intensity\": 1,\n  \"cutoffDegrees\": 0}]}\n")
expect_failure("spot cutoff 0" "cutoff.json:4: lights/0/cutoffDegrees: light 'light-0': value 0 is outside (0, 180]" ${WORK}/nu.png
               render --scene ${WORK}/cutoff.json --size 8x8 --out ${WORK}/nu.png)
file(WRITE ${WORK}/typo.json "{\"objects\": [{\"model\": \"tri.obj\"}],\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]},\n\"settings\": {\"rsm.vplgrid\": 8}}\n")
expect_failure("scene setting typo under direct" "typo.json:3: setting \"rsm.vplgrid\"" ${WORK}/nu.png
               render --scene ${WORK}/typo.json --technique direct --size 8x8 --out ${WORK}/nu.png)
expect_failure("scene setting typo under reference" "unknown setting 'vplgrid'" ${WORK}/ref.exr
               reference --scene ${WORK}/typo.json --size 8x8 --spp 1 --out ${WORK}/ref.exr)
file(WRITE ${WORK}/notech.json "{\"objects\": [{\"model\": \"tri.obj\"}],\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]},\n\"settings\": {\"rsmm.vplGrid\": 8}}\n")
expect_failure("scene setting of an unknown technique" "rsmm" ${WORK}/nu.png
               render --scene ${WORK}/notech.json --size 8x8 --out ${WORK}/nu.png)

# A light of zero power: render and reference agree (both refuse, naming the scene).
file(WRITE ${WORK}/dark.json "{\"objects\": [{\"model\": \"tri.obj\"}],\n\"camera\": {\"position\": [0, 1, 3], \"target\": [0, 0, 0]},\n\"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": 0}]}\n")
expect_failure("render with a dark light" "no light source" ${WORK}/nu.png render --scene ${WORK}/dark.json --size 8x8 --out ${WORK}/nu.png)
expect_failure("reference with a dark light" "no light source" ${WORK}/ref.exr
               reference --scene ${WORK}/dark.json --size 8x8 --spp 1 --out ${WORK}/ref.exr)

# bounce reference prints its one-line summary on success (docs/reference.md), at the default log level.
execute_process(COMMAND ${BOUNCE} reference --scene cornell-box --size 8x8 --spp 2 --out ${WORK}/ref.exr
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^reference: cornell-box 8x8, 2 spp in [0-9.]+ s \\([0-9.]+ M paths/s, [0-9.]+ M rays/s\\); noise [0-9.]+% per pixel, [0-9.]+% image mean; wrote .*ref.exr\n$")
  message(SEND_ERROR "reference summary line missing or malformed (${rc}): '${out}' ${err}")
endif()

# bounce render --camera-path and bounce view --script: input checked before any rendering or window.
set(frame0 ${WORK}/rp_0000.png)
set(key "{\"time\": 0, \"position\": [0.278, 0.273, -0.8], \"target\": [0.278, 0.273, 0.2]}")
file(WRITE ${WORK}/path.json "{\"format\": \"bounce-camera-path\", \"version\": 1, \"keys\": [${key}]}\n")
expect_failure("camera path without a frame pattern" "needs exactly one %d" ${WORK}/cp.png
               render --scene cornell-box --size 8x8 --camera-path ${WORK}/path.json --out ${WORK}/cp.png)
expect_failure("camera path with --frames" "drop --frames" ${frame0}
               render --scene cornell-box --size 8x8 --camera-path ${WORK}/path.json --frames 3 --out ${WORK}/rp_%04d.png)
expect_failure("camera path missing" "nopath.json" ${frame0}
               render --scene cornell-box --size 8x8 --camera-path ${WORK}/nopath.json --out ${WORK}/rp_%04d.png)
file(WRITE ${WORK}/badpath.json "{\"format\": \"bounce-camera-path\", \"version\": 1, \"keys\": [{\"time\": 0}]}\n")
expect_failure("camera path key without position" "badpath.json: key 0: 'position' is missing" ${frame0}
               render --scene cornell-box --size 8x8 --camera-path ${WORK}/badpath.json --out ${WORK}/rp_%04d.png)
file(WRITE ${WORK}/lightpath.json "{\"format\": \"bounce-camera-path\", \"version\": 1, \"keys\": [${key}],\n\"lights\": [{\"name\": \"lamp\", \"position\": [0, 0, 0], \"direction\": [0, -1, 0]}]}\n")
expect_failure("camera path names a light the scene lacks" "light 'lamp' is not in scene" ${frame0}
               render --scene cornell-box --size 8x8 --camera-path ${WORK}/lightpath.json --out ${WORK}/rp_%04d.png)
file(WRITE ${WORK}/bad-script.txt "# comment\nab split\nfrobnicate 3\n")
expect_failure("viewer script unknown action" "bad-script.txt:3: unknown action 'frobnicate'" ""
               view --scene cornell-box --script ${WORK}/bad-script.txt)
file(WRITE ${WORK}/bad-number.txt "wait many\n")
expect_failure("viewer script bad number" "bad-number.txt:1: 'wait': argument 1 'many' is not a number" ""
               view --scene cornell-box --script ${WORK}/bad-number.txt)
file(WRITE ${WORK}/bad-count.txt "orbit 1 2\n")
expect_failure("viewer script argument count" "'orbit' takes 3 argument(s)" "" view --scene cornell-box --script ${WORK}/bad-count.txt)
expect_failure("viewer bad render size" "--render-size '0x3'" "" view --scene cornell-box --render-size 0x3)
expect_failure("viewer unknown viewer setting" "unknown setting 'bogus'" "" view --scene cornell-box --set viewer.bogus=1)
# A good replay writes every frame of the path (one key: frame 0 only).
execute_process(COMMAND ${BOUNCE} render --scene cornell-box --size 8x8 --camera-path ${WORK}/path.json --out ${WORK}/rp_%04d.png
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${frame0} OR EXISTS ${WORK}/rp_0001.png)
  message(SEND_ERROR "good camera-path replay failed (${rc}): ${err}")
endif()

# A one-sided surface wound away from the camera and the light (docs/scene.md "One-sided or
# two-sided"): the render succeeds and warns, one line per finding, naming the file and the object.
file(WRITE ${WORK}/down.obj "v 0 0 0\nv 0 0 -1\nv 1 0 0\nv 1 0 -1\nf 1 2 3\nf 3 2 4\n")
file(WRITE ${WORK}/reversed.json "{\"objects\": [{\"name\": \"floor\", \"model\": \"down.obj\", \"material\": \"m\", \"transform\": {\"scale\": 4, \"translation\": [-2, 0, 2]}}],\n\"materials\": {\"m\": {\"twoSided\": false}},\n\"camera\": {\"position\": [0, 2, 2], \"target\": [0, 0, 0]},\n\"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": 1}]}\n")
execute_process(COMMAND ${BOUNCE} render --scene ${WORK}/reversed.json --size 16x16 --out ${WORK}/reversed.png
                RESULT_VARIABLE rc ERROR_VARIABLE err)
string(REGEX MATCHALL "\n" newlines "${err}")
list(LENGTH newlines lines)
if(NOT rc EQUAL 0 OR NOT lines EQUAL 2
   OR NOT err MATCHES "reversed.json: object 'floor' is one-sided and seen from behind over [0-9]+% of the image"
   OR NOT err MATCHES "reversed.json: object 'floor' is one-sided and every light is behind it")
  message(SEND_ERROR "one-sided warning missing or malformed (${rc}):\n${err}")
endif()
