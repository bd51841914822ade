# The robot-only executable nao-soccer-robot and the bundle robot/deploy/deploy.sh gives a NAO
# (docs/real-robot.md, "Deployment"): its link and instruction set, its command line against
# `nao-soccer run --backend nao`'s, the staged bundle, the deploy against stand-in robots, and
# the bundle running in roots that are not the build machine's.
add_test(NAME robot_executable_test
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/robot_executable_test.sh $<TARGET_FILE:nao-soccer-robot> $<TARGET_FILE:nao-soccer>)
set_tests_properties(robot_executable_test PROPERTIES TIMEOUT 120 LABELS "nao")

# The bundle is a Release artefact: under ASan + UBSan it would carry libasan, which needs /proc
# (absent in the empty root), so the sanitizer build leaves these out.
if(NOT NAO_SANITIZE)
  # robot/deploy/deploy.sh --dry-run: the staged bundle (size, libraries, files), the venue's
  # field file in place, the staged start script running the staged program.
  add_test(NAME deploy_test COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/deploy_test.sh $<TARGET_FILE:nao-soccer-robot> ${CMAKE_SOURCE_DIR})
  set_tests_properties(deploy_test PROPERTIES TIMEOUT 120 LABELS "nao")
  # The deploy's failure cases and the atomic switch, against stand-in robots (local folders).
  add_test(NAME deploy_target_test COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/deploy_target_test.sh $<TARGET_FILE:nao-soccer-robot> ${CMAKE_SOURCE_DIR})
  set_tests_properties(deploy_target_test PROPERTIES TIMEOUT 180 LABELS "nao")
  # The bundle in chroot against lola_peer for 10 s: a root with nothing but the bundle, and a
  # Debian 11 root (debootstrap, cached; skipped when Debian's mirror cannot be reached). Alone
  # (RUN_SERIAL), as lola_peer_test: every answer is judged against the 12 ms cycle.
  # The robot executable under qemu-user's Nehalem model (no AVX, as the NAO's Atom): its whole
  # cognition on the real NAO images (skipped without qemu-user or ../shared).
  add_test(NAME robot_noavx_test
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/robot_noavx_test.sh $<TARGET_FILE:nao-soccer-robot>
                   $<TARGET_FILE:lola_peer> ${CMAKE_SOURCE_DIR})
  set_tests_properties(robot_noavx_test PROPERTIES RUN_SERIAL TRUE TIMEOUT 300 SKIP_RETURN_CODE 77 LABELS "nao")
  foreach(root empty debian11)
    add_test(NAME robot_bundle_${root}_root_test
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/robot_bundle_test.sh ${root} $<TARGET_FILE:nao-soccer-robot>
                     $<TARGET_FILE:lola_peer> ${CMAKE_SOURCE_DIR})
    set_tests_properties(robot_bundle_${root}_root_test PROPERTIES RUN_SERIAL TRUE TIMEOUT 900 SKIP_RETURN_CODE 77 LABELS "nao")
  endforeach()
endif()
# The robot executable and `nao-soccer run --backend nao` answer a recorded LoLA packet and image
# sequence alike (--lockstep); skipped without ../shared's real images. Alone (RUN_SERIAL): the
# recording is a soak against lola_peer, every answer judged against the 12 ms cycle.
add_test(NAME same_answers_test
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/same_answers_test.sh $<TARGET_FILE:nao-soccer-robot>
                 $<TARGET_FILE:nao-soccer> $<TARGET_FILE:lola_peer> ${CMAKE_SOURCE_DIR})
set_tests_properties(same_answers_test PROPERTIES RUN_SERIAL TRUE TIMEOUT 600 SKIP_RETURN_CODE 77 LABELS "nao")
