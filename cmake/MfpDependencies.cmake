# Imported targets for dependencies whose Debian packages ship no usable CMake config.

# Ipopt 3.11 (coinor-libipopt-dev): pkg-config only.
pkg_check_modules(IPOPT REQUIRED IMPORTED_TARGET ipopt)

# NLopt (libnlopt-dev): pkg-config.
pkg_check_modules(NLOPT REQUIRED IMPORTED_TARGET nlopt)

# urdfdom (liburdfdom-dev).
pkg_check_modules(URDFDOM REQUIRED IMPORTED_TARGET urdfdom)

# OctoMap (liboctomap-dev) ships a CMake config.
find_package(octomap REQUIRED)
if(NOT TARGET mfp_octomap)
  add_library(mfp_octomap INTERFACE)
  target_include_directories(mfp_octomap SYSTEM INTERFACE ${OCTOMAP_INCLUDE_DIRS})
  target_link_libraries(mfp_octomap INTERFACE ${OCTOMAP_LIBRARIES})
endif()

# LCM 1.3.1 ships no CMake config and its pkg-config file wants glib's development
# files; find the header, library and code generator directly.
find_path(LCM_INCLUDE_DIR lcm/lcm-cpp.hpp REQUIRED)
find_library(LCM_LIBRARY lcm REQUIRED)
find_program(LCM_GEN_EXECUTABLE lcm-gen REQUIRED)
if(NOT TARGET mfp_lcm_lib)
  add_library(mfp_lcm_lib INTERFACE)
  target_include_directories(mfp_lcm_lib SYSTEM INTERFACE ${LCM_INCLUDE_DIR})
  target_link_libraries(mfp_lcm_lib INTERFACE ${LCM_LIBRARY})
endif()
