# Camera calibration (perception/calibration, scenarios/Calibrate): synthetic samples, solvers,
# goal box finding and refinement on painted images, the store; then a small evaluation in
# the simulator with the acceptance thresholds: the robot program calibrates itself (phase 1,
# about a minute of wall time each; under the sanitizers several).
nao_add_test(calibration_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibration_test.cpp LIBS nao_perception nao_controllers opencv_imgcodecs)
nao_add_test(calibration_sim_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibration_sim_test.cpp LIBS nao_scenarios opencv_imgcodecs TIMEOUT 2400)
nao_add_test(calibration_log_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/calibration_log_test.cpp LIBS nao_controllers)
# Real goal-box frames (../shared/data/real-goalbox-images): the recorded camera matrices, and
# perceive --camera-matrix and eval real on them.
nao_add_test(real_goalbox_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/real_goalbox_test.cpp LIBS nao_perception nao_controllers TIMEOUT 300)
add_dependencies(real_goalbox_test nao-soccer)
