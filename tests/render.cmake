# Scene assembly and camera rendering (sim/SceneBuilder, CameraRenderer, Lighting, ImageIO, FieldView).
nao_add_test(scene_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/scene_test.cpp LIBS nao_sim)
nao_add_test(render_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/render_test.cpp LIBS nao_sim)
nao_add_test(image_decoder_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/image_decoder_test.cpp LIBS nao_sim)
