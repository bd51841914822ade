# The robot program's cognition in the simulator, judged by the simulator's truth.
nao_add_test(cognition_test SOURCES cognition_test.cpp LIBS nao_scenarios TIMEOUT 300)
