# -Wall -Wextra everywhere; NAO_WERROR turns warnings into errors (CI sets it). Every target of
# ours calls nao_warnings, which also gives it the precompiled headers (PrecompiledHeaders.cmake).
option(NAO_WERROR "Treat warnings as errors" OFF)
# GCC builds the Release tree, clang the sanitizer tree (.ci/run): each gets its own shadowing check.
set(NAO_WARNING_OPTIONS -Wall -Wextra -Wpedantic
    $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local> $<$<CXX_COMPILER_ID:Clang>:-Wshadow-uncaptured-local>)
function(nao_warnings target)
  target_compile_options(${target} PRIVATE ${NAO_WARNING_OPTIONS})
  if(NAO_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  nao_use_pch(${target})
endfunction()

# A library of all .cpp files below the calling folder (an empty one still configures).
function(nao_library name)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(NOT sources)
    set(sources ${CMAKE_CURRENT_BINARY_DIR}/${name}_empty.cpp)
    file(WRITE ${sources} "// ${name} has no sources yet\n")
  endif()
  add_library(${name} STATIC ${sources})
  nao_warnings(${name})
endfunction()
