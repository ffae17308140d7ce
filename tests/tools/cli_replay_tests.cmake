# cli_replay_tests.cmake — end-to-end cases of `tandem record`, `replay`,
# `verify`, `diff` and `synctest`, included from tests/CMakeLists.txt inside
# if(TARGET tandem). Each case runs through cli_case.cmake (exit code and
# messages); the cases that read a replay depend, through ctest fixtures, on
# the case that records it. ctest names: "cli/<case>".
set(tandem_replay_case ${CMAKE_CURRENT_LIST_DIR}/cli_case.cmake)
set(tandem_replay_out ${CMAKE_CURRENT_BINARY_DIR}/cli-replay-out)
file(MAKE_DIRECTORY ${tandem_replay_out})

# tandem_replay_cli_test(NAME RC "ARG|ARG..." [OUT re] [ERR re] [SAME "ARG|..."] [EXISTS "f|f"]
#                        [ALLOW_STDERR] [SETUP fixture] [REQUIRES "fixture;..."])
function(tandem_replay_cli_test name rc args)
  cmake_parse_arguments(PARSE_ARGV 3 arg "ALLOW_STDERR" "OUT;ERR;SAME;EXISTS;SETUP" "REQUIRES")
  add_test(NAME "cli/${name}"
    COMMAND ${CMAKE_COMMAND} "-DTANDEM=$<TARGET_FILE:tandem>" "-DARGS=${args}" "-DRC=${rc}" "-DOUT=${arg_OUT}"
      "-DERR=${arg_ERR}" "-DSAME=${arg_SAME}" "-DEXISTS=${arg_EXISTS}" "-DOUT_ALLOW_STDERR=${arg_ALLOW_STDERR}"
      -P ${tandem_replay_case}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  if(arg_SETUP)
    set_tests_properties("cli/${name}" PROPERTIES FIXTURES_SETUP ${arg_SETUP})
  endif()
  if(arg_REQUIRES)
    set_tests_properties("cli/${name}" PROPERTIES FIXTURES_REQUIRED "${arg_REQUIRES}")
  endif()
endfunction()

set(out ${tandem_replay_out})

# --- help ---------------------------------------------------------------------------
foreach(command record replay verify diff synctest)
  tandem_replay_cli_test(${command}-help 0 "${command}|--help" OUT "Examples:\n  tandem ${command}")
endforeach()

# --- record, then replay and verify -------------------------------------------------------
tandem_replay_cli_test(record-stack 0 "record|scenes/stack.json|-o|${out}/stack.tnr|--ticks|60|--keyframe-every|20"
  OUT "recorded .*stack.tnr: 60 ticks of scenes/stack.json, [0-9]+ bytes, keyframe every 20 ticks\nfinal tick 60  hash 0x[0-9a-f]+\n"
  EXISTS "${out}/stack.tnr" SETUP replay_stack)
tandem_replay_cli_test(record-impulses 0 "record|scenes/impulses.json|-o|${out}/impulses.tnr|--ticks|40|--no-hash|--quiet"
  OUT "^final tick 40  hash 0x[0-9a-f]+\n$" SETUP replay_impulses)
tandem_replay_cli_test(record-json 0 "--json|record|scenes/stack.json|-o|${out}/stack-json.tnr|--ticks|5"
  OUT "^\\{\"replay\":\".*stack-json.tnr\",\"scene\":\"scenes/stack.json\",\"ticks\":5,")
tandem_replay_cli_test(record-missing-scene 2 "record|scenes/no-such-scene.json|-o|${out}/x.tnr"
  ERR "tandem record: scenes/no-such-scene.json: cannot open")
tandem_replay_cli_test(record-no-out 2 "record|scenes/stack.json" ERR "--out is required")
tandem_replay_cli_test(record-unwritable 2 "record|scenes/stack.json|-o|/nonexistent-dir/x.tnr"
  ERR "/nonexistent-dir/x.tnr: cannot create")

# A scene with joints: recorded (create_joint commands after the bodies, keyframes in state format 2)
# and replayed to the bit of `tandem run`.
tandem_replay_cli_test(record-bridge 0 "record|scenes/bridge.json|-o|${out}/bridge.tnr|--ticks|60|--keyframe-every|20|--quiet"
  OUT "^final tick 60  hash 0x[0-9a-f]+\n$" SETUP replay_bridge)
tandem_replay_cli_test(replay-bridge-matches-run 0 "replay|${out}/bridge.tnr|--quiet"
  OUT "^final tick 60  hash 0x[0-9a-f]+\n$" SAME "run|scenes/bridge.json|--ticks|60|--quiet" REQUIRES replay_bridge)

# The bundled joint scenes: each recorded past its scripted joint inputs
# (motor changes, rope reeling, the hook's release), replayed to the bit of
# `tandem run` and verified tick by tick.
foreach(scene_ticks pendulum:120 chain50:120 ragdolls:180 car:750 grappling_hook:500)
  string(REPLACE ":" ";" pair ${scene_ticks})
  list(GET pair 0 scene)
  list(GET pair 1 ticks)
  tandem_replay_cli_test(record-${scene} 0 "record|scenes/${scene}.json|-o|${out}/${scene}.tnr|--ticks|${ticks}|--keyframe-every|60|--quiet"
    OUT "^final tick ${ticks}  hash 0x[0-9a-f]+\n$" SETUP replay_${scene})
  tandem_replay_cli_test(replay-${scene}-matches-run 0 "replay|${out}/${scene}.tnr|--quiet"
    OUT "^final tick ${ticks}  hash 0x[0-9a-f]+\n$" SAME "run|scenes/${scene}.json|--ticks|${ticks}|--quiet"
    REQUIRES replay_${scene})
  tandem_replay_cli_test(verify-${scene} 0 "verify|${out}/${scene}.tnr"
    OUT "ticks re-simulated: ${ticks}, tick hashes checked: ${ticks}, .*\nOK: every recorded hash matches"
    REQUIRES replay_${scene})
endforeach()

# The replay reproduces `tandem run` of the same scene, to the bit.
tandem_replay_cli_test(replay-stack-matches-run 0 "replay|${out}/stack.tnr|--quiet"
  OUT "^final tick 60  hash 0x[0-9a-f]+\n$" SAME "run|scenes/stack.json|--ticks|60|--quiet" REQUIRES replay_stack)
tandem_replay_cli_test(replay-stack 0 "replay|${out}/stack.tnr|--ticks|30|--save-state|${out}/stack-30.state"
  OUT "recorded hash at tick 30: 0x[0-9a-f]+ \\(matches\\)\n.*final tick 30  hash" EXISTS "${out}/stack-30.state"
  SETUP replay_state30 REQUIRES replay_stack)
tandem_replay_cli_test(replay-state-60 0 "replay|${out}/stack.tnr|--save-state|${out}/stack-60.state|--quiet"
  EXISTS "${out}/stack-60.state" SETUP replay_state60 REQUIRES replay_stack)
tandem_replay_cli_test(replay-json 0 "replay|${out}/stack.tnr|--json"
  OUT "\"final_hash\":\"0x[0-9a-f]+\"" REQUIRES replay_stack)
tandem_replay_cli_test(replay-too-far 2 "replay|${out}/stack.tnr|--ticks|61"
  ERR "--ticks 61 is past the last recorded tick 60" REQUIRES replay_stack)

tandem_replay_cli_test(verify-stack 0 "verify|${out}/stack.tnr"
  OUT "ticks re-simulated: 60, tick hashes checked: 60, keyframes checked: 4\nOK: every recorded hash matches"
  REQUIRES replay_stack)
tandem_replay_cli_test(verify-no-hash 0 "verify|${out}/impulses.tnr"
  OUT "tick hashes checked: 0, keyframes checked: 1\nOK" REQUIRES replay_impulses)
tandem_replay_cli_test(verify-json 0 "verify|${out}/stack.tnr|--json"
  OUT "\"result\":\"ok\",\"truncated\":false,\"ticks_run\":60" REQUIRES replay_stack)
tandem_replay_cli_test(verify-quiet 0 "--quiet|verify|${out}/stack.tnr" OUT "^OK 60 ticks\n$" REQUIRES replay_stack)

# --- damaged files: a cut tail reads with a warning; a flipped byte is an error ----------
add_test(NAME "cli/replay-damage-files"
  COMMAND sh -c "head -c -5 stack.tnr > cut.tnr && cp stack.tnr flipped.tnr && printf '\\377' | dd of=flipped.tnr bs=1 seek=40 conv=notrunc 2>/dev/null"
  WORKING_DIRECTORY ${out})
set_tests_properties("cli/replay-damage-files" PROPERTIES FIXTURES_SETUP replay_damaged FIXTURES_REQUIRED replay_stack)
tandem_replay_cli_test(verify-cut 0 "verify|${out}/cut.tnr" ALLOW_STDERR
  OUT "OK: every recorded hash matches"
  ERR "tandem verify: warning: .*cut.tnr: file cut at byte [0-9]+ after tick 60 \\(mid END chunk"
  REQUIRES replay_damaged)
tandem_replay_cli_test(verify-flipped 2 "verify|${out}/flipped.tnr"
  ERR "tandem verify: .*flipped.tnr: offset 12: HEAD chunk \\(payload at 24\\.\\.[0-9]+\\) is corrupted: checksum"
  REQUIRES replay_damaged)
tandem_replay_cli_test(verify-not-a-replay 2 "verify|scenes/stack.json"
  ERR "scenes/stack.json: offset 0: expected the replay magic \"TANDREPL\", got bytes [0-9a-f]+ \\(not a Tandem replay\\)")
tandem_replay_cli_test(verify-missing 2 "verify|${out}/none.tnr" ERR "none.tnr: cannot open")

# --- many files: --jobs, one JSON line per file, the exit code of the worst verdict ----------
tandem_replay_cli_test(verify-many 0 "verify|--jobs|2|${out}/stack.tnr|${out}/impulses.tnr|${out}/bridge.tnr"
  OUT "^OK        [^\n]*stack.tnr: 60 ticks, 60 hashes, 4 keyframes\nOK        [^\n]*impulses.tnr: 40 ticks, 0 hashes, 1 keyframes\nOK        [^\n]*bridge.tnr: 60 ticks, 60 hashes, 4 keyframes\nverified 3 files with 2 jobs: 3 ok, 0 mismatched, 0 not verified \\(bad file\\)\n$"
  REQUIRES "replay_stack;replay_impulses;replay_bridge")
tandem_replay_cli_test(verify-many-json 2 "verify|-j|0|--json|${out}/stack.tnr|${out}/flipped.tnr|${out}/none.tnr|${out}/impulses.tnr"
  OUT "^\\{\"replay\":\"[^\n]*stack.tnr\",\"result\":\"ok\",[^\n]*\"ticks_run\":60,[^\n]*\\}\n\\{\"replay\":\"[^\n]*flipped.tnr\",\"result\":\"error\",\"error\":\"[^\n]*flipped.tnr: offset 12: HEAD chunk[^\n]*\\}\n\\{\"replay\":\"[^\n]*none.tnr\",\"result\":\"error\",\"error\":\"[^\n]*none.tnr: cannot open[^\n]*\\}\n\\{\"replay\":\"[^\n]*impulses.tnr\",\"result\":\"ok\",[^\n]*\\}\n$"
  REQUIRES "replay_stack;replay_impulses;replay_damaged")
tandem_replay_cli_test(verify-many-quiet 2 "verify|-q|${out}/stack.tnr|${out}/flipped.tnr"
  OUT "^ERROR     [^\n]*flipped.tnr: offset 12[^\n]*\nverified 2 files with 1 job: 1 ok, 0 mismatched, 1 not verified \\(bad file\\)\n$"
  REQUIRES "replay_stack;replay_damaged")
tandem_replay_cli_test(verify-many-cut 0 "verify|${out}/cut.tnr|${out}/stack.tnr" ALLOW_STDERR
  OUT "^OK        [^\n]*cut.tnr: 60 ticks[^\n]*\\(truncated file\\)\nOK        [^\n]*stack.tnr: 60 ticks"
  ERR "tandem verify: warning: .*cut.tnr: file cut at byte" REQUIRES "replay_stack;replay_damaged")
# The two replays of a netplay with an injected desync (tests/CMakeLists.txt, ENet builds): the
# perturbed peer's recording mismatches at the injected tick, the other verifies.
if(TEST net/cli_netplay_desync)
  set(net_art ${CMAKE_CURRENT_BINARY_DIR}/net_artifacts)
  tandem_replay_cli_test(verify-many-netplay-desync 1
    "verify|--jobs|2|--json|${net_art}/netplay_peer0.replay|${net_art}/netplay_peer1.replay"
    OUT "\"result\":\"mismatch\",[^\n]*\"mismatch_tick\":100,"
    REQUIRES netplay_desync_artifacts)
  tandem_replay_cli_test(verify-many-netplay-text 1
    "verify|${net_art}/netplay_peer0.replay|${net_art}/netplay_peer1.replay|${out}/stack.tnr"
    OUT "MISMATCH  [^\n]*netplay_peer[01].replay: tick 100, expected 0x[0-9a-f]+, got 0x[0-9a-f]+\n.*verified 3 files with 1 job: 2 ok, 1 mismatched, 0 not verified"
    REQUIRES "netplay_desync_artifacts;replay_stack")
endif()
# The same from the arena scene file: the verdict includes the scores (game states) checked.
if(TEST net/cli_netplay_scene_desync)
  set(net_art_scene ${CMAKE_CURRENT_BINARY_DIR}/net_artifacts_scene)
  tandem_replay_cli_test(verify-netplay-scene-game-states 1
    "verify|-j|2|--json|${net_art_scene}/netplay_peer0.replay|${net_art_scene}/netplay_peer1.replay"
    OUT "\"result\":\"ok\",[^\n]*\"game_states_recorded\":[1-9][0-9]*,\"game_states_checked\":[1-9][0-9]*,.*\"result\":\"mismatch\",[^\n]*\"mismatch_tick\":60,[^\n]*\"difference\":\\{\"record\":\"body\",\"index\":44,"
    REQUIRES netplay_scene_artifacts)
endif()
tandem_replay_cli_test(verify-bad-jobs 2 "verify|--jobs|-1|${out}/stack.tnr" ERR "jobs")

# --- diff -----------------------------------------------------------------------------
tandem_replay_cli_test(diff-same 0 "diff|${out}/stack.tnr|${out}/stack.tnr"
  OUT "method: hash chain, ticks compared: 60\nIDENTICAL" REQUIRES replay_stack)
tandem_replay_cli_test(diff-scenes 1 "diff|${out}/stack.tnr|${out}/impulses.tnr"
  OUT "DIFFERENT from tick 0: hashes 0x[0-9a-f]+ vs 0x[0-9a-f]+\nat tick 0: "
  REQUIRES "replay_stack;replay_impulses")
tandem_replay_cli_test(diff-snapshots 1 "diff|${out}/stack-30.state|${out}/stack-60.state|--json"
  OUT "\"method\":\"snapshot\",\"result\":\"different\".*\"difference\":\\{\"record\":\"[a-z_]+\",\"index\":[0-9]+"
  REQUIRES "replay_state30;replay_state60")
tandem_replay_cli_test(diff-snapshot-same 0 "diff|${out}/stack-30.state|${out}/stack-30.state" OUT "IDENTICAL"
  REQUIRES replay_state30)
tandem_replay_cli_test(diff-mixed 2 "diff|${out}/stack.tnr|${out}/stack-30.state"
  ERR "cannot compare a replay with a snapshot" REQUIRES "replay_stack;replay_state30")

# --- synctest ---------------------------------------------------------------------------
tandem_replay_cli_test(synctest-stack 0 "synctest|scenes/stack.json|--ticks|30|--rollback|4"
  OUT "synctest scenes/stack.json: 30 ticks, rollback 4, [0-9]+ ticks re-simulated\npassed")
tandem_replay_cli_test(synctest-json 0 "synctest|scenes/impulses.json|--ticks|20|--json"
  OUT "\"result\":\"passed\"")
tandem_replay_cli_test(synctest-bad-rollback 2 "synctest|scenes/stack.json|--rollback|0" ERR "rollback")

# --- state: every body at one tick, from a scene or a replay ------------------------------
tandem_replay_cli_test(state-replay-matches-scene 0 "state|${out}/stack.tnr|--tick|30"
  OUT "^tick 30: 13 bodies, world hash 0x[0-9a-f]+\n# body .*\nbody 1:1 dynamic (awake|asleep) \\| p -?[0-9.]+ \\[-?[0-9]+\\] "
  SAME "state|scenes/stack.json|--tick|30" REQUIRES replay_stack)
tandem_replay_cli_test(state-quiet 0 "state|scenes/impulses.json|--tick|25|--quiet"
  OUT "^tick 25: [0-9]+ bodies, world hash 0x[0-9a-f]+\n$")
tandem_replay_cli_test(state-json 0 "state|${out}/stack.tnr|--tick|0|--json"
  OUT "^\\{\"tick\":0,\"world_hash\":\"0x[0-9a-f]+\",\"bodies\":\\[\\{\"index\":0,\"generation\":1,\"type\":\"static\",\"position\":\\{\"x\":\\{\"value\":\"[-0-9.]+\",\"raw\":-?[0-9]+\\}"
  REQUIRES replay_stack)
tandem_replay_cli_test(state-past-end 2 "state|${out}/stack.tnr|--tick|61"
  ERR "stack.tnr: --tick 61 is past the last recorded tick 60" REQUIRES replay_stack)
tandem_replay_cli_test(state-negative-tick 2 "state|scenes/stack.json|--tick|-3"
  ERR "--tick: Value -3 not in range 0 to 1099511627776")
tandem_replay_cli_test(state-huge-tick 2 "state|scenes/stack.json|--tick|99999999999999999999"
  ERR "--tick: Value 99999999999999999999 not in range 0 to 1099511627776")
tandem_replay_cli_test(state-help 0 "state|--help" OUT "Examples:\n  tandem state")
tandem_replay_cli_test(state-bad-scene 2 "state|${out}/none.json" ERR "none.json: cannot open")
