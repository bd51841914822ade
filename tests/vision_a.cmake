# Vision, first half (perception/vision: ScanGrid, Yhs, ScanLineRegionizer, FieldBoundaryDetector,
# ObstacleDetector): synthetic and real images (nao_perception only), simulated images (nao_sim).
nao_add_test(scan_regions_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/scan_regions_test.cpp LIBS nao_perception)
nao_add_test(field_boundary_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/field_boundary_test.cpp LIBS nao_sim nao_controllers)
