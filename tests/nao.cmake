# The real NAO backend (robot/nao/): LoLA packets and safety, the LoLA peer end to end,
# the GameController protocol and buttons, V4L2 against a test double of the ioctl layer.

# A stand-in for the NAO's LoLA daemon: its own msgpack encoder/decoder, a real Unix socket,
# the real nao-soccer as its client (ctest lola_peer_test).
add_executable(lola_peer lola_peer.cpp)
target_link_libraries(lola_peer PRIVATE ${NAO_MSGPACK_TARGET})
target_include_directories(lola_peer PRIVATE ${CMAKE_SOURCE_DIR})
target_compile_definitions(lola_peer PRIVATE MSGPACK_NO_BOOST)
nao_warnings(lola_peer)

# The peer runs the real nao-soccer for 1000+ cycles and judges every answer's timing, so it
# runs alone (RUN_SERIAL): "no late answer" is a claim about normal load, not about a machine
# busy with other tests.
add_test(NAME lola_peer_test COMMAND lola_peer --nao-soccer $<TARGET_FILE:nao-soccer> --cycles 1000)
set_tests_properties(lola_peer_test PROPERTIES RUN_SERIAL TRUE TIMEOUT 300 LABELS "nao")

# The simulator as a whole NAO under run --backend nao: LoLA over a Unix socket, both cameras
# rendered and sent to --cameras socket:PATH, the program's belief scored against the truth.
add_executable(sim_lola_peer sim_lola_peer.cpp)
target_include_directories(sim_lola_peer PRIVATE ${CMAKE_SOURCE_DIR})
target_link_libraries(sim_lola_peer PRIVATE nao_sim nao_controllers ${NAO_MSGPACK_TARGET} nlohmann_json::nlohmann_json)
target_compile_definitions(sim_lola_peer PRIVATE MSGPACK_NO_BOOST)
nao_warnings(sim_lola_peer)

# run --backend nao with the full cognition: lola_peer's soak with --cameras files:DIR, frames
# rendered by `nao-soccer render` in the test, every answer judged; alone, as lola_peer_test.
add_executable(nao_cognition_test nao_cognition_test.cpp)
target_link_libraries(nao_cognition_test PRIVATE nao_perception nlohmann_json::nlohmann_json GTest::gtest GTest::gtest_main)
target_include_directories(nao_cognition_test PRIVATE ${CMAKE_SOURCE_DIR})
target_compile_definitions(nao_cognition_test PRIVATE NAO_BINARY="$<TARGET_FILE:nao-soccer>"
                                                       LOLA_PEER="$<TARGET_FILE:lola_peer>"
                                                       SIM_LOLA_PEER="$<TARGET_FILE:sim_lola_peer>"
                                                       NAO_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
add_dependencies(nao_cognition_test nao-soccer lola_peer sim_lola_peer)
nao_warnings(nao_cognition_test)
gtest_discover_tests(nao_cognition_test DISCOVERY_TIMEOUT 60
                     PROPERTIES RUN_SERIAL TRUE TIMEOUT 300 LABELS "nao;${NAO_FRAGMENT_LABELS}")

nao_add_test(lola_test SOURCES lola_test.cpp LIBS nao_robot ${NAO_MSGPACK_TARGET} LABELS nao)
target_compile_definitions(lola_test PRIVATE MSGPACK_NO_BOOST)

nao_add_test(gamecontroller_test SOURCES gamecontroller_test.cpp LIBS nao_robot LABELS nao)
nao_add_test(v4l2_test SOURCES v4l2_test.cpp LIBS nao_robot LABELS nao)
nao_add_test(file_camera_test SOURCES file_camera_test.cpp LIBS nao_robot LABELS nao TIMEOUT 60)
nao_add_test(socket_camera_test SOURCES socket_camera_test.cpp LIBS nao_robot LABELS nao TIMEOUT 60)

# deploy_test (robot/deploy/deploy.sh --dry-run) is in tests/robot_bundle.cmake, with the robot bundle's tests.

# libFuzzer targets for the parsers that read bytes from the network and for the command line
# (.ci/fuzz.sh builds and runs them in build-fuzz with clang). The parsers are compiled into each target with
# coverage instrumentation.
option(NAO_FUZZ "Build the libFuzzer targets (needs clang)" OFF)
if(NAO_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "NAO_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++ (.ci/fuzz.sh)")
  endif()
  set(_fuzz_flags -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  function(nao_fuzz_target name)
    add_executable(${name} ${ARGN})
    target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR})
    target_compile_options(${name} PRIVATE ${_fuzz_flags} -g -Wall -Wextra)
    target_link_options(${name} PRIVATE ${_fuzz_flags})
    target_compile_definitions(${name} PRIVATE MSGPACK_NO_BOOST)
    target_link_libraries(${name} PRIVATE Eigen3::Eigen ${NAO_MSGPACK_TARGET})
  endfunction()
  nao_fuzz_target(lola_fuzz fuzz/lola_fuzz.cpp ${CMAKE_SOURCE_DIR}/robot/nao/LolaPacket.cpp)
  nao_fuzz_target(gamecontroller_fuzz fuzz/gamecontroller_fuzz.cpp ${CMAKE_SOURCE_DIR}/robot/nao/GameController.cpp)
  # The declared command line (apps/cli/): argv words from the fuzzer, parsed, never run.
  nao_fuzz_target(argv_fuzz fuzz/argv_fuzz.cpp ${CMAKE_SOURCE_DIR}/apps/cli/CommandLine.cpp
                  ${CMAKE_SOURCE_DIR}/apps/cli/Declarations.cpp ${CMAKE_SOURCE_DIR}/robot/OutputFiles.cpp
                  ${CMAKE_SOURCE_DIR}/robot/Debug.cpp)
  find_package(CLI11 REQUIRED CONFIG)
  target_link_libraries(argv_fuzz PRIVATE CLI11::CLI11 nlohmann_json::nlohmann_json)
  target_compile_definitions(argv_fuzz PRIVATE NAO_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  nao_fuzz_target(calibration_log_fuzz fuzz/calibration_log_fuzz.cpp ${CMAKE_SOURCE_DIR}/perception/calibration/CalibrationLog.cpp)
  target_link_libraries(calibration_log_fuzz PRIVATE nlohmann_json::nlohmann_json)
  nao_fuzz_target(camera_matrix_fuzz fuzz/camera_matrix_fuzz.cpp ${CMAKE_SOURCE_DIR}/perception/RecordedCameraMatrix.cpp
                  ${CMAKE_SOURCE_DIR}/robot/InputFiles.cpp)
  target_link_libraries(camera_matrix_fuzz PRIVATE nlohmann_json::nlohmann_json)
  # The venues (config/venues.json, every --venue).
  nao_fuzz_target(venues_fuzz fuzz/venues_fuzz.cpp ${CMAKE_SOURCE_DIR}/sim/VenueLook.cpp ${CMAKE_SOURCE_DIR}/robot/Parameters.cpp)
  target_link_libraries(venues_fuzz PRIVATE nlohmann_json::nlohmann_json)
  # Seed inputs (a valid packet of each kind and a few damaged ones), written at run time.
  add_executable(fuzz_seeds fuzz/fuzz_seeds.cpp ${CMAKE_SOURCE_DIR}/robot/nao/GameController.cpp
                 ${CMAKE_SOURCE_DIR}/perception/calibration/CalibrationLog.cpp)
  target_include_directories(fuzz_seeds PRIVATE ${CMAKE_SOURCE_DIR})
  target_compile_definitions(fuzz_seeds PRIVATE MSGPACK_NO_BOOST)
  target_link_libraries(fuzz_seeds PRIVATE Eigen3::Eigen ${NAO_MSGPACK_TARGET} nlohmann_json::nlohmann_json)
endif()
