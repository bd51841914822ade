# The simulated world (MuJoCo, servo model, sensors, miscalibration) and the stand controller on it.
nao_add_test(world_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/world_test.cpp LIBS nao_sim)
nao_add_test(stand_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/stand_test.cpp LIBS nao_sim nao_controllers)
nao_add_test(ground_truth_test SOURCES ground_truth_test.cpp LIBS nao_sim nao_controllers)
