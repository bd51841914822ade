nao_add_test(camera_agreement_test SOURCES camera_agreement_test.cpp LIBS nao_scenarios TIMEOUT 900)
nao_add_test(cli_test SOURCES cli_test.cpp LIBS TIMEOUT 300)
add_dependencies(cli_test nao-soccer)
