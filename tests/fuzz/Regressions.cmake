# The fuzzers' regression inputs (tests/fuzz/regressions, docs/reliability.md "Fuzzing") through the
# `bounce` command line of the ordinary build (ctest fuzz_regressions_cli): every scene, model and study
# file must end in one error line naming it, exit 1 and write nothing; the images that once aborted
# `bounce compare --heatmap` must now compare. Each command runs under a timeout: some inputs used to hang.
# Run: cmake -DBOUNCE=build/src/app/bounce -DREGRESSIONS=tests/fuzz/regressions -DWORK=/tmp/w -P Regressions.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_clean_error file output)
  execute_process(COMMAND ${BOUNCE} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
  string(STRIP "${err}" err_stripped)
  string(REGEX MATCHALL "\n" newlines "${err_stripped}")
  list(LENGTH newlines extra_lines)
  string(FIND "${err}" "${file}" named)
  if(NOT rc EQUAL 1)
    message(SEND_ERROR "${file}: expected exit 1, got '${rc}'\n${err}")
  elseif(NOT extra_lines EQUAL 0 OR named EQUAL -1)
    message(SEND_ERROR "${file}: expected one error line naming the file, got:\n${err}")
  elseif(EXISTS "${output}")
    message(SEND_ERROR "${file}: left ${output} behind")
  else()
    message(STATUS "ok: ${err_stripped}")
  endif()
endfunction()

file(GLOB scene_inputs ${REGRESSIONS}/scene/* ${REGRESSIONS}/model/*)
foreach(f ${scene_inputs})
  expect_clean_error(${f} ${WORK}/out.exr reference --scene ${f} --size 8x8 --spp 1 --out ${WORK}/out.exr)
endforeach()
file(GLOB study_inputs ${REGRESSIONS}/study/*)
foreach(f ${study_inputs})
  expect_clean_error(${f} ${WORK}/study sweep ${f} --out ${WORK}/study --list)
endforeach()

file(GLOB image_inputs ${REGRESSIONS}/image/oversized-*)
foreach(f ${image_inputs})
  expect_clean_error(${f} ${WORK}/heatmap.png compare ${f} ${f} --heatmap ${WORK}/heatmap.png)
endforeach()

# |3e38 - (-3e38)| overflows float: the heat map's colour bar used to be infinite and abort.
foreach(metric abs relmse flip)
  set(heatmap ${WORK}/heatmap-${metric}.png)
  execute_process(COMMAND ${BOUNCE} compare ${REGRESSIONS}/image/huge-test.exr ${REGRESSIONS}/image/huge-reference.exr
                  --heatmap ${heatmap} --heatmap-metric ${metric} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 60)
  if(NOT rc EQUAL 0 OR NOT EXISTS ${heatmap})
    message(SEND_ERROR "compare --heatmap-metric ${metric} of huge-test.exr and huge-reference.exr: exit '${rc}', no heat map\n${err}")
  else()
    message(STATUS "ok: compare --heatmap-metric ${metric} of the overflowing pair")
  endif()
endforeach()
