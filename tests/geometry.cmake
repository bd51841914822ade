# Geometry of the robot program: NAO forward kinematics, the field model, the camera model.
nao_add_test(kinematics_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/kinematics_test.cpp LIBS nao_perception)
nao_add_test(field_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/field_test.cpp LIBS nao_perception)
nao_add_test(camera_model_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/camera_model_test.cpp LIBS nao_perception)
