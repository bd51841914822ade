# The second half of the vision (issue 3): lines, circle, intersections, penalty mark, goal
# box side, ball, the pipeline, its evaluation against simulator truth, and real images.
nao_add_test(lines_test SOURCES lines_test.cpp LIBS nao_perception nao_sim nao_controllers)
nao_add_test(ball_test SOURCES ball_test.cpp LIBS nao_scenarios)
nao_add_test(ball_classifier_test SOURCES ball_classifier_test.cpp LIBS nao_scenarios TIMEOUT 300)
nao_add_test(perception_eval_test SOURCES perception_eval_test.cpp LIBS nao_scenarios)
nao_add_test(real_images_test SOURCES real_images_test.cpp support/RealImages.cpp
             LIBS nao_perception nao_sim nao_controllers opencv_imgcodecs TIMEOUT 300)
nao_add_test(real_images_ball_test SOURCES real_images_ball_test.cpp support/RealImages.cpp
             LIBS nao_perception nao_sim nao_controllers opencv_imgcodecs TIMEOUT 300)
