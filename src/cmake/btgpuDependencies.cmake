# btgpuDependencies.cmake — finds OpenCL and the single-precision Bullet, for the build and for
# find_package(btgpu). Debian's BulletConfig.cmake has relative paths and no targets, so
# Bullet comes through pkg-config ("bullet", the float build; "bullet-float64" is the double).
find_package(OpenCL REQUIRED)
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
if(NOT TARGET btgpu_bullet)
  pkg_check_modules(BTGPU_BULLET REQUIRED IMPORTED_TARGET GLOBAL bullet)
  add_library(btgpu_bullet INTERFACE IMPORTED GLOBAL)
  target_link_libraries(btgpu_bullet INTERFACE PkgConfig::BTGPU_BULLET)
endif()
