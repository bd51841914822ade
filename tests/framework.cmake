# Module framework: pipeline order, the module registry and config/modules.json, parameters
# from files, each module alone through the harness (tests/support/ModuleHarness.h).
nao_add_test(pipeline_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/framework/pipeline_test.cpp LIBS nao_robot TIMEOUT 60)
nao_add_test(debug_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/framework/debug_test.cpp LIBS nao_robot TIMEOUT 60)
nao_add_test(parameters_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/framework/parameters_test.cpp LIBS nao_controllers TIMEOUT 60)
nao_add_test(module_registry_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/framework/module_registry_test.cpp
             LIBS nao_controllers TIMEOUT 60)
nao_add_test(modules_test
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/framework/camera_matrix_provider_test.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/framework/fall_detector_module_test.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/framework/head_control_module_test.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/framework/motion_engine_module_test.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/framework/nao_modules_test.cpp
             LIBS nao_controllers TIMEOUT 120)
nao_add_test(cadence_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/framework/cadence_test.cpp LIBS nao_controllers TIMEOUT 120)

# Compile-time enforcement: reading an undeclared representation, writing a required one and
# requiring what one provides do not compile (binding_violation.cpp); the control compiles.
set(_binding ${CMAKE_CXX_COMPILER} -std=c++20 -fsyntax-only -I${CMAKE_SOURCE_DIR}
             ${CMAKE_CURRENT_LIST_DIR}/framework/binding_violation.cpp)
add_test(NAME module_binding_control COMMAND ${_binding} -DVIOLATION=0)
add_test(NAME module_binding_read_undeclared COMMAND ${_binding} -DVIOLATION=1)
add_test(NAME module_binding_write_required COMMAND ${_binding} -DVIOLATION=2)
add_test(NAME module_binding_require_provided COMMAND ${_binding} -DVIOLATION=3)
set_tests_properties(module_binding_read_undeclared PROPERTIES PASS_REGULAR_EXPRESSION "is not in this module's Requires")
set_tests_properties(module_binding_write_required PROPERTIES PASS_REGULAR_EXPRESSION "is not in this module's Provides")
set_tests_properties(module_binding_require_provided PROPERTIES PASS_REGULAR_EXPRESSION "cannot require what it provides")
set_tests_properties(module_binding_control module_binding_read_undeclared module_binding_write_required
                     module_binding_require_provided PROPERTIES TIMEOUT 60 LABELS "framework;${NAO_FRAGMENT_LABELS}")

# libFuzzer target for the parameter loader (.ci/fuzz.sh runs it with clang in build-fuzz).
if(NAO_FUZZ)
  add_executable(params_fuzz ${CMAKE_CURRENT_LIST_DIR}/fuzz/params_fuzz.cpp ${CMAKE_SOURCE_DIR}/robot/Parameters.cpp)
  target_include_directories(params_fuzz PRIVATE ${CMAKE_SOURCE_DIR})
  set(_params_fuzz_flags -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_compile_options(params_fuzz PRIVATE ${_params_fuzz_flags} -g -Wall -Wextra)
  target_link_options(params_fuzz PRIVATE ${_params_fuzz_flags})
  target_link_libraries(params_fuzz PRIVATE Eigen3::Eigen nlohmann_json::nlohmann_json)
endif()
