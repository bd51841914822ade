# The MJCF model of the NAO V6 (models/nao_v6.xml) against nao-v6.md.
nao_add_test(model_test SOURCES model_test.cpp LIBS mujoco::mujoco nao_robot)
