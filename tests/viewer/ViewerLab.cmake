# The viewer as a lab bench, end to end under Xvfb (ctest: view_lab): a scripted session
# (tests/viewer/lab.txt) switches techniques, moves the light, compares A/B side by side and as a
# wipe with the heat map, records a two-key camera path, shows debug views and renders the background
# reference; then `bounce render --camera-path` replays the path and this script checks the results.
# Inputs: -DBOUNCE=... -DCHECK=bounce_image_check -DXVFB_RUN=... -DSCRIPT=lab.txt -DWORK=folder
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(failures 0)

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
run("viewer session" ${XVFB_RUN} -a -s "-screen 0 1024x768x24" ${BOUNCE} view --scene cornell-box-dynamic
    --size 880x560 --render-size 256x256 --script ${SCRIPT})
run("replay" ${BOUNCE} render --scene cornell-box-dynamic --technique rsm --size 256x256
    --camera-path path.json --out replay_%04d.exr)

foreach(f split-same.png split-ab.png viewer-split.png viewer-wipe-heatmap.png view-normal.png view-rsm-flux.png
          viewer-reference.png shot.exr reference.exr path.json metrics-ab.json replay_0000.exr replay_0004.exr replay_0008.exr)
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
run("A = B: halves equal" ${CHECK} halves ${WORK}/split-same.png 0 0.001)
run("direct | rsm: halves differ" ${CHECK} halves ${WORK}/split-ab.png 0.003 1)
# Moving the light changes the image.
run("light moved" ${CHECK} differ ${WORK}/light-after.exr ${WORK}/light-before.exr 1e-4 1e30)
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
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} viewer checks failed")
endif()
