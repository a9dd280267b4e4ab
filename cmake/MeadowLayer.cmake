# meadow_add_layer(NAME DEPS...): one static library per layer from <layer>/src/*.cpp, public
# headers in <layer>/include. Sources are globbed so each stage can live in its own small file.
function(meadow_add_layer name)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(meadow_${name} STATIC ${sources})
  add_library(meadow::${name} ALIAS meadow_${name})
  target_include_directories(meadow_${name}
    PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(meadow_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  # The layer's private headers, for its own unit tests and benches only (tests of one stage
  # include "segmentation/stages.h"); no other layer links this.
  add_library(meadow_${name}_internals INTERFACE)
  add_library(meadow::${name}_internals ALIAS meadow_${name}_internals)
  target_include_directories(meadow_${name}_internals INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(meadow_${name}_internals INTERFACE meadow_${name})
endfunction()

# meadow_add_test_suite(NAME DIR LIBS...): one GoogleTest program from tests/<dir>/*.cpp.
function(meadow_add_test_suite name dir)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*.cpp)
  if(NOT sources)
    return()
  endif()
  add_executable(${name} ${sources})
  target_include_directories(${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${name} PRIVATE ${ARGN} GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    MEADOW_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    MEADOW_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data"
    MEADOW_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
    PROPERTIES ENVIRONMENT "XDG_RUNTIME_DIR=/tmp;EGL_PLATFORM=surfaceless")
endfunction()
