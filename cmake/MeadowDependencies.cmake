# Every dependency is a Debian 12 package; meadow.sh installs them (see README).
find_package(PkgConfig REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs ximgproc)
find_package(glm REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(CLI11 REQUIRED)
find_package(TinyGLTF REQUIRED)
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)

# PCL through pkg-config: find_package(PCL) drags in VTK, which meadow does not use.
pkg_check_modules(PCL REQUIRED IMPORTED_TARGET
  pcl_common pcl_sample_consensus pcl_segmentation pcl_filters pcl_features pcl_search pcl_kdtree
  pcl_io pcl_registration)
find_package(Eigen3 REQUIRED NO_MODULE)

# OpenNI2: Debian's libopenni2.pc names a libdir that does not hold the library, so link the
# multiarch libOpenNI2.so directly.
find_path(OPENNI2_INCLUDE_DIR OpenNI.h PATH_SUFFIXES openni2 REQUIRED)
find_library(OPENNI2_LIBRARY NAMES OpenNI2 PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE} REQUIRED)
add_library(meadow_openni2 INTERFACE)
target_include_directories(meadow_openni2 SYSTEM INTERFACE ${OPENNI2_INCLUDE_DIR})
target_link_libraries(meadow_openni2 INTERFACE ${OPENNI2_LIBRARY})

if(MEADOW_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(MEADOW_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
