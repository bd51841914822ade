nao_add_test(camera_agreement_test SOURCES camera_agreement_test.cpp LIBS nao_scenarios TIMEOUT 900)
nao_add_test(cli_test SOURCES cli_test.cpp LIBS nao_robot TIMEOUT 300)
add_dependencies(cli_test nao-soccer)
nao_add_test(output_files_test SOURCES output_files_test.cpp LIBS nao_robot)
# Walks every declared option of every command (apps/cli/Declarations.cpp) with bad values.
nao_add_test(cli_contract_test SOURCES cli_contract_test.cpp LIBS nao_cli TIMEOUT 900)
add_dependencies(cli_contract_test nao-soccer)
nao_add_test(cli_json_test SOURCES cli_json_test.cpp LIBS nao_cli TIMEOUT 900)
add_dependencies(cli_json_test nao-soccer)
# --debug on the commands: timing, walk_trace, refusals, stdout kept for the JSON.
nao_add_test(debug_channels_test SOURCES debug_channels_test.cpp LIBS nao_robot TIMEOUT 600)
add_dependencies(debug_channels_test nao-soccer)
# batch: every runner (local, GNU parallel, a single-node Slurm from tools/slurm-local.sh, which
# needs root: CI runs as root) against one uninterrupted evaluation; resume; crashes; bad input.
nao_add_test(batch_test SOURCES batch_test.cpp LIBS nao_batch TIMEOUT 1200)
add_dependencies(batch_test nao-soccer)
