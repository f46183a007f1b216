# `bounce sweep` study files with mistakes (ctest study_bad_input): each must fail before any job,
# with one line naming the file, its line, the key and the known values, and create no output folder.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_study_failure name expected_text json)
  set(study ${WORK}/${name}.json)
  file(WRITE ${study} "${json}")
  execute_process(COMMAND ${BOUNCE} sweep ${study} --out ${WORK}/out-${name} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err_stripped)
  string(REGEX MATCHALL "\n" newlines "${err_stripped}")
  list(LENGTH newlines extra_lines)
  if(rc EQUAL 0)
    message(SEND_ERROR "${name}: expected a non-zero exit, got 0")
  elseif(NOT extra_lines EQUAL 0)
    message(SEND_ERROR "${name}: expected a one-line error, got:\n${err}")
  elseif(EXISTS ${WORK}/out-${name})
    message(SEND_ERROR "${name}: created the output folder")
  else()
    string(FIND "${err}" "${expected_text}" pos)
    if(pos EQUAL -1)
      message(SEND_ERROR "${name}: error does not mention '${expected_text}':\n${err}")
    else()
      message(STATUS "ok: ${name}: ${err_stripped}")
    endif()
  endif()
endfunction()

set(scenes "\"scenes\": [\"cornell-box\"]")
expect_study_failure(unknown_key "unknown_key.json:2: sceens: unknown key 'sceens' (known: name, output, size"
  "{\"name\": \"x\",\n \"sceens\": [\"cornell-box\"], \"techniques\": [\"direct\"]}")
expect_study_failure(unknown_technique "unknown_technique.json:3: techniques[1]: unknown technique 'rsmm' (known: direct, ambient"
  "{${scenes},\n \"techniques\": [\"direct\",\n \"rsmm\"]}")
expect_study_failure(unknown_setting "unknown_setting.json:3: techniques[0].grid.vplGird[0]: technique 'rsm': unknown setting 'vplGird' (known:"
  "{${scenes},\n \"techniques\": [{\"name\": \"rsm\",\n \"grid\": {\"vplGird\": [8, 16]}}]}")
expect_study_failure(setting_out_of_range "techniques[0].grid.radiance[1]: technique 'ambient'"
  "{${scenes}, \"techniques\": [{\"name\": \"ambient\", \"grid\": {\"radiance\": [0.1, -5]}}]}")
expect_study_failure(unknown_technique_key "techniques[0].gird: unknown key 'gird' (known: name, settings, grid, list, scope)"
  "{${scenes}, \"techniques\": [{\"name\": \"ambient\", \"gird\": {}}]}")
expect_study_failure(unknown_scene "scenes[0]: unknown built-in scene 'cornel-box' (known: cornell-box"
  "{\"scenes\": [\"cornel-box\"], \"techniques\": [\"direct\"]}")
expect_study_failure(unknown_scene_param "scenes[0]"
  "{\"scenes\": [{\"name\": \"atrium\", \"params\": {\"triangels\": 5}}], \"techniques\": [\"direct\"]}")
expect_study_failure(missing_scene_file "file not found"
  "{\"scenes\": [{\"file\": \"nowhere.json\"}], \"techniques\": [\"direct\"]}")
expect_study_failure(bad_size "size: --size 'big'" "{${scenes}, \"techniques\": [\"direct\"], \"size\": \"big\"}")
expect_study_failure(bad_spp "reference.spp: 0 is not an integer" "{${scenes}, \"techniques\": [\"direct\"], \"reference\": {\"spp\": 0}}")
expect_study_failure(unknown_reference_key "reference.samples: unknown key 'samples' (known: spp, timeLimit, seed, threads)"
  "{${scenes}, \"techniques\": [\"direct\"], \"reference\": {\"samples\": 4}}")
expect_study_failure(bad_scope_component "techniques[0].scope.component: unknown component"
  "{${scenes}, \"techniques\": [{\"name\": \"rsm\", \"scope\": {\"component\": \"glossy\"}}]}")
expect_study_failure(temporal_unknown_technique "temporal.techniques[0]: 'iir' is not a technique of this study (known: direct)"
  "{${scenes}, \"techniques\": [\"direct\"], \"temporal\": {\"techniques\": [\"iir\"]}}")
expect_study_failure(temporal_one_frame "temporal.frames: 1 is not an integer in [2"
  "{${scenes}, \"techniques\": [\"direct\"], \"temporal\": {\"frames\": 1}}")
expect_study_failure(temporal_unknown_animation "temporal.animation: unknown animation 'pause' (known: play, hold, step)"
  "{${scenes}, \"techniques\": [\"direct\"], \"temporal\": {\"frames\": 4, \"eventFrame\": 2, \"animation\": \"pause\"}}")
expect_study_failure(temporal_step_without_event "temporal.animation: animation 'step' needs an eventFrame after startFrame 0"
  "{${scenes}, \"techniques\": [\"direct\"], \"temporal\": {\"frames\": 4, \"animation\": \"step\"}}")
expect_study_failure(temporal_event_after_run "temporal.eventFrame: 3 is not an integer in [0, 2]"
  "{${scenes}, \"techniques\": [\"direct\"], \"temporal\": {\"frames\": 4, \"eventFrame\": 3, \"animation\": \"hold\"}}")
# A scene file whose leak regions are wrong is refused while the study is read, naming both files.
file(WRITE ${WORK}/floor.obj "v -2 0 -1\nv 2 0 -1\nv 2 0 1\nv -2 0 1\nf 1 4 3\nf 1 3 2\n")
file(WRITE ${WORK}/leaky.json "{\"objects\": [{\"model\": \"floor.obj\"}],\n \"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": 1}],\n \"camera\": {\"position\": [0, 4, 0.1], \"target\": [0, 0, 0]},\n \"leakRegions\": {\"dark\": {\"min\": [0, -1, -1], \"max\": [2, 1, 1]},\n   \"lit\": {\"min\": [-2, -1, -1], \"max\": [0.5, 1, 1]}}}\n")
expect_study_failure(scene_file_leak_overlap "scene_file_leak_overlap.json:1: scenes[0]: ${WORK}/leaky.json:5: leakRegions: the dark and the lit boxes overlap"
  "{\"scenes\": [{\"file\": \"leaky.json\"}], \"techniques\": [\"direct\"]}")
expect_study_failure(wildcard_technique_setting "techniques[0]: technique 'direct': unknown setting 'radiance'"
  "{${scenes}, \"techniques\": [{\"name\": \"*\", \"grid\": {\"radiance\": [1]}}]}")
expect_study_failure(malformed "malformed.json:2:" "{${scenes},\n \"techniques\": [\"direct\",]}")
expect_study_failure(missing_techniques "missing 'techniques'" "{${scenes}}")
expect_study_failure(unknown_emit "--emit: unknown scheduler 'condor' (known: parallel, slurm)"
  "{${scenes}, \"techniques\": [\"direct\"]}" --emit condor)
expect_study_failure(unknown_job "--job 'render/x': no such job" "{${scenes}, \"techniques\": [\"direct\"]}" --job render/x)
execute_process(COMMAND ${BOUNCE} sweep ${WORK}/nonexistent.json RESULT_VARIABLE rc ERROR_VARIABLE err)
string(FIND "${err}" "nonexistent.json" pos)
if(rc EQUAL 0 OR pos EQUAL -1)
  message(SEND_ERROR "missing study file: expected an error naming it, got ${rc}: ${err}")
endif()
