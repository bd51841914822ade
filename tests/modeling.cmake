# Modeling (perception/modeling/): self-localization and ball model against synthetic truth.
nao_add_test(modeling_localization_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/modeling_localization_test.cpp LIBS nao_modeling TIMEOUT 300)
nao_add_test(modeling_ball_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/modeling_ball_test.cpp LIBS nao_modeling TIMEOUT 300)
# The modeling and behaviour modules of the robot program, each in the module harness.
nao_add_test(modeling_modules_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/modeling_modules_test.cpp LIBS nao_controllers TIMEOUT 300)
nao_add_test(view_region_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/view_region_test.cpp LIBS nao_modeling TIMEOUT 60)
nao_add_test(ball_tracker_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/ball_tracker_test.cpp LIBS nao_controllers TIMEOUT 120)
