# The viewer as a lab bench, end to end under Xvfb (ctest: view_lab): a scripted session
# (tests/viewer/lab.txt) switches techniques, moves the light, compares A/B side by side and as a
# wipe with the heat map, records a two-key camera path, shows debug views and renders the background
# reference (and its restart when the camera moves), the frame-time graph; then `bounce render
# --camera-path` replays the path and this script checks the results. The radiosity techniques'
# hemicube views run on their own scene (tests/viewer/hemicubes.txt).
# Inputs: -DBOUNCE=... -DCHECK=bounce_image_check -DXVFB_RUN=... -DSCRIPT=lab.txt -DCONTROLS=controls.txt
#         -DHEMICUBES=hemicubes.txt -DWORK=folder
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(failures 0)

# xvfb-run with its own auth file (-f) makes no temporary folder: removing that folder failed now and
# then at exit (exit 5, "problem while cleaning up temporary directory", the program's status lost).
set(XVFB ${XVFB_RUN} -a -f ${WORK}/Xauthority)
function(run name)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(SEND_ERROR "${name}: exit ${rc}\n${out}\n${err}")
    math(EXPR f "${failures} + 1")
    set(failures ${f} PARENT_SCOPE)
  else()
    string(STRIP "${out}" out)
    message(STATUS "ok: ${name} ${out}")
  endif()
endfunction()

# 256x256 internal size, fixed, so the captures have the size the replay renders at.
run("viewer session" ${XVFB} -s "-screen 0 1024x1024x24" ${BOUNCE} view --scene cornell-box-dynamic
    --size 880x800 --render-size 256x256 --script ${SCRIPT})
run("replay" ${BOUNCE} render --scene cornell-box-dynamic --technique rsm --size 256x256
    --camera-path path.json --out replay_%04d.exr)

# Animation, bookmarks, adaptive size: a 660x300 window leaves a 330x300 view beside the panel.
run("viewer controls" ${XVFB} -s "-screen 0 1024x768x24" ${BOUNCE} view --scene cornell-box-dynamic
    --size 660x300 --set viewer.frameBudgetMs=1 --set viewer.minScale=0.5 --script ${CONTROLS})
# The radiosity techniques' hemicube views on an area-lit scene.
run("viewer hemicubes" ${XVFB} -s "-screen 0 1024x768x24" ${BOUNCE} view --scene cornell-box-rotating
    --size 700x400 --render-size 128x128 --script ${HEMICUBES})
# A script action that fails while running ends the viewer with one line naming the script line.
file(WRITE ${WORK}/bad.txt "wait 1\ntechnique nope\n")
execute_process(COMMAND ${XVFB} -s "-screen 0 1024x768x24" ${BOUNCE} view --scene cornell-box --size 320x240
                --script bad.txt WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc ERROR_VARIABLE err)
string(STRIP "${err}" err)
if(rc EQUAL 0 OR NOT err MATCHES "^bounce view: bad.txt:2: technique: unknown technique 'nope'[^\n]*$")
  message(SEND_ERROR "failing script action: expected exit 1 and one line naming bad.txt:2, got ${rc}: ${err}")
else()
  message(STATUS "ok: failing script action: ${err}")
endif()

foreach(f split-same.png split-ab.png viewer-split.png viewer-wipe-heatmap.png view-normal.png view-rsm-flux.png
          viewer-reference.png shot.exr shot.png reference.exr reference-orbit.exr path.json metrics-ab.json replay_0000.exr replay_0004.exr replay_0008.exr)
  if(NOT EXISTS ${WORK}/${f})
    message(SEND_ERROR "missing output ${f}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
if(EXISTS ${WORK}/replay_0009.exr)
  message(SEND_ERROR "the replay wrote frames past the path's last key (frame 8)")
endif()

# The screenshots show an image (a blank view has deviation 0; the Cornell box's walls and light give
# 0.08 in split-ab.png), and the halves of the side-by-side view are equal when both sides run rsm
# (the same pipeline twice; measured 1e-8, the bound 0.001 is a quarter of one 8-bit step) and differ
# when A is direct and B is rsm (the indirect light rsm adds: measured mean difference 0.009 of the
# display range over the whole half, letterbox included; required > 0.003, three times the bound for equal).
run("view non-blank" ${CHECK} nonblank ${WORK}/split-ab.png 0.02)
run("debug view non-blank" ${CHECK} nonblank ${WORK}/view-normal.png 0.02)
run("rsm flux view non-blank" ${CHECK} nonblank ${WORK}/view-rsm-flux.png 0.01)
# The VPL points are drawn over the image (256 VPLs as 7-pixel dots change far more than 1e-4).
run("vpl points drawn" ${CHECK} differ ${WORK}/view-vpl.png ${WORK}/view-image.png 1e-4 1e30)
run("A = B: halves equal" ${CHECK} halves ${WORK}/split-same.png 0 0.001)
run("direct | rsm: halves differ" ${CHECK} halves ${WORK}/split-ab.png 0.003 1)
# Moving the light changes the image.
run("light moved" ${CHECK} differ ${WORK}/light-after.exr ${WORK}/light-before.exr 1e-4 1e30)
# ...and so does moving the animated block.
run("object moved" ${CHECK} differ ${WORK}/object-after.exr ${WORK}/light-after.exr 1e-4 1e30)
# The replayed frames equal the viewer's frames at the key times: same GL implementation, the same
# camera bit for bit (keys are exact), the same light positions, a stateless technique. llvmpipe is
# deterministic (measured relMSE 0), so the tolerance (relMSE 1e-9) only allows for a float summation
# order, not a different camera or time (replay frame 7 against the viewer's frame 8 gives 1.0).
run("replay frame 0 = viewer" ${CHECK} differ ${WORK}/replay_0000.exr ${WORK}/path-0000.exr 0 1e-9)
run("replay frame 8 = viewer" ${CHECK} differ ${WORK}/replay_0008.exr ${WORK}/path-0008.exr 0 1e-9)
# ...and the two keys are different views (so the check above could fail).
run("the keys differ" ${CHECK} differ ${WORK}/path-0008.exr ${WORK}/path-0000.exr 1e-4 1e30)
# The background reference converged to something like rsm's image (4 spp: noisy, but a black or
# wrongly placed reference would give relMSE >> 1).
run("reference non-blank" ${CHECK} nonblank ${WORK}/reference.exr 0.01)
file(READ ${WORK}/metrics-reference.json ref_json)
string(JSON ref_relmse GET "${ref_json}" relMse)
if(NOT ref_relmse LESS 1.0)
  message(SEND_ERROR "rsm against the background reference: relMSE ${ref_relmse}, expected < 1")
else()
  message(STATUS "ok: rsm vs background reference relMSE ${ref_relmse}")
endif()
file(READ ${WORK}/metrics-ab.json ab_json)
string(JSON ab_relmse GET "${ab_json}" relMse)
string(JSON ab_flip GET "${ab_json}" flipLdr)
if(NOT ab_relmse GREATER 0 OR NOT ab_flip GREATER 0)
  message(SEND_ERROR "direct vs rsm: relMSE ${ab_relmse}, FLIP ${ab_flip}: expected both > 0")
else()
  message(STATUS "ok: direct vs rsm relMSE ${ab_relmse} FLIP ${ab_flip}")
endif()
# Playing at speed 2 for 5 displayed frames advances 10 frames; step 3 then adds 3; time = frame / 30.
function(expect_json file key expected)
  file(READ ${WORK}/${file} json)
  string(JSON value GET "${json}" ${ARGN})
  if(NOT "${value}" STREQUAL "${expected}")
    message(SEND_ERROR "${file} ${ARGN}: ${value}, expected ${expected}")
  else()
    message(STATUS "ok: ${file} ${ARGN} = ${value}")
  endif()
endfunction()
expect_json(animation.json frame 10 frame)
expect_json(animation.json playing OFF playing)
expect_json(step.json frame 13 frame)
# Every frame over a 1 ms budget: the scale falls to viewer.minScale and the internal size to half the
# view, in multiples of 8 (330x300 -> 168x152), keeping the view's aspect.
expect_json(adaptive.json scale 0.5 scale)
expect_json(adaptive.json width 168 renderSize 0)
expect_json(adaptive.json height 152 renderSize 1)
# goto restored the bookmarked camera (the scene's, x = 0.278 m) after the orbit moved it.
file(READ ${WORK}/adaptive.json json)
string(JSON cam_x GET "${json}" camera 0)
string(JSON cam_z GET "${json}" camera 2)
if(cam_x LESS 0.2779 OR cam_x GREATER 0.2781 OR cam_z LESS -0.8001 OR cam_z GREATER -0.7999)
  message(SEND_ERROR "goto start: camera at x ${cam_x}, z ${cam_z}; expected the bookmark's 0.278, -0.8")
endif()
file(READ ${WORK}/bookmarks.json json)
string(JSON mark GET "${json}" bookmarks 0 name)
if(NOT mark STREQUAL "start")
  message(SEND_ERROR "bookmarks.json: first bookmark '${mark}', expected 'start'")
endif()
expect_json(overlap.json view photon-splat.overlap view)
# Screenshots: the PNG is the view as displayed (880x800 window minus the 340-pixel panel), the EXR
# side A's radiance at the render size.
run("screenshot png size" ${CHECK} size ${WORK}/shot.png 540 800)
run("screenshot exr size" ${CHECK} size ${WORK}/shot.exr 256 256)
run("screenshot png non-blank" ${CHECK} nonblank ${WORK}/shot.png 0.02)
run("screenshot exr non-blank" ${CHECK} nonblank ${WORK}/shot.exr 0.01)
# The frame-time graph: it has bars for the frames shown (the lab shows far more than 10), and its
# rectangle in the window is not the plain background (stacked coloured bars; an empty graph is one
# colour, deviation 0; measured ~0.1).
file(READ ${WORK}/graph.json json)
string(JSON graph_frames GET "${json}" graph frames)
if(graph_frames LESS 10)
  message(SEND_ERROR "frame-time graph: ${graph_frames} frames, expected at least 10")
else()
  message(STATUS "ok: frame-time graph has ${graph_frames} frames")
endif()
foreach(i 0 1 2 3)
  string(JSON g${i} GET "${json}" graph rect ${i})
  string(REGEX REPLACE "\\..*" "" g${i} "${g${i}}")  # whole pixels
endforeach()
run("frame-time graph drawn" ${CHECK} nonblank ${WORK}/graph-window.png 0.03 ${g0} ${g1} ${g2} ${g3})
# The background reference restarted once for the orbited camera; the new one is of the new view
# (it differs from the first, and rsm of the new view is close to it, as rsm was to the first).
expect_json(reference-restart.json restarts 1 reference restarts)
run("reference restarted: a new image" ${CHECK} differ ${WORK}/reference-orbit.exr ${WORK}/reference.exr 0.05 1e30)
file(READ ${WORK}/metrics-reference-orbit.json json)
string(JSON orbit_relmse GET "${json}" relMse)
if(NOT orbit_relmse LESS 1.0)
  message(SEND_ERROR "rsm against the restarted reference: relMSE ${orbit_relmse}, expected < 1")
else()
  message(STATUS "ok: rsm vs the restarted reference relMSE ${orbit_relmse}")
endif()
# Debug views of photon-splat, hisr and the radiosity techniques (their data: tests/gpu/DebugViewsGpuTest.cpp).
# Points over the image change it (each dot is several pixels of yellow; 1e-4 as for vpl.points).
run("photon-splat bundles drawn" ${CHECK} differ ${WORK}/view-bundles.png ${WORK}/view-photon-image.png 1e-4 1e30)
run("hisr tree roots drawn" ${CHECK} differ ${WORK}/view-hisr-tree0.png ${WORK}/view-hisr-image.png 1e-4 1e30)
# ...and the two depths are different node sets (64 roots against 4096 nodes two levels down).
run("hisr tree depths differ" ${CHECK} differ ${WORK}/view-hisr-tree2.png ${WORK}/view-hisr-tree0.png 1e-4 1e30)
# Hemicube views show something (a black or single-colour view has deviation 0), and faces differ.
foreach(f hc-gather-radiosity hc-pr-id hc-pr-id-side hc-incremental-idold hc-cross-back)
  run("${f} non-blank" ${CHECK} nonblank ${WORK}/${f}.png 0.01)
endforeach()
run("hemicube faces differ" ${CHECK} differ ${WORK}/hc-pr-id-side.png ${WORK}/hc-pr-id.png 1e-3 1e30)
run("overlap view non-blank" ${CHECK} nonblank ${WORK}/view-overlap.png 0.01)

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} viewer checks failed")
endif()
