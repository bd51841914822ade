# The calibration challenge (issue 20): the referee's buttons through the robot's own touch
# sensors, judged in the simulator.
nao_add_test(challenge_buttons_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/challenge_buttons_test.cpp
             LIBS nao_scenarios TIMEOUT 300)
# Reports: the raised arm in the simulator (truth), the Report option, the NAO's speech command.
nao_add_test(report_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/report_test.cpp LIBS nao_scenarios TIMEOUT 300)
# The Calibrator module on rendered goal-box views of a robot with injected offsets.
nao_add_test(calibrator_module_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibrator_module_test.cpp LIBS nao_scenarios TIMEOUT 600)
# Phase 2's parts: the per-half ball estimate, the detours, the ball draw, and the termination
# rules judged from the simulator's truth.
nao_add_test(challenge_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/challenge_test.cpp LIBS nao_scenarios TIMEOUT 300)
# The whole challenge, `calibration-challenge --seed 1`, twice (Release only: about 3 min each).
nao_add_test(challenge_sim_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/challenge_sim_test.cpp LIBS nao_scenarios opencv_imgcodecs TIMEOUT 1200)
