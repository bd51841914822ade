# Scene assembly and camera rendering (sim/SceneBuilder, CameraRenderer, Lighting, ImageIO, FieldView).
nao_add_test(scene_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/scene_test.cpp LIBS nao_sim opencv_imgcodecs)
nao_add_test(render_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/render_test.cpp LIBS nao_sim opencv_imgcodecs)
nao_add_test(image_decoder_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/image_decoder_test.cpp LIBS nao_sim opencv_imgcodecs)
# --gl: EGL (Mesa's software device here) against OSMesa, through the command line's processes.
nao_add_test(gl_context_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/gl_context_test.cpp LIBS nao_sim)
add_dependencies(gl_context_test nao-soccer)
nao_add_test(camera_sensor_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/camera_sensor_test.cpp LIBS nao_sim)
nao_add_test(venue_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/venue_test.cpp LIBS nao_scenarios)
nao_add_test(exposure_weighting_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/exposure_weighting_test.cpp LIBS nao_scenarios)
