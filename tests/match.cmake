# Simulated 1vs1 games (issue 21): the in-process GameController (rules, packets), the ball and robot rules.
nao_add_test(match_gc_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/match_gc_test.cpp LIBS nao_scenarios LABELS match)
nao_add_test(ball_rules_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/ball_rules_test.cpp LIBS nao_scenarios LABELS match)
nao_add_test(robot_rules_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/robot_rules_test.cpp LIBS nao_scenarios LABELS match)
nao_add_test(kick_choice_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/kick_choice_test.cpp LIBS nao_controllers LABELS match)
nao_add_test(striker_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/striker_test.cpp LIBS nao_controllers LABELS match)
nao_add_test(match_sim_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/match_sim_test.cpp LIBS nao_scenarios LABELS match TIMEOUT 1200)
