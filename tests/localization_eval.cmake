# eval localization: the robot program's localization and ball model in the simulator, scored
# by the truth; the command's --rows resume.
nao_add_test(localization_eval_test SOURCES localization_eval_test.cpp LIBS nao_scenarios TIMEOUT 600)
add_dependencies(localization_eval_test nao-soccer)
