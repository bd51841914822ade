# The fast percept mode: the simulator's view, the OracleVision module, its fitted error model.
nao_add_test(oracle_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/oracle_test.cpp LIBS nao_scenarios TIMEOUT 600)
