# cli_tests.cmake — end-to-end cases of the `tandem` command line, included
# from tests/CMakeLists.txt inside if(TARGET tandem). Each case runs tandem
# from the source tree (so scenes/... paths work) through cli_case.cmake and
# asserts the exit code (0 ok, 1 check failed, 2 bad usage or input) and the
# message. ctest names: "cli/<case>".
set(tandem_cli_case ${CMAKE_CURRENT_LIST_DIR}/cli_case.cmake)
set(tandem_cli_data ${CMAKE_CURRENT_LIST_DIR}/data)
set(tandem_cli_out ${CMAKE_CURRENT_BINARY_DIR}/cli-out)

# tandem_cli_test(NAME RC "ARG|ARG..." [OUT re] [ERR re] [NOT_ERR re] [EXISTS "f|f"] [SAME "ARG|..."])
function(tandem_cli_test name rc args)
  cmake_parse_arguments(PARSE_ARGV 3 arg "" "OUT;ERR;NOT_ERR;EXISTS;SAME" "")
  add_test(NAME "cli/${name}"
    COMMAND ${CMAKE_COMMAND} "-DTANDEM=$<TARGET_FILE:tandem>" "-DARGS=${args}" "-DRC=${rc}" "-DOUT=${arg_OUT}"
      "-DERR=${arg_ERR}" "-DNOT_ERR=${arg_NOT_ERR}" "-DEXISTS=${arg_EXISTS}" "-DSAME=${arg_SAME}" -P ${tandem_cli_case}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()

# --- usage, help ------------------------------------------------------------------
tandem_cli_test(no-command 2 "" ERR "A subcommand is required")
tandem_cli_test(unknown-command 2 "frobnicate" ERR "unknown command .frobnicate.")
tandem_cli_test(version 0 "version" OUT "^tandem [0-9]+\\.[0-9]+\\.[0-9]+")
tandem_cli_test(fixed-demo 0 "fixed-demo" OUT "Fingerprint of 200000 evaluations.*Physics preview")
tandem_cli_test(fixed-sqrt 0 "fixed|sqrt|2" OUT "1\\.4142135")
tandem_cli_test(fixed-bad-function 2 "fixed|cube|2" ERR "unknown function 'cube'")
foreach(command run render demo)
  tandem_cli_test(${command}-help 0 "${command}|--help" OUT "Examples:\n  tandem ${command}")
endforeach()
# `tandem peer` is an alias of `tandem session`: same help, same argument checks.
tandem_cli_test(peer-help 0 "peer|--help" OUT "Play one peer of a networked arena game over UDP.*tandem peer. is the same command"
  SAME "session|--help")
tandem_cli_test(peer-missing-endpoint 2 "peer|--peers|127.0.0.1:7000,127.0.0.1:7001" ERR "--endpoint is required")
tandem_cli_test(peer-in-command-list 0 "--help" OUT "session, peer")

# --- run ----------------------------------------------------------------------------
tandem_cli_test(run-pyramid 0 "run|scenes/pyramid.json|--ticks|90|--hash-every|30"
  OUT "211 bodies.*tick       30  hash 0x[0-9a-f]+\ntick       60  hash 0x[0-9a-f]+\n.*final tick 90  hash 0x[0-9a-f]+\n")
tandem_cli_test(run-quiet 0 "run|scenes/impulses.json|--ticks|30|--quiet" OUT "^final tick 30  hash 0x[0-9a-f]+\n$")
tandem_cli_test(run-json 0 "run|scenes/stack.json|--ticks|20|--json"
  OUT "^\\{\"scene\": \"scenes/stack.json\", \"ticks\": 20.*\"final_hash\": \"0x[0-9a-f]+\".*\"step_ms\": \\{\"median\"")
tandem_cli_test(run-json-global 0 "--json|run|scenes/stack.json|--ticks|5" OUT "\"final_tick\": 5")
tandem_cli_test(run-repeats 0 "run|scenes/impulses.json|--quiet" OUT "final tick 300"
  SAME "run|scenes/impulses.json|--quiet")
# --profile: the per-stage table / JSON object; reading the profile changes no hash.
tandem_cli_test(run-profile 0 "run|scenes/pyramid.json|--ticks|30|--profile"
  OUT "per-stage profile over 30 steps.*\nsolve +[0-9.]+ +[0-9.]+ .*\ntotal +[0-9.]+")
tandem_cli_test(run-profile-json 0 "run|scenes/stack.json|--ticks|10|--json|--profile"
  OUT "\"profile\": \\{\"broad_phase\": \\{\"median_ms\": [0-9.]+, \"mean_ms\": [0-9.]+\\}.*\"total\": \\{")
tandem_cli_test(run-profile-same-hash 0 "run|scenes/impulses.json|--quiet|--profile" OUT "final tick 300"
  SAME "run|scenes/impulses.json|--quiet")
tandem_cli_test(run-missing-scene-arg 2 "run" ERR "scene is required")
tandem_cli_test(run-bad-broadphase 2 "run|scenes/stack.json|--broadphase|quadtree" ERR "quadtree not in")
# A 142-byte scene asking for 10^6 bodies is refused before expansion; the
# limit is a global option, and raising it below the request still refuses.
tandem_cli_test(run-scene-over-body-limit 2 "run|${tandem_cli_data}/huge_grid.json"
  ERR "huge_grid.json: /generators/0: the grid generator asks for 1000 columns × 1000 rows = 1000000 bodies, over the limit of 100000 bodies per scene \\(raise it with --max-bodies")
tandem_cli_test(run-scene-max-bodies-flag 2 "run|${tandem_cli_data}/huge_grid.json|--max-bodies|999999"
  ERR "over the limit of 999999 bodies")
tandem_cli_test(run-scene-max-bodies-lowered 2 "--max-bodies|5|run|scenes/stack.json" ERR "asks for 1 columns × 12 rows = 12 bodies, on top of 1 before it, over the limit of 5")
tandem_cli_test(run-scene-max-shapes-flag 2 "run|scenes/pyramid.json|--max-shapes|100" ERR "over the limit of 100 shapes")
tandem_cli_test(run-negative-ticks 2 "run|scenes/stack.json|--ticks|-5" ERR "ticks")
tandem_cli_test(run-missing-file 2 "run|scenes/no-such-scene.json" ERR "no-such-scene.json: cannot open the file")
tandem_cli_test(run-malformed 2 "run|${tandem_cli_data}/malformed.json"
  ERR "malformed.json: parse error at line 4, column [0-9]+: syntax error")
tandem_cli_test(run-wrong-type 2 "run|${tandem_cli_data}/wrong_type.json"
  ERR "wrong_type.json: /bodies/1/shapes/0/radius: expected a number, got a string")
tandem_cli_test(run-unknown-key 2 "run|${tandem_cli_data}/unknown_key.json"
  ERR "unknown_key.json: /world/gravty: unknown key \\(did you mean \"gravity\"\\?\\)")
tandem_cli_test(run-out-of-range 2 "run|${tandem_cli_data}/out_of_range.json"
  ERR "out_of_range.json: /world/sub_steps: expected an integer in \\[1, 64\\], got 100")
tandem_cli_test(run-integer-fraction 2 "run|${tandem_cli_data}/integer_fraction.json"
  ERR "/step_hz: expected an integer in \\[1, 10000\\] \\(no fraction or exponent\\), got 60.5")
tandem_cli_test(run-engine-refusal 2 "run|${tandem_cli_data}/engine_refusal.json"
  ERR "engine_refusal.json: /bodies/1/shapes/0: .*restitution")
tandem_cli_test(run-joints 2 "run|${tandem_cli_data}/joints.json"
  ERR "joints.json: /joints/0: create_joint: create_revolute_joint: RevoluteJointDef.base.body_a and base.body_b are both static")

# --- render ----------------------------------------------------------------------------
tandem_cli_test(render-one 0 "render|scenes/stack.json|--tick|30|-o|${tandem_cli_out}/one|--format|both|--aabbs|--contacts"
  OUT "wrote .*stack-000030.png\nwrote .*stack-000030.svg"
  EXISTS "${tandem_cli_out}/one/stack-000030.png|${tandem_cli_out}/one/stack-000030.svg")
tandem_cli_test(render-every 0 "render|scenes/dominoes.json|--every|20|--ticks|60|-o|${tandem_cli_out}/every|--sheet|--size|320x200"
  EXISTS "${tandem_cli_out}/every/dominoes-000000.png|${tandem_cli_out}/every/dominoes-000060.png|${tandem_cli_out}/every/dominoes-sheet.png")
# Every bundled joint scene renders with its joints drawn (a contact sheet of 4 frames).
foreach(scene pendulum chain50 ragdolls car grappling_hook)
  tandem_cli_test(render-${scene} 0 "render|scenes/${scene}.json|--every|40|--ticks|120|-o|${tandem_cli_out}/${scene}|--sheet|--size|320x200"
    EXISTS "${tandem_cli_out}/${scene}/${scene}-000000.png|${tandem_cli_out}/${scene}/${scene}-000120.png|${tandem_cli_out}/${scene}/${scene}-sheet.png")
  tandem_cli_test(run-${scene} 0 "run|scenes/${scene}.json|--ticks|60|--quiet" OUT "^final tick 60  hash 0x[0-9a-f]+\n$")
endforeach()
tandem_cli_test(render-no-out 2 "render|scenes/stack.json" ERR "--out is required")
tandem_cli_test(render-bad-size 2 "render|scenes/stack.json|-o|${tandem_cli_out}/bad|--size|huge" ERR "--size: expected WIDTHxHEIGHT")
tandem_cli_test(render-tick-and-every 2 "render|scenes/stack.json|-o|${tandem_cli_out}/bad|--tick|3|--every|2" ERR "excludes")
tandem_cli_test(render-bad-format 2 "render|scenes/stack.json|-o|${tandem_cli_out}/bad|--format|gif" ERR "gif not in")
tandem_cli_test(render-missing-file 2 "render|nope.json|-o|${tandem_cli_out}/bad" ERR "nope.json: cannot open the file")
tandem_cli_test(render-malformed 2 "render|${tandem_cli_data}/malformed.json|-o|${tandem_cli_out}/bad" ERR "line 4, column")

# --- demo --------------------------------------------------------------------------------
tandem_cli_test(demo 0 "demo|-o|${tandem_cli_out}/demo|--seconds|1"
  OUT "final state hash.*0x[0-9a-f]+.*OK: every recorded hash matches.*picture: .*rain-final.png.*replay: .*rain.tandem-replay"
  EXISTS "${tandem_cli_out}/demo/rain-final.png|${tandem_cli_out}/demo/rain-sheet.png|${tandem_cli_out}/demo/rain.tandem-replay")
tandem_cli_test(demo-bad-scene 2 "demo|--scene|${tandem_cli_data}/unknown_key.json|-o|${tandem_cli_out}/bad" ERR "gravty")

# render accepts a replay file too (the demo's recording): it plays the ticks.
tandem_cli_test(render-replay 0 "render|${tandem_cli_out}/demo/rain.tandem-replay|--tick|30|-o|${tandem_cli_out}/from-replay"
  EXISTS "${tandem_cli_out}/from-replay/rain-000030.png")
tandem_cli_test(render-replay-too-far 2 "render|${tandem_cli_out}/demo/rain.tandem-replay|--tick|100000|-o|${tandem_cli_out}/bad"
  ERR "the replay has 60 ticks")
set_tests_properties("cli/demo" PROPERTIES FIXTURES_SETUP tandem_demo_replay)
set_tests_properties("cli/render-replay" "cli/render-replay-too-far" PROPERTIES FIXTURES_REQUIRED tandem_demo_replay)

# An engine refusal of a scripted input stops the run with the input's path and tick.
tandem_cli_test(run-input-refused 2 "run|${tandem_cli_data}/input_refused.json"
  ERR "input_refused.json: /inputs/0 \\(tick 3\\): set_linear_velocity body .*faster than the world's maximum")
