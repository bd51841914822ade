# Motion: inverse kinematics and the mass model, walk (with motion engine, head control and the
# World's robot variations), kick, get-up -- closed-loop in the simulator, judged by ground truth.
nao_add_test(kinematics_ik_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/kinematics_ik_test.cpp LIBS nao_sim nao_controllers)
nao_add_test(walk_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/walk_test.cpp LIBS nao_scenarios)
nao_add_test(kick_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/kick_test.cpp LIBS nao_scenarios)
nao_add_test(fall_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/fall_test.cpp LIBS nao_scenarios)
# Get-up: issue 4's acceptance (upright within 15 s from front and back, nominal and randomised
# robots), 4 trials per side and robot kind (NAO_TEST_QUICK: 2); about 40 s in Release.
nao_add_test(getup_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/getup_test.cpp LIBS nao_scenarios)
# Odometry: the inertial check of the feet (synthetic truth), a twisting sole, the simulated
# IMU against the truth, randomised walk-to odometry against the truth.
nao_add_test(odometry_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/odometry_test.cpp LIBS nao_scenarios)
