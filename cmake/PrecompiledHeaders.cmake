# Precompiled headers: the standard, Eigen, nlohmann::json (and for tests GoogleTest) headers that
# most of our files include, parsed once per build tree instead of once per file. Measured on
# tests/walk_test.cpp: 14.5 s to compile without, 8.7 s with (docs/ci.md).
#
# Two carrier targets compile them (nao_pch; nao_pch_test adds gtest.h); every target of ours
# reuses one (nao_use_pch, called by nao_warnings). The carriers get no compile definitions of
# ours: GCC refuses a PCH built with a macro its user does not define, while a user may define
# more. -Winvalid-pch (an error under NAO_WERROR) says when a file could not use it.
option(NAO_PCH "Precompile the common headers" ON)

set(NAO_PCH_HEADERS <algorithm> <array> <chrono> <cmath> <cstdint> <cstdio> <filesystem> <fstream> <functional>
    <map> <memory> <optional> <random> <sstream> <string> <vector> <Eigen/Core> <Eigen/Geometry> <nlohmann/json.hpp>)

function(nao_pch_carrier name)
  set(source ${CMAKE_BINARY_DIR}/${name}.cpp)
  file(WRITE ${source} "// carries the precompiled headers (cmake/PrecompiledHeaders.cmake)\n")
  add_library(${name} OBJECT ${source})
  target_link_libraries(${name} PRIVATE Eigen3::Eigen nlohmann_json::nlohmann_json ${ARGN})
  # The same warning options as nao_warnings: -Wpedantic changes the predefined macros.
  target_compile_options(${name} PRIVATE ${NAO_WARNING_OPTIONS} -Winvalid-pch)
  target_precompile_headers(${name} PRIVATE ${NAO_PCH_HEADERS} $<$<BOOL:${ARGN}>:<gtest/gtest.h$<ANGLE-R>>)
endfunction()

if(NAO_PCH)
  nao_pch_carrier(nao_pch)
  nao_pch_carrier(nao_pch_test GTest::gtest)
endif()

# `target` compiles with the shared precompiled headers: the test set when it links GoogleTest.
function(nao_use_pch target)
  if(NOT NAO_PCH)
    return()
  endif()
  # A target built for another CPU (-march: the robot executables) cannot use a PCH built for this one.
  get_target_property(options ${target} COMPILE_OPTIONS)
  if(options MATCHES "-march=")
    return()
  endif()
  get_target_property(libs ${target} LINK_LIBRARIES)
  set(carrier nao_pch)
  if(libs MATCHES "GTest::")
    set(carrier nao_pch_test)
  endif()
  target_precompile_headers(${target} REUSE_FROM ${carrier})
  # Include paths for the headers, so that a file still compiles should it not use the PCH.
  target_include_directories(${target} SYSTEM PRIVATE $<TARGET_PROPERTY:Eigen3::Eigen,INTERFACE_INCLUDE_DIRECTORIES>)
  target_compile_options(${target} PRIVATE -Winvalid-pch)
endfunction()
