# The vision as modules (issue 18): each module of the camera pipeline alone through the
# harness on synthetic images with exact truth, and the camera pipeline itself (same percepts
# as the hand-ordered vision it replaced, order, provider swap, timing, configuration).
nao_add_test(vision_modules_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/vision/vision_modules_test.cpp
             LIBS nao_perception nao_sim nao_controllers TIMEOUT 300)
nao_add_test(camera_pipeline_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/vision/camera_pipeline_test.cpp
             LIBS nao_perception nao_sim nao_controllers TIMEOUT 600)
# The robot's own body (perception/OwnBody.h) against the simulator's rays, and balls beside it.
nao_add_test(own_body_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/vision/own_body_test.cpp
             LIBS nao_perception nao_sim nao_controllers TIMEOUT 300)
# The image's noise and the blur of a noisy image (perception/vision/Denoise.h, ImageDenoiser).
nao_add_test(denoise_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/vision/denoise_test.cpp
             LIBS nao_perception nao_sim nao_controllers TIMEOUT 300)
