# Motion: inverse kinematics and the mass model, walk (with motion engine, head control and the
# World's robot variations), kick, get-up -- closed-loop in the simulator, judged by ground truth.
nao_add_test(kinematics_ik_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/kinematics_ik_test.cpp LIBS nao_sim nao_controllers)
nao_add_test(walk_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/walk_test.cpp LIBS nao_scenarios)
nao_add_test(kick_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/kick_test.cpp LIBS nao_scenarios)
nao_add_test(fall_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/fall_test.cpp LIBS nao_scenarios)
# Label 'pending': issue 4's get-up acceptance (upright within 15 s, nominal and randomised
# robots) is not reached yet; CI skips it until it is. Budget once it passes: < 120 s in Release
# (NAO_TEST_QUICK: 2 trials per side and robot kind).
nao_add_test(getup_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/getup_test.cpp LIBS nao_scenarios LABELS pending)
